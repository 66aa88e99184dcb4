// The cube maps and 3D textures a scene gives a shader (docs/scenes.md), sampled on every lane:
// each cube face where Direct3D puts it, in Direct3D's orientation, through an asymmetric cube
// (every texel of every face a different colour); a cube from an equirect image and the scene's
// environment; 3D textures from a LUT strip and from a .cube file; and the errors of a texture the
// shader's declaration cannot take, with the scene's line.
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "harness/image/image_io.h"
#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::FloatImage;
using harness::Lane;

// A post effect that writes `expression` for pixel column i: a one-row image of `width` pixels.
std::string scene_with_post(uint32_t width, const std::string& textures) {
  return probe_scene_head("scene textures probe", width, 1) + fmt::format(R"([environment]
kind = "equirect"
file = "environment.exr"
[[post]]
effect = "probe.hlsl"
[post.textures]
{}
)",
                                                                          textures);
}

std::string post_probe(const std::string& declarations, const std::string& expression) {
  return fmt::format(R"(#pragma pass probe frag
{}
float4 frag(float4 p : SV_Position) : SV_Target {{
  uint i = uint(p.x);
  return {};
}}
)",
                     declarations, expression);
}

// Direct3D's cube addressing written out: the direction through point st of face f (+X, -X, +Y,
// -Y, +Z, -Z), s to the right and t down the face's uploaded rows.
constexpr const char* kFaceDirection = R"(
float3 face_direction(uint f, float2 st) {
  float sc = 2.0 * st.x - 1.0;
  float tc = 2.0 * st.y - 1.0;
  if (f == 0) return float3(1, -tc, -sc);
  if (f == 1) return float3(-1, -tc, sc);
  if (f == 2) return float3(sc, 1, tc);
  if (f == 3) return float3(sc, -1, -tc);
  if (f == 4) return float3(sc, -tc, 1);
  return float3(-sc, -tc, -1);
}
)";

// The colour of texel (x, y) of face f in the asymmetric test cube.
glm::vec4 face_texel(uint32_t f, uint32_t x, uint32_t y) {
  return {0.1f + 0.15f * float(f), 0.25f + 0.5f * float(x), 0.25f + 0.5f * float(y), 1.0f};
}

class SceneTextures : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void SetUp() override { probe_.write_direction_equirect("environment.exr"); }
  void TearDown() override { expect_no_driver_messages(); }

  // Renders on every lane and compares pixel k with expected[k] within `tolerance`.
  void expect_pixels(const std::string& scene_text, const std::vector<glm::vec4>& expected, float tolerance) {
    for (Lane lane : harness::all_lanes()) {
      SCOPED_TRACE(harness::lane_name(lane));
      auto image = probe_.render(scene_text, lane, suite_backend(lane));
      ASSERT_TRUE(image) << image.error().to_string();
      for (uint32_t k = 0; k < expected.size(); ++k)
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(image->at(k, 0)[c], expected[k][c], tolerance) << "pixel " << k << " channel " << c;
    }
  }

  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(SceneTextures, SixFacesEachWhereDirect3DPutsIt) {
  for (uint32_t f = 0; f < 6; ++f) {
    FloatImage face(2, 2);
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 2; ++x) face.set(x, y, face_texel(f, x, y));
    probe_.write_image("face" + std::to_string(f) + ".exr", face);
  }
  // Pixel 4 f + 2 y + x looks through the centre of texel (x, y) of face f; texel centres filter
  // to the texel itself.
  probe_.write("probe.hlsl", post_probe(std::string("TextureCube _Cube; SamplerState sampler_Cube;") + kFaceDirection,
                                        "_Cube.SampleLevel(sampler_Cube, face_direction(i / 4, "
                                        "float2((i % 2) + 0.5, ((i / 2) % 2) + 0.5) / 2.0), 0)"));
  std::vector<glm::vec4> expected;
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t y = 0; y < 2; ++y)
      for (uint32_t x = 0; x < 2; ++x) expected.push_back(face_texel(f, x, y));
  // 1e-5: an exact texel read, through each driver's float filtering.
  expect_pixels(
      scene_with_post(
          24, R"(_Cube = { faces = ["face0.exr", "face1.exr", "face2.exr", "face3.exr", "face4.exr", "face5.exr"] })"),
      expected, 1e-5f);
}

