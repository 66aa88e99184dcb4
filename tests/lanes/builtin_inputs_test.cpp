// Every input the renderer gives a shader by name (docs/shader_library.md, "Unity's built-in
// inputs"), read by a shader on every lane and checked against the value the host expects. One
// test per row of that table: the test writes a probe shader that declares the input and writes
// it out (a matrix row per pixel), renders a scene with it on gl, vk and vk-hlsl, and compares.
// The expected values are worked out here from the scene's numbers and Unity's definitions, not
// taken from the renderer.
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::Lane;

// The scene every probe renders in: its numbers are the ones the expected values use.
constexpr uint32_t kWidth = 8, kHeight = 2;
const glm::vec3 kCameraPosition{1.0f, 2.0f, 6.0f}, kCameraTarget{0.0f, 0.5f, 0.0f};
constexpr float kFovY = 40.0f, kNear = 0.3f, kFar = 50.0f, kTime = 3.5f;
const glm::vec3 kLightDirection = glm::vec3(1.0f, 2.0f, 2.0f) / 3.0f, kLightColor{1.0f, 0.5f, 0.25f};
constexpr float kLightIntensity = 2.0f;
const glm::vec3 kObjectPosition{0.5f, -1.0f, 2.0f};
constexpr float kObjectScale = 2.0f;  // and rotated 90 degrees about +y

constexpr const char* kSceneText = R"(
description = "built-in inputs probe"
size = [8, 2]
time = 3.5
[camera]
position = [1, 2, 6]
target = [0, 0.5, 0]
fov_y = 40
near = 0.3
far = 50
[[light]]
type = "directional"
direction = [1, 2, 2]
color = [1, 0.5, 0.25]
intensity = 2
[environment]
kind = "equirect"
file = "environment.exr"
[[object]]
mesh = "plane"
material = "probe_material.hlsl"
position = [0.5, -1, 2]
rotation = [0, 90, 0]
scale = 2
)";

// A probe's object gives only what its material declares: the scene-shader contract refuses
// any other name.
constexpr const char* kCheckerMainTex = "[object.textures]\n_MainTex = \"checker\"\n";

// A material that covers the whole target at depth 0.5 whatever the camera (its plane's uv is
// its clip position) and writes `expression` of pixel column i (0..3).
std::string material_probe(const std::string& declarations, const std::string& expression) {
  return fmt::format(R"(#pragma vertex vert
#pragma fragment frag
struct Vertex {{ float3 position : POSITION; float2 uv : TEXCOORD0; }};
float4 vert(Vertex v) : SV_Position {{ return float4(v.uv * 2.0 - 1.0, 0.5, 1.0); }}
{}
float4 frag(float4 p : SV_Position) : SV_Target {{
  uint i = min(uint(p.x), 3u);
  return {};
}}
)",
                     declarations, expression);
}

std::string post_probe(const std::string& inputs, const std::string& declarations, const std::string& expression) {
  return fmt::format(R"(#pragma pass probe frag {}
{}
float4 frag(float4 p : SV_Position) : SV_Target {{
  uint i = min(uint(p.x), 3u);
  return {};
}}
)",
                     inputs, declarations, expression);
}

// The environment is direction_equirect(): radiance 0.5 + 0.5 d, whose irradiance / pi is exactly
// 0.5 + d / 3 (a linear radiance's cosine convolution is 2/3 of its linear part, over pi).

std::vector<float> rows_of(const glm::mat4& m) {  // HLSL component order: row by row
  std::vector<float> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.push_back(m[c][r]);
  return out;
}

glm::mat4 view() { return glm::lookAtRH(kCameraPosition, kCameraTarget, glm::vec3(0, 1, 0)); }
glm::mat4 gpu_projection() {  // Direct3D clip space, depth 0 at the near plane
  return glm::perspectiveRH_ZO(glm::radians(kFovY), float(kWidth) / float(kHeight), kNear, kFar);
}
glm::mat4 camera_projection() {  // Unity's Camera.projectionMatrix: OpenGL's clip space
  return glm::perspectiveRH_NO(glm::radians(kFovY), float(kWidth) / float(kHeight), kNear, kFar);
}
glm::mat4 model() {
  return glm::scale(
      glm::rotate(glm::translate(glm::mat4(1.0f), kObjectPosition), glm::radians(90.0f), glm::vec3(0, 1, 0)),
      glm::vec3(kObjectScale));
}
const glm::mat4 kFlipZ = glm::scale(glm::mat4(1.0f), glm::vec3(1, 1, -1));

