#include "harness/render/planner.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const fs::path kLibrary = fs::path(XSHADE_SOURCE_DIR) / "shaders";

constexpr const char* kCameraAndSize = R"(
description = "planner test"
size = [64, 64]
[camera]
position = [0, 0, 5]
target = [0, 0, 0]
fov_y = 40
near = 0.3
far = 100
)";

// Each instance's first draw's variant (an .hlsl material draws once).
std::vector<size_t> first_variants(const Plan& plan) {
  std::vector<size_t> variants;
  for (const auto& draws : plan.instance_draws) variants.push_back(draws.front().variant);
  return variants;
}

Scene scene(const std::string& body) {
  auto parsed = parse_scene(std::string(kCameraAndSize) + body, "/tmp/planner_test.toml");
  EXPECT_TRUE(parsed) << parsed.error().to_string();
  return *parsed;
}

bool has_line(const std::vector<std::string>& lines, const std::string& line) {
  return std::find(lines.begin(), lines.end(), line) != lines.end();
}

TEST(Planner, AGridOfOneMaterialIsOneVariantAndOnePass) {
  auto plan = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/standard_pbr.hlsl"
[object.grid]
rows = 5
cols = 5
spacing = 2.2
[object.grid.vary]
_Metallic = { along = "cols", from = 0.0, to = 1.0 }
)"),
                         kLibrary);
  ASSERT_TRUE(plan) << plan.error().to_string();
  ASSERT_EQ(plan->variants.size(), 1u);
  // No keyword asked for: each multi_compile set's first keyword, as the front end defines them.
  EXPECT_EQ(plan->variants[0].keywords, (std::vector<std::string>{"_D_GGX_SEED", "_F_SCHLICK", "_G_COOK_TORRANCE"}));
  EXPECT_EQ(plan->instances.size(), 25u);
  EXPECT_EQ(first_variants(*plan), std::vector<size_t>(25, 0));
  ASSERT_EQ(plan->passes.size(), 1u);
  EXPECT_EQ(plan->passes[0].kind, PlannedPass::Kind::Scene);
  // 2 D forms x 3 G forms x 3 F forms x guards on/off.
  EXPECT_TRUE(has_line(plan->left_out,
                       "materials/standard_pbr.hlsl: 71 of its 72 keyword combinations (the scene asks for no other)"));
  EXPECT_TRUE(has_line(plan->left_out, "materials/toon.hlsl: no object uses it"));
  EXPECT_TRUE(has_line(plan->left_out,
                       "post/depth_of_field.hlsl: not in the post chain, so none of its passes is compiled or run"));
}

TEST(Planner, NamingADefaultKeywordGivesTheSameVariant) {
  auto plan = plan_scene(scene(R"(
[[object]]
name = "a"
mesh = "sphere"
material = "materials/toon.hlsl"
[[object]]
name = "b"
mesh = "cube"
material = "materials/toon.hlsl"
keywords = ["_GUARDED"]
[[object]]
name = "c"
mesh = "torus"
material = "materials/toon.hlsl"
keywords = ["_GUARDED", "_GUARDED"]
)"),
                         kLibrary);
  ASSERT_TRUE(plan) << plan.error().to_string();
  ASSERT_EQ(plan->variants.size(), 2u);
  EXPECT_EQ(first_variants(*plan), (std::vector<size_t>{0, 1, 1}));
  EXPECT_TRUE(plan->variants[0].keywords.empty());
  EXPECT_EQ(plan->variants[1].keywords, std::vector<std::string>{"_GUARDED"});
}