// The axes +x, -x, +y, -y, +z, -z read 0.5 + 0.5 axis from a cube made of an equirect image, and
// from the scene's environment. 0.02: the cube's texel centres lie half a texel off the axis,
// over a bilinear equirect, about one texel's change of d.
constexpr const char* kAxes =
    "_Cube.SampleLevel(sampler_Cube, i == 0 ? float3(1, 0, 0) : i == 1 ? float3(-1, 0, 0) : i == 2 ? float3(0, 1, 0) "
    ": i == 3 ? float3(0, -1, 0) : i == 4 ? float3(0, 0, 1) : float3(0, 0, -1), 0)";
const std::vector<glm::vec4> kAxisColours = {{1, 0.5f, 0.5f, 1}, {0, 0.5f, 0.5f, 1}, {0.5f, 1, 0.5f, 1},
                                             {0.5f, 0, 0.5f, 1}, {0.5f, 0.5f, 1, 1}, {0.5f, 0.5f, 0, 1}};

TEST_F(SceneTextures, ACubeFromAnEquirectImageLooksWhereTheImageDoes) {
  probe_.write_direction_equirect("sky.exr");
  probe_.write("probe.hlsl", post_probe("TextureCube _Cube; SamplerState sampler_Cube;", kAxes));
  expect_pixels(scene_with_post(6, R"(_Cube = "sky.exr")"), kAxisColours, 0.02f);
}

TEST_F(SceneTextures, TheEnvironmentAsACube) {
  probe_.write("probe.hlsl", post_probe("TextureCube _Cube; SamplerState sampler_Cube;", kAxes));
  expect_pixels(scene_with_post(6, R"(_Cube = "environment")"), kAxisColours, 0.02f);
}

// Pixel 16 b + 4 g + r samples the centre of texel (r, g, b) of a 4 x 4 x 4 LUT.
constexpr const char* kLutProbe = "_Lut.SampleLevel(sampler_Lut, (float3(i % 4, (i / 4) % 4, i / 16) + 0.5) / 4.0, 0)";

TEST_F(SceneTextures, A3DTextureFromALutStripAsUnityLaysItOut) {
  // Unity's layout: slice b at columns 4b..4b+3, red to the right, green up from the bottom row.
  FloatImage strip(16, 4);
  for (uint32_t b = 0; b < 4; ++b)
    for (uint32_t g = 0; g < 4; ++g)
      for (uint32_t r = 0; r < 4; ++r)
        strip.set(4 * b + r, 3 - g, glm::vec4(float(r), float(g), float(b), 3.0f) / 3.0f);
  probe_.write_image("lut.png", strip);
  probe_.write("probe.hlsl", post_probe("Texture3D _Lut; SamplerState sampler_Lut;", kLutProbe));
  // srgb = false: the file's bytes are data, byte / 255: what the PNG's encoding of each value left.
  std::vector<glm::vec4> expected;
  const auto stored = [](float linear) { return float(harness::linear_to_srgb8(linear)) / 255.0f; };
  for (uint32_t b = 0; b < 4; ++b)
    for (uint32_t g = 0; g < 4; ++g)
      for (uint32_t r = 0; r < 4; ++r)
        expected.push_back({stored(float(r) / 3), stored(float(g) / 3), stored(float(b) / 3), 1.0f});
  // 1e-5: exact texel reads of 8-bit values.
  expect_pixels(scene_with_post(64, R"(_Lut = { file = "lut.png", srgb = false })"), expected, 1e-5f);
}