struct Row {
  std::string name;             // the test's name: the table's row
  bool post = false;            // read in a post pass; else in the object's material
  std::string declarations;     // what the probe declares
  std::string expression;       // the float4 pixel column i writes
  std::vector<float> expected;  // pixel 0's four values, then pixel 1's, ... (at most 4 pixels)
  // Why the comparison allows what it does: float32 through different drivers' arithmetic.
  float tolerance = 1e-5f;
  std::string pass_inputs = {};
  std::string object_tables = {};  // TOML the object adds: the textures and properties the row reads
};

void PrintTo(const Row& row, std::ostream* out) { *out << row.name; }

Row vector_row(const std::string& name, const std::string& type, std::vector<float> expected, bool post = true) {
  std::string expression = type == "float4"   ? name
                           : type == "float3" ? "float4(" + name + ", 0)"
                                              : "float4(" + name + ", 0, 0, 0)";
  expected.resize(4, 0.0f);
  return {name, post, type + " " + name + ";", expression, expected};
}
Row matrix_row(const std::string& name, const glm::mat4& m, bool post = true) {
  return {name,         post,       "float4x4 " + name + ";",
          name + "[i]", rows_of(m), 1e-4f};  // inverses and products: a few ulps of 100
}

std::vector<Row> rows() {
  const float t = kTime;
  std::vector<Row> all = {
      vector_row("_Time", "float4", {t / 20, t, 2 * t, 3 * t}),
      vector_row("_SinTime", "float4", {std::sin(t / 8), std::sin(t / 4), std::sin(t / 2), std::sin(t)}),
      vector_row("_CosTime", "float4", {std::cos(t / 8), std::cos(t / 4), std::cos(t / 2), std::cos(t)}),
      vector_row("unity_DeltaTime", "float4", {1.0f / 60, 60, 1.0f / 60, 60}),
      vector_row("unity_StereoEyeIndex", "int", {0}),
      vector_row("_WorldSpaceCameraPos", "float3", {kCameraPosition.x, kCameraPosition.y, kCameraPosition.z}),
      vector_row("_ProjectionParams", "float4", {1, kNear, kFar, 1 / kFar}),
      vector_row("_ScreenParams", "float4", {8, 2, 1.125f, 1.5f}),
      vector_row("_ZBufferParams", "float4",
                 {1 - kFar / kNear, kFar / kNear, (1 - kFar / kNear) / kFar, (kFar / kNear) / kFar}),
      vector_row("unity_OrthoParams", "float4", {0, 0, 0, 0}),
      vector_row("_WorldSpaceLightPos0", "float4", {kLightDirection.x, kLightDirection.y, kLightDirection.z, 0}),
      vector_row("_LightColor0", "float4", {2, 1, 0.5f, 2}),
      vector_row("unity_ColorSpaceLuminance", "float4", {0.0396819152f, 0.458021790f, 0.00609653955f, 1}),
      vector_row("unity_SpecCube0_HDR", "float4", {1, 1, 0, 0}),
      matrix_row("unity_CameraProjection", camera_projection()),
      matrix_row("unity_CameraInvProjection", glm::inverse(camera_projection())),
      matrix_row("glstate_matrix_projection", gpu_projection()),
      matrix_row("unity_MatrixV", view()),
      matrix_row("unity_MatrixInvV", glm::inverse(view())),
      matrix_row("unity_MatrixVP", gpu_projection() * view()),
      matrix_row("unity_WorldToCamera", kFlipZ * view()),
      matrix_row("unity_CameraToWorld", glm::inverse(kFlipZ * view())),
      matrix_row("unity_ObjectToWorld", model(), false),
      matrix_row("unity_WorldToObject", glm::inverse(model()), false),
      vector_row("unity_WorldTransformParams", "float4", {0, 0, 0, 1}, false),
  };
  // Ambient light: ShadeSH9's constants for irradiance / pi = 0.5 + d / 3 in each channel. The
  // environment is texel-constant on a 256 x 128 image: 1e-3 covers that discretisation.
  const char* channels[] = {"r", "g", "b"};
  for (int c = 0; c < 3; ++c) {
    std::vector<float> a{0, 0, 0, 0.5f};
    a[size_t(c)] = 1.0f / 3.0f;
    Row row = vector_row(std::string("unity_SHA") + channels[c], "float4", a);
    row.tolerance = 1e-3f;
    all.push_back(row);
    row = vector_row(std::string("unity_SHB") + channels[c], "float4", {0, 0, 0, 0});
    row.tolerance = 1e-3f;
    all.push_back(row);
  }
  // Half the mean ambient, 0.5 (the constant of 0.5 + d / 3), as Unity stores it.
  Row ambient = vector_row("glstate_lightmodel_ambient", "float4", {0.25f, 0.25f, 0.25f, 0.5f});
  ambient.tolerance = 1e-3f;
  all.push_back(ambient);
  Row shc = vector_row("unity_SHC", "float4", {0, 0, 0, 1});
  shc.tolerance = 1e-3f;
  all.push_back(shc);

  // A light without shadows and no light probe proxy volume, one value a pixel.
  all.push_back(
      {"unity_shadow_and_probe_volume",
       true,
       "float4 _LightShadowData; float4 unity_ShadowFadeCenterAndType; float4 unity_OcclusionMaskSelector; "
       "float4 unity_ProbeVolumeParams;",
       "i == 0 ? _LightShadowData : i == 1 ? unity_ShadowFadeCenterAndType : i == 2 ? unity_OcclusionMaskSelector "
       ": unity_ProbeVolumeParams",
       {1, 0, 0, 0, kCameraPosition.x, kCameraPosition.y, kCameraPosition.z, 0, 1, 0, 0, 0, 0, 0, 0, 0}});

  // Lights the scene has not: a vertex light's slot as Unity's manual describes an unused one.
  all.push_back(
      {"unused_vertex_lights",
       true,
       "float4 unity_LightColor[8]; float4 unity_LightPosition[8]; float4 unity_LightAtten[8]; "
       "float4 unity_SpotDirection[8]; float4 unity_4LightPosX0; float4 unity_4LightAtten0; float4 unity_LightmapST;",
       "i == 0 ? unity_LightColor[7] + unity_4LightPosX0 + unity_4LightAtten0 : i == 1 ? unity_LightPosition[7] "
       ": i == 2 ? unity_LightAtten[3] + float4(0, 0, unity_SpotDirection[5].xy) : unity_LightmapST",
       {0, 0, 0, 0, 0, 0, 1, 0, -1, 1, 0, 0, 1, 1, 0, 0}});
  // The frustum's left, right, bottom and top planes, made here from its corners: each plane holds
  // three of them and its unit normal points at the frustum's centre.
  {
    const glm::mat4 inverse = glm::inverse(gpu_projection() * view());
    const auto corner = [&](float x, float y, float z) {
      const glm::vec4 p = inverse * glm::vec4(x, y, z, 1);
      return glm::vec3(p) / p.w;
    };
    const glm::vec3 centre = corner(0, 0, 0.5f);
    std::vector<float> planes;
    for (const auto& [a, b, c] : {std::tuple{corner(-1, -1, 0), corner(-1, 1, 0), corner(-1, -1, 1)},
                                  std::tuple{corner(1, -1, 0), corner(1, 1, 0), corner(1, -1, 1)},
                                  std::tuple{corner(-1, -1, 0), corner(1, -1, 0), corner(-1, -1, 1)},
                                  std::tuple{corner(-1, 1, 0), corner(1, 1, 0), corner(-1, 1, 1)}}) {
      glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
      if (glm::dot(n, centre - a) < 0) n = -n;
      planes.insert(planes.end(), {n.x, n.y, n.z, -glm::dot(n, a)});
    }
    // Corners unprojected through an inverse: a few ulps of the far plane's 100.
    all.push_back({"unity_CameraWorldClipPlanes", true, "float4 unity_CameraWorldClipPlanes[6];",
                   "unity_CameraWorldClipPlanes[i]", planes, 1e-4f});
  }

  // The matrix macros of the prelude, over the variables they name.
  const std::string mvp_declarations = "float4x4 unity_ObjectToWorld; float4x4 unity_MatrixVP; float4x4 unity_MatrixV;";
  all.push_back({"UNITY_MATRIX_MVP", false, mvp_declarations, "UNITY_MATRIX_MVP[i]",
                 rows_of(gpu_projection() * view() * model()), 1e-4f});
  all.push_back({"UNITY_MATRIX_MV", false, mvp_declarations, "UNITY_MATRIX_MV[i]", rows_of(view() * model()), 1e-4f});
  all.push_back({"UNITY_MATRIX_IT_MV", false, "float4x4 unity_WorldToObject; float4x4 unity_MatrixInvV;",
                 "UNITY_MATRIX_IT_MV[i]", rows_of(glm::transpose(glm::inverse(view() * model()))), 1e-4f});
  all.push_back({"UNITY_MATRIX_P", true, "float4x4 glstate_matrix_projection;", "UNITY_MATRIX_P[i]",
                 rows_of(gpu_projection()), 1e-5f});

  // Textures' sizes, tiling and offset; the depth texture; the reflection probe.
  const std::string main_tex = "Texture2D _MainTex; SamplerState sampler_MainTex; ";
  const std::string touch_main_tex = " + 0.0 * _MainTex.Load(int3(0, 0, 0))";  // the texture must be read to be bound
  all.push_back({"material_HDR",
                 false,
                 main_tex + "half4 _MainTex_HDR;",
                 "_MainTex_HDR" + touch_main_tex,
                 {1, 1, 0, 0},
                 1e-5f,
                 "",
                 kCheckerMainTex});
  all.push_back({"material_TexelSize",
                 false,
                 main_tex + "float4 _MainTex_TexelSize;",
                 "_MainTex_TexelSize" + touch_main_tex,
                 {1.0f / 64, 1.0f / 64, 64, 64},
                 1e-5f,
                 "",
                 kCheckerMainTex});
  all.push_back({"post_TexelSize",
                 true,
                 main_tex + "float4 _MainTex_TexelSize;",
                 "_MainTex_TexelSize" + touch_main_tex,
                 {1.0f / 8, 1.0f / 2, 8, 2},
                 1e-5f,
                 "_MainTex=scene.color"});
  all.push_back({"ST_default",
                 false,
                 main_tex + "float4 _MainTex_ST;",
                 "_MainTex_ST" + touch_main_tex,
                 {1, 1, 0, 0},
                 1e-5f,
                 "",
                 kCheckerMainTex});
  all.push_back({"ST_from_the_scene",
                 false,
                 "float4 _DetailTex_ST;",
                 "_DetailTex_ST",
                 {2, 3, 0.5f, 0.25f},
                 1e-5f,
                 "",
                 "[object.properties]\n_DetailTex_ST = [2, 3, 0.5, 0.25]\n"});
  // The material wrote depth 0.5 everywhere; the pass names no source for the depth texture.
  all.push_back({"_CameraDepthTexture",
                 true,
                 "Texture2D _CameraDepthTexture;",
                 "_CameraDepthTexture.Load(int3(i, 0, 0)).rrrr",
                 {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f}});
  // Level 0 along +x, -y, +z, -z: 0.5 + 0.5 d. The cube's texel centres are a half texel off the
  // axis and the equirect behind them is bilinear: 0.02 is about one texel's change of d.
  Row probe{"unity_SpecCube0",
            true,
            "TextureCube unity_SpecCube0; SamplerState samplerunity_SpecCube0;",
            "unity_SpecCube0.SampleLevel(samplerunity_SpecCube0, i == 0 ? float3(1, 0, 0) : i == 1 ? float3(0, -1, 0) "
            ": i == 2 ? float3(0, 0, 1) : float3(0, 0, -1), 0)",
            {1, 0.5f, 0.5f, 1, 0.5f, 0, 0.5f, 1, 0.5f, 0.5f, 1, 1, 0.5f, 0.5f, 0, 1},
            0.02f};
  all.push_back(probe);
  return all;
}

