#include "hlsl_like/keyword_pragmas.h"

#include <initializer_list>
#include <string>

namespace xshade::hlsl {
namespace {

// The scope suffixes Unity allows after multi_compile and shader_feature: where the keyword
// applies (a material's or global) and which stage's variants it makes. Neither changes which
// variants a scene draws with.
constexpr std::string_view kScopeSuffixes[] = {"",
                                               "_local",
                                               "_vertex",
                                               "_fragment",
                                               "_hull",
                                               "_domain",
                                               "_geometry",
                                               "_raytracing",
                                               "_local_vertex",
                                               "_local_fragment",
                                               "_local_hull",
                                               "_local_domain",
                                               "_local_geometry",
                                               "_local_raytracing"};

std::vector<KeywordSet> sets(std::initializer_list<std::initializer_list<const char*>> lists) {
  std::vector<KeywordSet> out;
  for (const auto& list : lists) {
    KeywordSet set;
    for (const char* keyword : list) set.keywords.emplace_back(keyword);
    out.push_back(std::move(set));
  }
  return out;
}

// The light types of an additive pass (a directional light is the only kind a scene has) and
// the shadow keywords of a light's pass.
constexpr std::initializer_list<const char*> kLightTypes = {"DIRECTIONAL", "POINT", "SPOT", "POINT_COOKIE",
                                                            "DIRECTIONAL_COOKIE"};
constexpr std::initializer_list<const char*> kShadowTypes = {"_", "SHADOWS_DEPTH", "SHADOWS_SCREEN", "SHADOWS_CUBE"};

}  // namespace

std::optional<KeywordPragma> keyword_pragma(std::string_view name) {
  for (const auto& [base, kind] : {std::pair{std::string_view("multi_compile"), KeywordPragma::MultiCompile},
                                   std::pair{std::string_view("shader_feature"), KeywordPragma::ShaderFeature}}) {
    if (!name.starts_with(base)) continue;
    for (std::string_view suffix : kScopeSuffixes)
      if (name.substr(base.size()) == suffix) return kind;
  }
  return std::nullopt;
}

std::optional<std::vector<KeywordSet>> keyword_shortcut(std::string_view name) {
  // The lists of Unity's manual ("Shader directive shortcuts"). Where Unity adds no variant with
  // every keyword off, a set has no `_`; LIGHTPROBE_SH comes first in its set because the scene's
  // environment lights an object through its spherical harmonics, as a light probe does.
  if (name == "multi_compile_fwdbase")
    return sets({{"DIRECTIONAL"},
                 {"LIGHTPROBE_SH", "_"},
                 {"_", "LIGHTMAP_ON"},
                 {"_", "DIRLIGHTMAP_COMBINED"},
                 {"_", "DYNAMICLIGHTMAP_ON"},
                 {"_", "SHADOWS_SCREEN"},
                 {"_", "SHADOWS_SHADOWMASK"},
                 {"_", "LIGHTMAP_SHADOW_MIXING"}});
  if (name == "multi_compile_fwdbasealpha")
    return sets({{"DIRECTIONAL"},
                 {"LIGHTPROBE_SH", "_"},
                 {"_", "LIGHTMAP_ON"},
                 {"_", "DIRLIGHTMAP_COMBINED"},
                 {"_", "DYNAMICLIGHTMAP_ON"},
                 {"_", "LIGHTMAP_SHADOW_MIXING"},
                 {"_", "VERTEXLIGHT_ON"}});
  if (name == "multi_compile_fwdadd") return sets({kLightTypes});
  if (name == "multi_compile_fwdadd_fullshadows" || name == "multi_compile_lightpass")
    return sets({kLightTypes,
                 kShadowTypes,
                 {"_", "SHADOWS_SOFT"},
                 {"_", "SHADOWS_SHADOWMASK"},
                 {"_", "LIGHTMAP_SHADOW_MIXING"}});
  if (name == "multi_compile_shadowcaster") return sets({{"SHADOWS_DEPTH", "SHADOWS_CUBE"}});
  if (name == "multi_compile_shadowcollector")
    return sets({{"_", "SHADOWS_SPLIT_SPHERES"}, {"_", "SHADOWS_SINGLE_CASCADE"}});
  if (name == "multi_compile_prepassfinal")
    return sets({{"LIGHTPROBE_SH", "_"},
                 {"_", "LIGHTMAP_ON"},
                 {"_", "DIRLIGHTMAP_COMBINED"},
                 {"_", "DYNAMICLIGHTMAP_ON"},
                 {"_", "UNITY_HDR_ON"},
                 {"_", "SHADOWS_SHADOWMASK"}});
  if (name == "multi_compile_fog") return sets({{"_", "FOG_LINEAR", "FOG_EXP", "FOG_EXP2"}});
  if (name == "multi_compile_instancing") return sets({{"_", "INSTANCING_ON"}});
  if (name == "multi_compile_particles") return sets({{"_", "SOFTPARTICLES_ON"}});
  return std::nullopt;
}

}  // namespace xshade::hlsl