TEST(Planner, APostEffectAddsItsPassesInOrderWithTheirSources) {
  auto plan = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
[[post]]
effect = "post/depth_of_field.hlsl"
keywords = ["_KERNEL_MEDIUM"]
)"),
                         kLibrary);
  ASSERT_TRUE(plan) << plan.error().to_string();
  std::vector<std::string> names;
  for (const PlannedPass& pass : plan->passes) names.push_back(pass.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"scene", "depth_of_field.coc", "depth_of_field.prefilter", "depth_of_field.bokeh",
                                      "depth_of_field.postfilter", "depth_of_field.combine"}));
  ASSERT_EQ(plan->variants.size(), 6u);
  EXPECT_EQ(plan->variants[plan->passes[3].variant].fragment_entry, "frag_bokeh");
  EXPECT_EQ(plan->variants[plan->passes[3].variant].keywords, std::vector<std::string>{"_KERNEL_MEDIUM"});
  const hlsl::PassDeclaration& combine = plan->passes[5].declaration;
  EXPECT_EQ(combine.scale, hlsl::PassDeclaration::Scale::Full);
  ASSERT_EQ(combine.inputs.size(), 3u);
  EXPECT_EQ(combine.inputs[2].texture, "_DoFTex");
  EXPECT_EQ(combine.inputs[2].pass, "postfilter");
  EXPECT_EQ(plan->passes[2].declaration.scale, hlsl::PassDeclaration::Scale::Half);
  // 4 kernels x guards on/off.
  EXPECT_TRUE(has_line(plan->left_out,
                       "post/depth_of_field.hlsl: 9 of its 10 keyword combinations (the scene asks for no other)"));
  // The effect is in the chain, so it is not left out as one that is not.
  for (const std::string& line : plan->left_out)
    EXPECT_EQ(line.find("not in the post chain"), std::string::npos) << line;
  const std::string described = describe_plan(scene(""), *plan, std::vector<bool>(6, false));
  EXPECT_NE(described.find("depth_of_field.bokeh: frag_bokeh, half resolution, _MainTex <- prefilter"),
            std::string::npos)
      << described;
}

TEST(Planner, AToonOnlySceneCompilesNoPbrVariant) {
  auto plan = plan_scene(scene(R"(
[[object]]
mesh = "torus"
material = "materials/toon.hlsl"
)"),
                         kLibrary);
  ASSERT_TRUE(plan) << plan.error().to_string();
  ASSERT_EQ(plan->variants.size(), 1u);
  for (const VariantRequest& variant : plan->variants) EXPECT_EQ(variant.library_path, "materials/toon.hlsl");
  EXPECT_TRUE(has_line(plan->left_out, "materials/standard_pbr.hlsl: no object uses it"));
}

TEST(Planner, ASourceOutsideTheLibraryOrBrokenIsAnError) {
  auto missing = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/velvet.hlsl"
)"),
                            kLibrary);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "'materials/velvet.hlsl' is in none of the shader folders (" + kLibrary.string() + ")");

  const fs::path root = fs::temp_directory_path() / "xshade_planner_test";
  fs::create_directories(root / "materials");
  std::ofstream(root / "materials" / "broken.hlsl")
      << "#pragma fragment frag\n#include \"lit.hlsl\"\nfloat4 frag() : SV_Target { return x; }\n";
  std::ofstream(root / "materials" / "lit.hlsl") << "float lit;\n";
  std::set<fs::path> files_read;
  auto broken = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/broken.hlsl"
)"),
                           root, &files_read);
  ASSERT_FALSE(broken);
  // What a watch must see change to plan it again: the source and what it includes.
  EXPECT_EQ(files_read.size(), 2u);
  EXPECT_EQ(files_read.count(root / "materials" / "broken.hlsl"), 1u);
  EXPECT_EQ(files_read.count(root / "materials" / "lit.hlsl"), 1u);
  // A source in none of the folders: where it would be, in each folder that could hold it.
  files_read.clear();
  EXPECT_FALSE(plan_scene(scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"materials/velvet.hlsl\"\n"),
                          ShaderSearchPath(std::vector<fs::path>{root, kLibrary}), &files_read));
  EXPECT_EQ(files_read,
            (std::set<fs::path>{root / "materials" / "velvet.hlsl", kLibrary / "materials" / "velvet.hlsl"}));
  EXPECT_EQ(broken.error().message, "'materials/broken.hlsl' does not compile");
  ASSERT_FALSE(broken.error().diagnostics.empty());
  EXPECT_EQ(broken.error().diagnostics[0].where.line, 3u);
  fs::remove_all(root);
}

TEST(Planner, AUserFolderSuppliesItsOwnMaterialThatIncludesTheLibrary) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_user_folder";
  fs::remove_all(user);
  fs::create_directories(user / "materials");
  std::ofstream(user / "materials" / "flat_lit.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _HALF_LAMBERT
#include "include/scene_inputs.hlsl"
float4 _Color = float4(1, 1, 1, 1);
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target {
  return _Color * saturate(dot(normalize(input.world_normal), _LightDirection.xyz));
}
)";
  auto plan = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/flat_lit.hlsl"
)"),
                         ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(plan) << plan.error().to_string();
  ASSERT_EQ(plan->variants.size(), 1u);
  EXPECT_EQ(plan->variants[0].source, user / "materials" / "flat_lit.hlsl");
  EXPECT_TRUE(has_line(plan->left_out,
                       "materials/flat_lit.hlsl: 1 of its 2 keyword combinations (the scene asks for no other)"));
  // The library's own materials are still there to be used, and are left out here.
  EXPECT_TRUE(has_line(plan->left_out, "materials/toon.hlsl: no object uses it"));
  fs::remove_all(user);
}