class BuiltinInputs : public ::testing::TestWithParam<Row> {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void TearDown() override { expect_no_driver_messages(); }
};

TEST_P(BuiltinInputs, ShadersReadTheHostsValueOnEveryLane) {
  const Row& row = GetParam();
  const ProbeScene probe("builtin_" + row.name);
  probe.write_direction_equirect("environment.exr");
  std::string scene_text = kSceneText + row.object_tables;
  if (row.post) {
    probe.write("probe_material.hlsl", material_probe("", "float4(0, 0, 0, 1)"));
    probe.write("probe_post.hlsl", post_probe(row.pass_inputs, row.declarations, row.expression));
    scene_text += "[[post]]\neffect = \"probe_post.hlsl\"\n";
  } else {
    probe.write("probe_material.hlsl", material_probe(row.declarations, row.expression));
  }
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image = probe.render(scene_text, lane, suite_backend(lane));
    ASSERT_TRUE(image) << image.error().to_string();
    for (size_t k = 0; k < row.expected.size(); ++k) {
      const glm::vec4 pixel = image->at(uint32_t(k / 4), 0);
      EXPECT_NEAR(pixel[int(k % 4)], row.expected[k], row.tolerance * std::max(1.0f, std::abs(row.expected[k])))
          << "pixel " << k / 4 << " component " << k % 4;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Rows, BuiltinInputs, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& row) { return row.param.name; });

}  // namespace
}  // namespace xshade::tests