TEST_F(SceneTextures, A3DTextureFromACubeFile) {
  std::string cube = "TITLE \"probe\"\nLUT_3D_SIZE 4\n";
  std::vector<glm::vec4> expected;
  for (int b = 0; b < 4; ++b)
    for (int g = 0; g < 4; ++g)
      for (int r = 0; r < 4; ++r) {
        const glm::vec4 value{0.25f * float(r), 0.125f * float(g), 1.0f - 0.25f * float(b), 1.0f};
        cube += fmt::format("{} {} {}\n", value.r, value.g, value.b);
        expected.push_back(value);
      }
  probe_.write("grade.cube", cube);
  probe_.write("probe.hlsl", post_probe("Texture3D _Lut; SamplerState sampler_Lut;", kLutProbe));
  expect_pixels(scene_with_post(64, R"(_Lut = "grade.cube")"), expected, 1e-5f);
}

// A material's textures come the same way: the asymmetric cube's +y face read by an object's
// material through [object.textures], at the centre of its one texel (off the centre, seamless
// cube filtering blends in the neighbouring faces).
TEST_F(SceneTextures, AMaterialTakesACubeToo) {
  for (uint32_t f = 0; f < 6; ++f) {
    FloatImage face(1, 1);
    face.set(0, 0, face_texel(f, 0, 0));
    probe_.write_image("face" + std::to_string(f) + ".exr", face);
  }
  probe_.write("probe_material.hlsl", R"(#pragma vertex vert
#pragma fragment frag
TextureCube _Cube;
SamplerState sampler_Cube;
float4 vert(float2 uv : TEXCOORD0) : SV_Position { return float4(uv * 2.0 - 1.0, 0.5, 1.0); }
float4 frag() : SV_Target { return _Cube.SampleLevel(sampler_Cube, float3(0, 1, 0), 0); }
)");
  const std::string scene = probe_scene_head("a material's cube", 2, 2) + R"([[object]]
mesh = "plane"
material = "probe_material.hlsl"
[object.textures]
_Cube = { faces = ["face0.exr", "face1.exr", "face2.exr", "face3.exr", "face4.exr", "face5.exr"] }
)";
  expect_pixels(scene, {face_texel(2, 0, 0)}, 1e-5f);
}

// A texture the shader's declaration cannot take fails with the scene value's line and column,
// or the LUT file's own.
TEST_F(SceneTextures, ErrorsNameTheSceneLineOrTheFilesLine) {
  probe_.write_image("strip.png", FloatImage(10, 4));
  probe_.write("bad.cube", "LUT_3D_SIZE 2\n0 0 zero\n");
  probe_.write("probe.hlsl",
               post_probe("Texture3D _Lut; SamplerState sampler_Lut;", "_Lut.SampleLevel(sampler_Lut, 0.5, 0)"));
  Lane lane = Lane::Gl;
  auto strip = probe_.render(scene_with_post(1, R"(_Lut = "strip.png")"), lane, suite_backend(lane));
  ASSERT_FALSE(strip);
  EXPECT_EQ(strip.error().where.to_string(), (probe_.folder() / "probe.toml").string() + ":15:8");
  EXPECT_EQ(strip.error().message,
            "pass 'probe.probe': texture '_Lut': a LUT strip is N * N x N texels (Unity's is 1024 x 32), "
            "this image is 10x4");
  auto cube_file = probe_.render(scene_with_post(1, R"(_Lut = "bad.cube")"), lane, suite_backend(lane));
  ASSERT_FALSE(cube_file);
  EXPECT_EQ(cube_file.error().where.to_string(), (probe_.folder() / "bad.cube").string() + ":2:5");
  probe_.write("probe.hlsl",
               post_probe("Texture2D _Lut; SamplerState sampler_Lut;", "_Lut.SampleLevel(sampler_Lut, 0.5, 0)"));
  auto shape = probe_.render(scene_with_post(1, R"(_Lut = "environment")"), lane, suite_backend(lane));
  ASSERT_FALSE(shape);
  EXPECT_EQ(shape.error().where.to_string(), (probe_.folder() / "probe.toml").string() + ":15:8");
  EXPECT_EQ(shape.error().message,
            "pass 'probe.probe': texture '_Lut': the environment is a cube map; the shader declares a Texture2D");
}

}  // namespace
}  // namespace xshade::tests
