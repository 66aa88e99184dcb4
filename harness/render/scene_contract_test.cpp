// The scene-shader contract through the planner, on the library's shaders and on small ones
// written here: each broken name is an error at the scene's line, with the nearest name.
#include "harness/render/scene_contract.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "harness/render/planner.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const fs::path kShaderLibrary = fs::path(XSHADE_SOURCE_DIR) / "shaders";

// Eight lines, so that a scene body's first line is line 9 of the file.
constexpr const char* kHeader = R"(description = "contract test"
size = [32, 32]
[camera]
position = [0, 0, 5]
target = [0, 0, 0]
fov_y = 40
near = 0.3
far = 100
)";

Result<Plan> plan(const std::string& body, const ShaderSearchPath& shaders = kShaderLibrary) {
  auto scene = parse_scene(std::string(kHeader) + body, "/tmp/contract_test.toml");
  EXPECT_TRUE(scene) << scene.error().to_string();
  if (!scene) return fail(ErrorKind::UserInput, "scene does not parse");
  return plan_scene(*scene, shaders);
}

// A user folder with one material, `materials/<name>.hlsl`.
fs::path user_folder(const std::string& name, const std::string& material) {
  const fs::path root = fs::temp_directory_path() / ("xshade_contract_" + name);
  fs::create_directories(root / "materials");
  std::ofstream(root / "materials" / (name + ".hlsl")) << material;
  return root;
}

constexpr const char* kRampMaterial = R"(#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _RIM
float4 _Color = float4(1, 1, 1, 1);
float _Strength;
Texture2D _RampTex;
SamplerState sampler_RampTex;
Texture2D _MaskTex <string Default = "black";>;
SamplerState sampler_MaskTex;
float4x4 _ObjectToWorld;
float4x4 _WorldToClip;
float4 vert(float3 p : POSITION) : SV_Position { return mul(_WorldToClip, mul(_ObjectToWorld, float4(p, 1))); }
float4 frag(float4 p : SV_Position) : SV_Target {
  float2 uv = p.xy / 32;
  return _Color * _Strength * _RampTex.Sample(sampler_RampTex, uv) + _MaskTex.Sample(sampler_MaskTex, uv);
}
)";

TEST(SceneContract, AMisspeltPropertyIsAnErrorAtItsKeyWithTheNearestName) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
[object.properties]
_Colr = [1, 0, 0, 1]
)");
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.to_string(), "/tmp/contract_test.toml:13:1");
  EXPECT_EQ(planned.error().message, "material 'materials/toon.hlsl' has no property '_Colr'; did you mean '_Color'?");
}

TEST(SceneContract, AValueOfTheWrongSizeSaysHowManyNumbersTheShaderWants) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
[object.properties]
_Color = [1, 0, 0]
)");
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.line, 13u);
  EXPECT_EQ(planned.error().message,
            "'_Color' is a half4 in material 'materials/toon.hlsl': give it 4 numbers, not 3 numbers");
}

TEST(SceneContract, AGridRuleNamesAPropertyTheMaterialHas) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/standard_pbr.hlsl"
[object.grid]
rows = 1
cols = 2
spacing = 2
[object.grid.vary]
_Metalic = { along = "cols", from = 0.0, to = 1.0 }
)");
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.line, 17u);
  EXPECT_NE(planned.error().message.find("no property '_Metalic'; did you mean '_Metallic'?"), std::string::npos);
}

TEST(SceneContract, TheRenderersOwnInputsAreNotTheScenesToSet) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
[object.properties]
_LightColor = [1, 1, 1, 1]
)");
  ASSERT_FALSE(planned);
  EXPECT_NE(planned.error().message.find("'_LightColor' is set by the renderer"), std::string::npos)
      << planned.error().message;
}

TEST(SceneContract, AnUndeclaredKeywordIsAnErrorEvenThoughItWouldCompile) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
keywords = ["_SHADOW_TEXTURE"]
)");
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.to_string(), "/tmp/contract_test.toml:12:13");
  EXPECT_EQ(planned.error().message,
            "material 'materials/toon.hlsl' declares no keyword '_SHADOW_TEXTURE' "
            "(#pragma multi_compile or shader_feature); did you mean '_SHADOW_TEX'?");
}

TEST(SceneContract, APostParameterTheEffectLacksIsAnError) {
  auto planned = plan(R"([[post]]
effect = "post/depth_of_field.hlsl"
[post.parameters]
_BlurAmount = 2.0
)");
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.line, 12u);
  EXPECT_NE(planned.error().message.find("post effect 'post/depth_of_field.hlsl' has no parameter '_BlurAmount'; its "
                                         "parameters are _FocusDistance"),
            std::string::npos)
      << planned.error().message;
}

TEST(SceneContract, AMisspeltTextureSuggestsTheOneTheMaterialSamples) {
  const fs::path user = user_folder("ramp", kRampMaterial);
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/ramp.hlsl"
[object.properties]
_Strength = 1
[object.textures]
_RampTexture = "checker"
_RampTex = "white"
)",
                      ShaderSearchPath({user, kShaderLibrary}));
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.line, 15u);
  EXPECT_EQ(planned.error().message,
            "material 'materials/ramp.hlsl' has no texture '_RampTexture'; did you mean '_RampTex'?");
}