// A .shader's [Toggle] and [KeywordEnum] properties choose its variant as Unity's inspector does,
// from their defaults or the object's values; a keyword the scene asks of the same set wins.
TEST(Planner, AShadersToggleAndKeywordEnumPropertiesChooseItsVariant) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_inspector_keywords";
  fs::remove_all(user);
  fs::create_directories(user);
  std::ofstream(user / "toggled.shader") << R"(Shader "Toggled" {
  Properties {
    [Toggle(_GLOW)] _Glow ("Glow", Float) = 1
    [KeywordEnum(Off, Soft, Hard)] _Rim ("Rim", Float) = 2
    [Toggle] _Unused ("Declared by no pragma", Float) = 1
    _Cull ("Cull", Float) = 1
  }
  SubShader { Pass { Cull [_Cull] HLSLPROGRAM
    #pragma vertex vert
    #pragma fragment frag
    #pragma shader_feature _GLOW
    #pragma multi_compile _RIM_OFF _RIM_SOFT _RIM_HARD
    float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
    float4 frag() : SV_Target { return 1; }
    ENDHLSL } }
})";
  const auto keywords_of = [&](const std::string& object) {
    auto plan = plan_scene(scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"toggled.shader\"\n" + object),
                           ShaderSearchPath({user, kLibrary}));
    EXPECT_TRUE(plan) << plan.error().to_string();
    return plan && plan->variants.size() == 1 ? plan->variants[0].keywords : std::vector<std::string>{"(no plan)"};
  };
  EXPECT_EQ(keywords_of(""), (std::vector<std::string>{"_GLOW", "_RIM_HARD"}));
  // A state in brackets reads the Property's default (Unity's CullMode 1: Front), or the object's value.
  const auto cull_of = [&](const std::string& object) {
    auto plan = plan_scene(scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"toggled.shader\"\n" + object),
                           ShaderSearchPath({user, kLibrary}));
    EXPECT_TRUE(plan) << plan.error().to_string();
    return plan ? plan->instance_draws.at(0).at(0).state.cull : CullMode::Off;
  };
  EXPECT_EQ(cull_of(""), CullMode::Front);
  EXPECT_EQ(cull_of("[object.properties]\n_Cull = 2\n"), CullMode::Back);
  EXPECT_EQ(keywords_of("[object.properties]\n_Glow = 0\n_Rim = 1\n"), (std::vector<std::string>{"_RIM_SOFT"}));
  EXPECT_EQ(keywords_of("keywords = [\"_RIM_OFF\"]\n"), (std::vector<std::string>{"_GLOW", "_RIM_OFF"}));
  // _Glow is the material's though no uniform holds it: a Float, one number.
  auto wrong = plan_scene(
      scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"toggled.shader\"\n[object.properties]\n_Glow = [1, 0]\n"),
      ShaderSearchPath({user, kLibrary}));
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().to_string().find(
                "'_Glow' is a property of material 'toggled.shader' with 1 number: give it 1 number"),
            std::string::npos)
      << wrong.error().to_string();
  fs::remove_all(user);
}

// A scene's fog turns its mode's keyword on in every shader with Unity's fog keywords, as Unity's
// global fog keyword does; an object that asks another of the set keeps its own, a shader without
// the set gets none, and without fog the set's first (no fog) is drawn.
TEST(Planner, TheScenesFogChoosesTheFogKeywordOfShadersThatHaveIt) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_fog";
  fs::remove_all(user);
  fs::create_directories(user / "materials");
  std::ofstream(user / "materials" / "fogged.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#pragma multi_compile_fog
float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
float4 frag() : SV_Target { return 1; }
)";
  const auto keywords_of = [&](const std::string& body) {
    auto plan = plan_scene(scene(body), ShaderSearchPath({user, kLibrary}));
    EXPECT_TRUE(plan) << plan.error().to_string();
    std::vector<std::vector<std::string>> keywords;
    if (plan)
      for (const VariantRequest& variant : plan->variants) keywords.push_back(variant.keywords);
    return keywords;
  };
  const std::string fogged = "[[object]]\nmesh = \"sphere\"\nmaterial = \"materials/fogged.hlsl\"\n";
  const std::string own = fogged + "keywords = [\"FOG_EXP\"]\n";
  const std::string unfogged = "[[object]]\nmesh = \"sphere\"\nmaterial = \"materials/toon.hlsl\"\n";
  using Keywords = std::vector<std::vector<std::string>>;
  EXPECT_EQ(keywords_of("[fog]\nmode = \"linear\"\n" + fogged + own + unfogged),
            (Keywords{{"FOG_LINEAR"}, {"FOG_EXP"}, {}}));
  EXPECT_EQ(keywords_of("[fog]\n" + fogged), (Keywords{{"FOG_EXP2"}}));
  EXPECT_EQ(keywords_of(fogged), (Keywords{{}}));
  fs::remove_all(user);
}

