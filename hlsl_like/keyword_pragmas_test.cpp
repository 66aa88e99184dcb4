#include "hlsl_like/keyword_pragmas.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hlsl_like/compiler.h"
#include "hlsl_like/reflection.h"

namespace xshade::hlsl {
namespace {

using Strings = std::vector<std::string>;

std::unique_ptr<Module> compile_with_pragmas(const std::string& pragmas, Strings keywords = {}) {
  CompileOptions options;
  options.keywords = std::move(keywords);
  return compile_text(
      "k.hlsl", pragmas + "#pragma fragment frag\nfloat4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n",
      options);
}

Strings messages(const Module& module) {
  Strings out;
  for (size_t i = 0; i < module.diagnostics.diagnostics().size(); ++i) out.push_back(module.diagnostics.render(i));
  return out;
}

TEST(KeywordPragmas, ScopeSuffixesDeclareTheSetsThePlainFormsDo) {
  EXPECT_EQ(keyword_pragma("multi_compile_local"), KeywordPragma::MultiCompile);
  EXPECT_EQ(keyword_pragma("multi_compile_fragment"), KeywordPragma::MultiCompile);
  EXPECT_EQ(keyword_pragma("shader_feature_local_fragment"), KeywordPragma::ShaderFeature);
  EXPECT_EQ(keyword_pragma("shader_feature"), KeywordPragma::ShaderFeature);
  EXPECT_FALSE(keyword_pragma("multi_compile_fwdbase"));  // a shortcut, not a list on the line
  EXPECT_FALSE(keyword_pragma("shader_feature_locale"));

  auto module =
      compile_with_pragmas("#pragma multi_compile_local _ A B\n#pragma shader_feature_local_fragment C\n", {"B"});
  EXPECT_TRUE(messages(*module).empty()) << messages(*module)[0];
  ASSERT_EQ(module->reflection.keyword_sets.size(), 2u);
  EXPECT_EQ(module->reflection.keyword_sets[0].keywords, (Strings{"_", "A", "B"}));
  EXPECT_EQ(module->reflection.keyword_sets[1].keywords, (Strings{"_", "C"}));
  EXPECT_TRUE(module->reflection.keyword_sets[1].shader_feature);
  EXPECT_EQ(module->reflection.active_keywords, (Strings{"B"}));
}

// A ForwardBase pass with one directional light and the environment's harmonics: DIRECTIONAL and
// LIGHTPROBE_SH on, every lightmap, shadow and fog keyword off, unless the scene asks.
TEST(KeywordPragmas, ShortcutsDeclareUnitysListsWithTheVariantTheRendererDrawsFirst) {
  auto module = compile_with_pragmas("#pragma multi_compile_fwdbase\n#pragma multi_compile_fog\n");
  EXPECT_TRUE(messages(*module).empty()) << messages(*module)[0];
  EXPECT_EQ(module->reflection.active_keywords, (Strings{"DIRECTIONAL", "LIGHTPROBE_SH"}));
  Strings declared;
  for (const KeywordSet& set : module->reflection.keyword_sets)
    for (const std::string& keyword : set.keywords)
      if (keyword != "_") declared.push_back(keyword);
  EXPECT_EQ(declared, (Strings{"DIRECTIONAL", "LIGHTPROBE_SH", "LIGHTMAP_ON", "DIRLIGHTMAP_COMBINED",
                               "DYNAMICLIGHTMAP_ON", "SHADOWS_SCREEN", "SHADOWS_SHADOWMASK", "LIGHTMAP_SHADOW_MIXING",
                               "FOG_LINEAR", "FOG_EXP", "FOG_EXP2"}));

  auto fogged = compile_with_pragmas("#pragma multi_compile_fwdbase\n#pragma multi_compile_fog\n", {"FOG_EXP2"});
  EXPECT_EQ(fogged->reflection.active_keywords, (Strings{"FOG_EXP2", "DIRECTIONAL", "LIGHTPROBE_SH"}));

  // Unity adds no variant without a keyword here: a shadow caster is for a directional or spot
  // light's depth, or a point light's cube.
  auto caster = compile_with_pragmas("#pragma multi_compile_shadowcaster\n");
  EXPECT_EQ(caster->reflection.active_keywords, (Strings{"SHADOWS_DEPTH"}));
  EXPECT_FALSE(keyword_shortcut("multi_compile_fwdbsae"));
}

TEST(KeywordPragmas, SkippedKeywordsAreNoChoiceOfTheirSet) {
  auto module = compile_with_pragmas("#pragma multi_compile_fog\n#pragma skip_variants FOG_EXP FOG_EXP2\n");
  ASSERT_EQ(module->reflection.keyword_sets.size(), 1u);
  EXPECT_EQ(module->reflection.keyword_sets[0].keywords, (Strings{"_", "FOG_LINEAR"}));
}

TEST(KeywordPragmas, UnitysBuildPragmasAreReadQuietlyAndOtherStagesAreErrors) {
  EXPECT_TRUE(messages(*compile_with_pragmas(
                           "#pragma target 3.0\n#pragma only_renderers d3d11 glcore\n#pragma require derivatives\n"))
                  .empty());
  // fxc's own warning switches, as HLSLSupport.cginc sets them.
  EXPECT_TRUE(messages(*compile_with_pragmas("#pragma warning (disable : 3205)\n")).empty());
  const Strings misspelt = messages(*compile_with_pragmas("#pragma multi_compile_fwdbsae\n"));
  ASSERT_EQ(misspelt.size(), 1u);
  EXPECT_TRUE(misspelt[0].starts_with("k.hlsl:1:9: warning: unknown pragma 'multi_compile_fwdbsae'")) << misspelt[0];
  const Strings geometry = messages(*compile_with_pragmas("#pragma geometry geom\n"));
  ASSERT_FALSE(geometry.empty());
  EXPECT_NE(geometry[0].find("k.hlsl:1:9: error: xshade compiles vertex and fragment stages; a geometry stage"),
            std::string::npos)
      << geometry[0];
  const Strings surface = messages(*compile_with_pragmas("#pragma surface surf Lambert\n"));
  ASSERT_FALSE(surface.empty());
  EXPECT_NE(surface[0].find("error: #pragma surface makes a surface shader"), std::string::npos) << surface[0];
}

TEST(KeywordCombinations, AreCountedAndListedOneAtATimeFirstSetSlowest) {
  const std::vector<KeywordSet> sets = {{{"_", "A"}}, {{"B", "C", "D"}}, {{}}};
  EXPECT_EQ(keyword_combination_count(sets), 6u);
  EXPECT_EQ(keyword_combination(sets, 0), Strings{"B"});
  EXPECT_EQ(keyword_combination(sets, 2), Strings{"D"});
  EXPECT_EQ(keyword_combination(sets, 4), (Strings{"A", "C"}));
  EXPECT_EQ(keyword_combination_count(std::vector<KeywordSet>(63, KeywordSet{{"_", "K"}})), uint64_t(1) << 63);
  EXPECT_EQ(keyword_combination_count(std::vector<KeywordSet>(70, KeywordSet{{"_", "K"}})), UINT64_MAX);
}

}  // namespace
}  // namespace xshade::hlsl