TEST(SceneContract, ASampledTextureNeedsTheScenesImageOrADeclaredDefault) {
  const fs::path user = user_folder("ramp", kRampMaterial);
  auto missing = plan(R"([[object]]
name = "ball"
mesh = "sphere"
material = "materials/ramp.hlsl"
[object.properties]
_Strength = 1
)",
                      ShaderSearchPath({user, kShaderLibrary}));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().where.line, 12u);  // the material line
  EXPECT_NE(missing.error().message.find("object 'ball': material 'materials/ramp.hlsl' samples '_RampTex', which the "
                                         "object's textures do not give and the shader declares no default"),
            std::string::npos)
      << missing.error().message;

  // Given _RampTex, the mask comes from its declared default, and the plan says so.
  auto given = plan(R"([[object]]
name = "ball"
mesh = "sphere"
material = "materials/ramp.hlsl"
[object.properties]
_Strength = 1
[object.textures]
_RampTex = "checker"
)",
                    ShaderSearchPath({user, kShaderLibrary}));
  ASSERT_TRUE(given) << given.error().to_string();
  ASSERT_EQ(given->instances.size(), 1u);
  ASSERT_TRUE(given->instances[0].textures.count("_MaskTex"));
  EXPECT_EQ(given->instances[0].textures.at("_MaskTex").source, TextureOrigin::Black);
  EXPECT_EQ(given->variant_notes[0],
            std::vector<std::string>{
                "object 'ball': material 'materials/ramp.hlsl': texture _MaskTex is the shader's default \"black\""});
}

// A shadow map is compared against depth, and every texture a scene names or a default gives
// holds colour: an error at the scene's line, not a draw the driver refuses.
TEST(SceneContract, ATextureReadWithAComparisonSamplerTakesNoSceneTexture) {
  const fs::path user = user_folder("shadowed", R"(#pragma vertex vert
#pragma fragment frag
Texture2D _ShadowMap <string Default = "white";>;
SamplerComparisonState sampler_ShadowMap;
float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
float4 frag(float4 p : SV_Position) : SV_Target { return _ShadowMap.SampleCmpLevelZero(sampler_ShadowMap, p.xy, 0.5); }
)");
  for (const std::string textures : {"", "[object.textures]\n_ShadowMap = \"white\"\n"}) {
    auto refused =
        plan("[[object]]\nname = \"ball\"\nmesh = \"sphere\"\nmaterial = \"materials/shadowed.hlsl\"\n" + textures,
             ShaderSearchPath({user, kShaderLibrary}));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().message.find("samples '_ShadowMap' with a comparison sampler, a shadow map's depth: no "
                                           "texture a scene names holds depth"),
              std::string::npos)
        << refused.error().message;
    EXPECT_EQ(refused.error().where.line, textures.empty() ? 12u : 14u) << "the material's line, or the texture's";
  }
}

TEST(SceneContract, AUniformWithoutAValueIsAnErrorAtTheObject) {
  const fs::path user = user_folder("ramp", kRampMaterial);
  auto planned = plan(R"([[object]]
name = "ball"
mesh = "sphere"
material = "materials/ramp.hlsl"
[object.textures]
_RampTex = "checker"
)",
                      ShaderSearchPath({user, kShaderLibrary}));
  ASSERT_FALSE(planned);
  EXPECT_EQ(planned.error().where.line, 12u);
  EXPECT_NE(planned.error().message.find("uniform '_Strength' (float) has no value"), std::string::npos)
      << planned.error().message;
}

TEST(SceneContract, EveryBreachIsReportedInFileOrder) {
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/toon.hlsl"
keywords = ["_GUARDD"]
[object.properties]
_Colr = [1, 0, 0, 1]
_RampSmoth = 0.2
)");
  ASSERT_FALSE(planned);
  ASSERT_EQ(planned.error().diagnostics.size(), 3u);
  EXPECT_EQ(planned.error().diagnostics[0].where.line, 12u);
  EXPECT_EQ(planned.error().diagnostics[1].where.line, 14u);
  EXPECT_EQ(planned.error().diagnostics[2].where.line, 15u);
  EXPECT_EQ(planned.error().message, planned.error().diagnostics[0].message);
}

TEST(SceneContract, ADefaultMustNameABuiltInTexture) {
  const fs::path user = user_folder("bad_default", R"(#pragma fragment frag
Texture2D _MaskTex <string Default = "whte";>;
SamplerState s;
float4 frag(float4 p : SV_Position) : SV_Target { return _MaskTex.Sample(s, p.xy); }
)");
  auto planned = plan(R"([[object]]
mesh = "sphere"
material = "materials/bad_default.hlsl"
)",
                      ShaderSearchPath({user, kShaderLibrary}));
  ASSERT_FALSE(planned);
  ASSERT_FALSE(planned.error().diagnostics.empty());
  EXPECT_NE(planned.error().diagnostics[0].message.find("Default of texture '_MaskTex' must be \"white\""),
            std::string::npos)
      << planned.error().to_string();
}

}  // namespace
}  // namespace xshade::harness
