// A scene's Unity platform (docs/unity.md): under GLCore the targets keep OpenGL's rows, bottom
// first; under D3D11 the renderer reverses depth and draws its targets upside down as Unity does.
// A shader that follows Unity's conventions (reads depth through _ZBufferParams, flips a
// triangle's uv where UNITY_UV_STARTS_AT_TOP says so) draws the same picture on both, on every
// lane; one that ignores them does not, which is what the platform is for: a shader that would
// break in a D3D11 player build breaks here.
#include <string>

#include <gtest/gtest.h>

#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::FloatImage;
using harness::Lane;

// A plane tilted away from the camera so that depth changes down the image, in a material whose
// colour is its uv (red across, green along; UnityCG's vert_img draws any mesh): every row and
// column reads differently. Cull Back,
// Unity's default: a platform that turned faces over without turning the culling round would
// draw nothing.
const std::string kSurface = std::string(R"(Shader "Probe/Surface" { SubShader { Pass {
  HLSLPROGRAM
  #pragma vertex vert_img
  #pragma fragment frag)") + kUnityBlitVertexFunctions +
                             R"(
  float4 frag(Blit i) : SV_Target { return float4(i.uv, 0.0, 1.0); }
  ENDHLSL } } })";

// Each pass reads the scene's colour and depth at its uv: red and green the colour, blue the
// depth made linear through _ZBufferParams (UnityCG's Linear01Depth), alpha the depth as stored.
// "Blit" draws Graphics.Blit's quad through the matrices (vert_img); "Triangle" puts the
// triangle's corners where they are and flips uv where UNITY_UV_STARTS_AT_TOP is defined (Post
// Processing v2's VertDefault); "Naive" does not flip.
const std::string kEffect = std::string(R"(Shader "Probe/Conventions" {
  SubShader {
    Cull Off ZWrite Off ZTest Always
    HLSLINCLUDE
    // What HLSLSupport.cginc defines for the platform.
    #if defined(SHADER_API_D3D11) || defined(SHADER_API_VULKAN)
    #define UNITY_UV_STARTS_AT_TOP 1
    #endif
    float4 _ZBufferParams;
    Texture2D _MainTex;
    SamplerState sampler_MainTex;
    Texture2D _CameraDepthTexture;
    SamplerState sampler_CameraDepthTexture;)") +
                            kUnityBlitVertexFunctions + R"(
    Blit vert_naive(float4 vertex : POSITION) {
      Blit o;
      o.pos = float4(vertex.xy, 0.0, 1.0);
      o.uv = (vertex.xy + 1.0) * 0.5;
      return o;
    }
    float4 probe(Blit i) : SV_Target {
      const float depth = _CameraDepthTexture.Sample(sampler_CameraDepthTexture, i.uv).r;
      return float4(_MainTex.Sample(sampler_MainTex, i.uv).rg, 1.0 / (_ZBufferParams.x * depth + _ZBufferParams.y), depth);
    }
    ENDHLSL
    Pass { Name "Blit" HLSLPROGRAM
      #pragma vertex vert_img
      #pragma fragment probe
      ENDHLSL }
    Pass { Name "Triangle" HLSLPROGRAM
      #pragma vertex vert_triangle
      #pragma fragment probe
      ENDHLSL }
    Pass { Name "Naive" HLSLPROGRAM
      #pragma vertex vert_naive
      #pragma fragment probe
      ENDHLSL }
  }
})";

constexpr uint32_t kPictureWidth = 16, kPictureHeight = 8;

std::string platform_scene(const std::string& platform, const std::string& pass) {
  return probe_scene_head("a Unity platform's conventions", kPictureWidth, kPictureHeight) + "[unity]\nplatform = \"" +
         platform +
         "\"\n[[object]]\nmesh = \"plane\"\nmaterial = \"surface.shader\"\nrotation = [60, 0, 0]\nscale = [8, 1, 8]\n"
         "[[post]]\neffect = \"conventions.shader\"\npasses = [\"" +
         pass + "\"]\n";
}

class UnityPlatform : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void SetUp() override {
    probe_.write("surface.shader", kSurface);
    probe_.write("conventions.shader", kEffect);
  }
  void TearDown() override { expect_no_driver_messages(); }

  FloatImage render(Lane lane, const std::string& platform, const std::string& pass) {
    auto image = probe_.render(platform_scene(platform, pass), lane, suite_backend(lane));
    EXPECT_TRUE(image) << platform << " " << pass << ": " << image.error().to_string();
    return image ? *image : FloatImage(kPictureWidth, kPictureHeight);
  }

  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(UnityPlatform, D3D11ReversesDepthAndFlipsTargetsAndAShaderThatFollowsItDrawsTheSamePicture) {
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    const FloatImage glcore = render(lane, "glcore", "Blit");
    const FloatImage d3d11 = render(lane, "d3d11", "Blit");
    const FloatImage triangle = render(lane, "d3d11", "Triangle");
    const FloatImage naive = render(lane, "d3d11", "Naive");
    // Under GLCore the triangle's uv needs no flip (UNITY_UV_STARTS_AT_TOP is undefined there):
    // OpenGL's rows start at the bottom, where clip y is -1.
    const FloatImage glcore_triangle = render(lane, "glcore", "Triangle");
    for (uint32_t y = 0; y < kPictureHeight; ++y)
      for (uint32_t x = 0; x < kPictureWidth; ++x) {
        const glm::vec4 g = glcore.at(x, y), d = d3d11.at(x, y);
        ASSERT_GT(g.a, 0.0f) << "the plane covers pixel " << x << ", " << y;
        // The same surface at the same place: the flip mirrors where the rasterizer samples, and
        // the samples of mirrored pixel centres are the same points, so only rounding differs.
        EXPECT_NEAR(d.r, g.r, 1e-4f) << x << ", " << y;
        EXPECT_NEAR(d.g, g.g, 1e-4f) << x << ", " << y;
        // Depth as stored is reversed: 1 - d, to the rounding of a float depth buffer near 1.
        EXPECT_NEAR(d.a, 1.0f - g.a, 1e-5f) << x << ", " << y;
        // Made linear through _ZBufferParams it is the same distance: the forward buffer's depth
        // near 1 keeps about 1e-7 of it, which the linearisation (far / near = 100) makes 1e-5 of
        // the distance; 1e-4 is ten times that.
        EXPECT_NEAR(d.b, g.b, 1e-4f) << x << ", " << y;
        // Post Processing v2's triangle, flipped as UNITY_UV_STARTS_AT_TOP says, reads what the
        // blit reads; without the flip it reads the image upside down.
        EXPECT_NEAR(triangle.at(x, y).g, d.g, 1e-4f) << x << ", " << y;
        EXPECT_NEAR(naive.at(x, y).g, d3d11.at(x, kPictureHeight - 1 - y).g, 1e-4f) << x << ", " << y;
        EXPECT_NEAR(glcore_triangle.at(x, y).g, g.g, 1e-4f) << x << ", " << y;
      }
    // The picture is upright: the plane's far edge (the top of the image) is deeper.
    EXPECT_GT(glcore.at(0, 0).b, glcore.at(0, kPictureHeight - 1).b);
  }
}

}  // namespace
}  // namespace xshade::tests