// A shader of 70 two-keyword sets has 2^70 combinations, past what a size_t counts: the plan
// still says what it leaves out (the count once wrapped to 0 and the line went missing).
TEST(Planner, TheCombinationsLeftOutAreSaidHoweverManyThereAre) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_many_keywords";
  fs::remove_all(user);
  fs::create_directories(user / "materials");
  std::string shader = "#pragma vertex vert\n#pragma fragment frag\n";
  for (int i = 0; i < 70; ++i) shader += "#pragma multi_compile _ KW_" + std::to_string(i) + "\n";
  shader +=
      "float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }\n"
      "float4 frag() : SV_Target { return 1; }\n";
  std::ofstream(user / "materials" / "many.hlsl") << shader;
  auto plan = plan_scene(scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"materials/many.hlsl\"\n"),
                         ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(plan) << plan.error().to_string();
  EXPECT_TRUE(has_line(plan->left_out,
                       "materials/many.hlsl: all but 1 of its 18446744073709551615 or more keyword "
                       "combinations (the scene asks for no other)"));
  fs::remove_all(user);
}

// AlphaToMask On (here by a property's default) is drawn as Off on targets of one sample, and the
// variant's notes say so, once for the two objects that draw it; a material that leaves it off
// has no such note.
TEST(Planner, AlphaToMaskOnIsNotedAsDrawnOff) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_alpha_to_mask";
  fs::remove_all(user);
  fs::create_directories(user);
  std::ofstream(user / "masked.shader") << R"(Shader "Masked" {
  Properties { _A2C ("Alpha to coverage", Float) = 1 }
  SubShader { Pass { AlphaToMask [_A2C] HLSLPROGRAM
    #pragma vertex vert
    #pragma fragment frag
    float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
    float4 frag() : SV_Target { return 1; }
    ENDHLSL } }
})";
  const std::string object = "[[object]]\nmesh = \"sphere\"\nmaterial = \"masked.shader\"\n";
  const auto notes_of = [&](const std::string& objects) {
    auto plan = plan_scene(scene(objects), ShaderSearchPath({user, kLibrary}));
    EXPECT_TRUE(plan) << plan.error().to_string();
    return plan && plan->variant_notes.size() == 1 ? plan->variant_notes[0] : std::vector<std::string>{"(no plan)"};
  };
  const auto noted = [](const std::vector<std::string>& notes) {
    return std::count_if(notes.begin(), notes.end(),
                         [](const std::string& note) { return note.starts_with("AlphaToMask On is drawn as Off"); });
  };
  EXPECT_EQ(noted(notes_of(object + object)), 1);
  EXPECT_EQ(noted(notes_of(object + "[object.properties]\n_A2C = 0\n")), 0);
  fs::remove_all(user);
}

// Unity's forward renderer: a ForwardAdd pass is drawn once for each light besides the main
// directional one, compiled with that light's keyword; a scene of one light draws none (and the
// plan says so), and one with more point lights than pixel lights gives ForwardBase the rest per
// vertex (VERTEXLIGHT_ON).
TEST(Planner, AForwardAddPassIsDrawnOnceForEachFurtherLightWithItsKeyword) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_forward_add";
  fs::remove_all(user);
  fs::create_directories(user);
  std::ofstream(user / "lit.shader") << R"(Shader "Lit" {
  SubShader {
    HLSLINCLUDE
    float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
    float4 frag() : SV_Target { return 1; }
    ENDHLSL
    Pass { Tags { "LightMode" = "ForwardBase" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma multi_compile _ VERTEXLIGHT_ON
      ENDHLSL }
    Pass { Tags { "LightMode" = "ForwardAdd" } Blend One One ZWrite Off HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma multi_compile POINT DIRECTIONAL SPOT
      ENDHLSL }
  }
})";
  const std::string object = "[[object]]\nname = \"ball\"\nmesh = \"sphere\"\nmaterial = \"lit.shader\"\n";
  const std::string sun = "[[light]]\ntype = \"directional\"\ndirection = [0, 1, 0]\n";
  const std::string lamp = "[[light]]\ntype = \"point\"\nposition = [1, 1, 1]\n";
  const std::string spot = "[[light]]\ntype = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, 1, 0]\nintensity = 2\n";

  auto one = plan_scene(scene(sun + object), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(one) << one.error().to_string();
  ASSERT_EQ(one->instance_draws[0].size(), 1u);
  EXPECT_TRUE(has_line(one->left_out,
                       "'lit.shader' pass 1 (ForwardAdd): not drawn: the scene has no light besides its main "
                       "directional one"));

  auto three = plan_scene(scene(sun + lamp + spot + object), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(three) << three.error().to_string();
  const auto& draws = three->instance_draws[0];
  ASSERT_EQ(draws.size(), 3u);
  EXPECT_FALSE(draws[0].light);
  EXPECT_EQ(draws[1].light, 2u);  // the brighter spot first
  EXPECT_EQ(draws[2].light, 1u);
  EXPECT_EQ(three->variants[draws[1].variant].keywords, (std::vector<std::string>{"SPOT"}));
  EXPECT_EQ(three->variants[draws[2].variant].keywords, (std::vector<std::string>{"POINT"}));
  EXPECT_EQ(draws[1].state.blend.enabled, true);
  const std::string described = describe_plan(scene(sun + lamp + spot + object), *three);
  EXPECT_NE(described.find("main light: light 1 (directional), in ForwardBase"), std::string::npos) << described;
  EXPECT_NE(described.find("object 'ball': lit.shader pass 1 [SPOT] for light 3 (spot)"), std::string::npos)
      << described;

  // No pixel lights: the point light lights ForwardBase per vertex, and ForwardAdd is not drawn.
  auto vertex =
      plan_scene(scene("[unity]\npixel_lights = 0\n" + sun + lamp + object), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(vertex) << vertex.error().to_string();
  ASSERT_EQ(vertex->instance_draws[0].size(), 1u);
  EXPECT_EQ(vertex->variants[vertex->instance_draws[0][0].variant].keywords,
            (std::vector<std::string>{"VERTEXLIGHT_ON"}));
  fs::remove_all(user);
}

// A shadow map only where the scene calls for one: the main light casts, a drawn pass receives
// (declares SHADOWS_SCREEN, then compiled with it) and something casts (its ShadowCaster drawn
// into the map with SHADOWS_DEPTH, not into the scene). Otherwise no caster is drawn and --plan
// says why.
TEST(Planner, AShadowMapIsDrawnOnlyWhereALightCastsAndSomethingReceivesIt) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_shadows";
  fs::remove_all(user);
  fs::create_directories(user);
  const std::string program = R"(HLSLINCLUDE
    float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
    float4 frag() : SV_Target { return 1; }
    ENDHLSL)";
  std::ofstream(user / "receiver.shader") << "Shader \"Receiver\" { SubShader { " << program << R"(
    Pass { Tags { "LightMode" = "ForwardBase" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma multi_compile _ SHADOWS_SCREEN
      ENDHLSL }
    Pass { Tags { "LightMode" = "ShadowCaster" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma multi_compile SHADOWS_CUBE SHADOWS_DEPTH
      ENDHLSL } } })";
  std::ofstream(user / "caster.shader") << "Shader \"Caster\" { SubShader { " << program << R"(
    Pass { HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      ENDHLSL }
    Pass { Tags { "LightMode" = "ShadowCaster" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      ENDHLSL } } })";
  std::ofstream(user / "unlit.shader") << "Shader \"Unlit\" { SubShader { " << program << R"(
    Pass { HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      ENDHLSL } } })";
  const auto object = [](const std::string& material) {
    return "[[object]]\nmesh = \"sphere\"\nmaterial = \"" + material + "\"\n";
  };
  const std::string sun = "[[light]]\ntype = \"directional\"\ndirection = [0, 1, 0]\n";
  const auto casters = [](const Plan& plan) {
    size_t count = 0;
    for (const auto& draws : plan.instance_draws)
      count +=
          size_t(std::count_if(draws.begin(), draws.end(), [](const Plan::InstanceDraw& draw) { return draw.caster; }));
    return count;
  };

  auto shadowed =
      plan_scene(scene(sun + "shadows = \"hard\"\n" + object("receiver.shader")), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(shadowed) << shadowed.error().to_string();
  EXPECT_EQ(shadowed->shadow_lights, (std::vector<size_t>{0}));
  ASSERT_EQ(shadowed->instance_draws[0].size(), 2u);
  EXPECT_EQ(shadowed->variants[shadowed->instance_draws[0][0].variant].keywords,
            (std::vector<std::string>{"SHADOWS_SCREEN"}));
  EXPECT_TRUE(shadowed->instance_draws[0][1].caster);
  EXPECT_EQ(shadowed->variants[shadowed->instance_draws[0][1].variant].keywords,
            (std::vector<std::string>{"SHADOWS_DEPTH"}));

  auto unlit = plan_scene(scene(sun + "shadows = \"hard\"\n" + object("unlit.shader") + object("receiver.shader") +
                                "position = [0, -2, 0]\n"),
                          ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(unlit) << unlit.error().to_string();
  EXPECT_EQ(casters(*unlit), 1u);  // the receiver casts too; the unlit object has nothing to cast with

  // A spot pixel light's shadow: its own map, received by the ForwardAdd drawn for it.
  std::ofstream(user / "spotlit.shader") << "Shader \"Spotlit\" { SubShader { " << program << R"(
    Pass { Tags { "LightMode" = "ForwardBase" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      ENDHLSL }
    Pass { Tags { "LightMode" = "ForwardAdd" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma multi_compile POINT SPOT
      #pragma multi_compile _ SHADOWS_DEPTH
      ENDHLSL }
    Pass { Tags { "LightMode" = "ShadowCaster" } HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      ENDHLSL } } })";
  const std::string spot =
      "[[light]]\ntype = \"spot\"\nposition = [0, 3, 0]\ndirection = [0, 1, 0]\nshadows = \"hard\"\n";
  auto spotlit = plan_scene(scene(sun + spot + object("spotlit.shader")), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(spotlit) << spotlit.error().to_string();
  EXPECT_EQ(spotlit->shadow_lights, (std::vector<size_t>{1}));  // the sun casts none
  ASSERT_EQ(spotlit->instance_draws[0].size(), 3u);
  EXPECT_EQ(spotlit->variants[spotlit->instance_draws[0][1].variant].keywords,
            (std::vector<std::string>{"SHADOWS_DEPTH", "SPOT"}));
  EXPECT_TRUE(spotlit->instance_draws[0][2].caster);
  EXPECT_EQ(spotlit->instance_draws[0][2].light, 1u);

  auto without = plan_scene(scene(sun + object("receiver.shader")), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(without) << without.error().to_string();
  EXPECT_TRUE(without->shadow_lights.empty());
  EXPECT_EQ(casters(*without), 0u);
  EXPECT_TRUE(without->variants[without->instance_draws[0][0].variant].keywords.empty());
  EXPECT_TRUE(
      has_line(without->left_out, "'receiver.shader' pass 1 (ShadowCaster): not drawn: no shadow map is drawn"));

  // Something casts, nothing receives: no map.
  auto unreceived =
      plan_scene(scene(sun + "shadows = \"hard\"\n" + object("caster.shader")), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(unreceived) << unreceived.error().to_string();
  EXPECT_TRUE(unreceived->shadow_lights.empty());
  EXPECT_TRUE(
      has_line(unreceived->left_out,
               "light 1's shadows: no shadow map: no pass drawn for it receives them (none declares SHADOWS_SCREEN)"));
  EXPECT_EQ(casters(*unreceived), 0u);
  // Something receives, nothing casts: no map either.
  auto uncast =
      plan_scene(scene(sun + "shadows = \"hard\"\n" + object("unlit.shader")), ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(uncast) << uncast.error().to_string();
  EXPECT_TRUE(uncast->shadow_lights.empty());
  fs::remove_all(user);
}

// A .shader post effect blits the passes `passes` names, in that order, each compiled whole (its
// own vertex program); each reads the step before as _MainTex unless its sources say otherwise.
TEST(Planner, AShaderPostEffectBlitsItsPassesInTheOrderTheSceneGives) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_shader_post";
  fs::remove_all(user);
  fs::create_directories(user);
  const std::string pass = R"(Pass { Name "NAME" Cull Off ZWrite Off ZTest Always HLSLPROGRAM
    #pragma vertex vert
    #pragma fragment frag
    Texture2D _MainTex; SamplerState sampler_MainTex; TEXTURES
    float4 vert(float3 p : POSITION, inout float2 uv : TEXCOORD0) : SV_Position { return float4(p, 1); }
    float4 frag(float4 pos : SV_Position, float2 uv : TEXCOORD0) : SV_Target { return BODY; }
    ENDHLSL }
)";
  const auto with = [&](std::string text, const std::string& name, const std::string& textures,
                        const std::string& body) {
    for (const auto& [from, to] :
         {std::pair<std::string, std::string>{"NAME", name}, {"TEXTURES", textures}, {"BODY", body}})
      text.replace(text.find(from), from.size(), to);
    return text;
  };
  std::ofstream(user / "blur.shader")
      << "Shader \"Hidden/Blur\" {\n  SubShader {\n"
      << with(pass, "Down", "", "_MainTex.Sample(sampler_MainTex, uv)")
      << with(pass, "Glow", "Texture2D _Bloom;",
              "_MainTex.Sample(sampler_MainTex, uv) + _Bloom.Sample(sampler_MainTex, uv)")
      << "  }\n}\n";
  const ShaderSearchPath folders({user, kLibrary});
  auto plan = plan_scene(scene(R"(
[[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
[[post]]
effect = "blur.shader"
passes = ["down", { pass = 0, name = "half", scale = "half" }, { pass = "Glow", sources = { _Bloom = "half", _MainTex = "scene.color" } }]
)"),
                         folders);
  ASSERT_TRUE(plan) << plan.error().to_string();
  std::vector<std::string> names;
  for (const PlannedPass& planned : plan->passes) names.push_back(planned.name);
  EXPECT_EQ(names, (std::vector<std::string>{"scene", "blur.down", "blur.half", "blur.Glow"}));
  const auto variant_of = [&](size_t index) { return plan->variants[plan->passes[index].variant]; };
  EXPECT_EQ(variant_of(1).shader_pass, std::optional<size_t>(0));
  EXPECT_EQ(variant_of(1).fragment_entry, "");
  EXPECT_EQ(plan->passes[1].variant, plan->passes[2].variant) << "pass 0 twice is one variant";
  EXPECT_EQ(variant_of(3).shader_pass, std::optional<size_t>(1));
  EXPECT_TRUE(plan->passes[1].blit);
  const auto inputs_of = [&](size_t index) {
    std::vector<std::string> inputs;
    for (const hlsl::PassInput& input : plan->passes[index].declaration.inputs)
      inputs.push_back(input.texture + " <- " +
                       (input.kind == hlsl::PassInput::Kind::Pass         ? input.pass
                        : input.kind == hlsl::PassInput::Kind::SceneColor ? "scene.color"
                                                                          : "scene.depth"));
    return inputs;
  };
  EXPECT_EQ(inputs_of(1), std::vector<std::string>{"_MainTex <- scene.color"});
  EXPECT_EQ(inputs_of(2), std::vector<std::string>{"_MainTex <- down"});
  EXPECT_EQ(plan->passes[2].declaration.scale, hlsl::PassDeclaration::Scale::Half);
  EXPECT_EQ(inputs_of(3), (std::vector<std::string>{"_Bloom <- half", "_MainTex <- scene.color"}));
  const std::string described = describe_plan(scene(""), *plan, std::vector<bool>(plan->variants.size(), false));
  EXPECT_NE(described.find("blur.half: blit of pass 0, half resolution, _MainTex <- down\n"), std::string::npos)
      << described;

  // No passes: the first pass alone. A pass the shader has not, and passes on an .hlsl effect, are
  // errors at their line.
  auto first = plan_scene(scene("[[post]]\neffect = \"blur.shader\"\n"), folders);
  ASSERT_TRUE(first) << first.error().to_string();
  ASSERT_EQ(first->passes.size(), 1u);
  EXPECT_EQ(first->passes[0].name, "blur.0");
  // The effect's textures give _MainTex: a blit of that texture, not of the scene's image.
  auto given =
      plan_scene(scene("[[post]]\neffect = \"blur.shader\"\n[post.textures]\n_MainTex = \"checker\"\n"), folders);
  ASSERT_TRUE(given) << given.error().to_string();
  EXPECT_TRUE(given->passes[0].declaration.inputs.empty());
  auto missing = plan_scene(scene("[[post]]\neffect = \"blur.shader\"\npasses = [\"Blur\"]\n"), folders);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().to_string(),
            "/tmp/planner_test.toml:12:11: the shader 'Hidden/Blur' has no pass 'Blur' in the SubShader it draws (its "
            "passes: "
            "0 (\"Down\"), 1 (\"Glow\"))");
  auto hlsl_passes = plan_scene(scene("[[post]]\neffect = \"post/depth_of_field.hlsl\"\npasses = [0]\n"), folders);
  ASSERT_FALSE(hlsl_passes);
  EXPECT_NE(hlsl_passes.error().to_string().find(":11:10: passes = [...] chooses the passes of a Unity .shader effect"),
            std::string::npos)
      << hlsl_passes.error().to_string();
  fs::remove_all(user);
}

// The front end's warnings about a scene's sources are the plan's, each once: the source's own
// with their place, those of the files it includes counted.
TEST(Planner, TheSourcesWarningsAreThePlansEachOnce) {
  const fs::path user = fs::temp_directory_path() / "xshade_planner_warnings";
  fs::remove_all(user);
  fs::create_directories(user);
  std::ofstream(user / "noisy.hlsl") << "#pragma fragment frag\n#pragma frobnicate\n#include \"noisy_include.hlsl\"\n"
                                        "float4 frag() : SV_Target { return widen(); }\n";
  std::ofstream(user / "noisy_include.hlsl") << "#pragma also_unknown\nfloat4 widen() { return 1; }\n";
  auto plan = plan_scene(scene("[[object]]\nmesh = \"sphere\"\nmaterial = \"noisy.hlsl\"\n[[object]]\nmesh = \"cube\"\n"
                               "material = \"noisy.hlsl\"\n"),
                         ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(plan) << plan.error().to_string();
  EXPECT_EQ(plan->warnings,
            (std::vector<std::string>{(user / "noisy.hlsl").string() + ":2:9: warning: unknown pragma 'frobnicate'",
                                      "noisy.hlsl: 1 warning in the files it includes (xshade compile shows them)"}));
  fs::remove_all(user);
}

TEST(Planner, AVariantThatReadsVertexInputsTheMeshesLackIsToldWhatItReads) {
  // TEXCOORD2 and COLOR1 only with the _EXTRA keyword: one variant reads them, the other not.
  const fs::path user = fs::temp_directory_path() / "xshade_planner_vertex_inputs";
  fs::remove_all(user);
  fs::create_directories(user / "materials");
  std::ofstream(user / "materials" / "extra_inputs.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _EXTRA
struct appdata {
  float3 position : POSITION;
  float2 uv : TEXCOORD0;
#ifdef _EXTRA
  float4 tint : COLOR1;
  float2 uv2 : TEXCOORD2;
#endif
};
struct v2f { float4 position : SV_Position; float4 color : COLOR0; };
v2f vert(appdata v) {
  v2f o;
  o.position = float4(v.position, 1);
  o.color = float4(v.uv, 0, 1);
#ifdef _EXTRA
  o.color += v.tint + float4(v.uv2, 0, 0);
#endif
  return o;
}
float4 frag(v2f i) : SV_Target { return i.color; }
)";
  auto plan = plan_scene(scene(R"(
[[object]]
name = "plain"
mesh = "sphere"
material = "materials/extra_inputs.hlsl"
[[object]]
name = "extra"
mesh = "cube"
material = "materials/extra_inputs.hlsl"
keywords = ["_EXTRA"]
)"),
                         ShaderSearchPath({user, kLibrary}));
  ASSERT_TRUE(plan) << plan.error().to_string();
  ASSERT_EQ(plan->variants.size(), 2u);
  ASSERT_EQ(plan->variant_notes.size(), 2u);
  EXPECT_TRUE(plan->variant_notes[first_variants(*plan)[0]].empty());
  EXPECT_EQ(
      plan->variant_notes[first_variants(*plan)[1]],
      (std::vector<std::string>{
          "vertex input COLOR1 is not in the meshes; the shader reads white, as from a mesh without vertex colours",
          "vertex input TEXCOORD2 is not in the meshes; the shader reads zeros"}));
  const std::string described = describe_plan(scene(""), *plan);
  EXPECT_NE(described.find("    materials/extra_inputs.hlsl [_EXTRA]\n"
                           "      vertex input COLOR1 is not in the meshes; the shader reads white, as from a mesh "
                           "without vertex colours\n"
                           "      vertex input TEXCOORD2 is not in the meshes; the shader reads zeros\n"),
            std::string::npos)
      << described;
  EXPECT_EQ(described.find("vertex input TEXCOORD0"), std::string::npos) << described;
  fs::remove_all(user);
}

}  // namespace
}  // namespace xshade::harness
