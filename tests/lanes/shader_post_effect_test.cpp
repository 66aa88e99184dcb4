// A Unity .shader as a post effect (docs/unity.md): the passes the scene's `passes` names, blitted
// in that order on every lane, each into an image of its own that the next reads as _MainTex. The
// probe's three passes draw the full-screen triangle both ways Unity's code does (through the
// matrices, as Graphics.Blit's vert_img; and its corners as they are, as Post Processing v2's
// VertDefault), and a copy through the blit's uv must leave the image upright and whole.
#include <string>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"
#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::Lane;

const std::string kBlitProbe = std::string(R"(Shader "Hidden/BlitProbe" {
  SubShader {
    Cull Off ZWrite Off ZTest Always
    HLSLINCLUDE
    Texture2D _MainTex;
    SamplerState sampler_MainTex;
    float4 _MainTex_TexelSize;)") +
                               kUnityBlitVertexFunctions + R"(
    ENDHLSL
    Pass { Name "Gradient" HLSLPROGRAM
      #pragma vertex vert_img
      #pragma fragment frag
      float4 frag(Blit i) : SV_Target { return float4(i.pos.x / 8.0, i.pos.y / 4.0, 0.0, 1.0); }
      ENDHLSL }
    Pass { Name "Copy" HLSLPROGRAM
      #pragma vertex vert_img
      #pragma fragment frag
      float4 frag(Blit i) : SV_Target { return _MainTex.Sample(sampler_MainTex, i.uv); }
      ENDHLSL }
    Pass { Name "Invert" HLSLPROGRAM
      #pragma vertex vert_triangle
      #pragma fragment frag
      float4 frag(Blit i) : SV_Target {
        float4 c = _MainTex.Load(int3(i.pos.xy, 0));
        return float4(1.0 - c.rg, _MainTex_TexelSize.z / 8.0, 1.0);
      }
      ENDHLSL }
  }
})";

const std::string kScene = probe_scene_head("a .shader post effect's blits", 8, 4) + R"([[post]]
effect = "blit_probe.shader"
passes = ["Gradient", "copy", { pass = 2, name = "inverted" }]
)";

class ShaderPostEffect : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void TearDown() override { expect_no_driver_messages(); }
  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(ShaderPostEffect, ItsPassesBlitInTheScenesOrderAndACopyKeepsTheImageUpright) {
  probe_.write("blit_probe.shader", kBlitProbe);
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image = probe_.render(kScene, lane, suite_backend(lane));
    ASSERT_TRUE(image) << image.error().to_string();
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 8; ++x) {
        // Pixel centres of the gradient, sampled at texel centres by the copy (bilinear there is
        // the texel, to float rounding), inverted; blue is _MainTex_TexelSize.z, the width, / 8.
        // Unity's GLCore keeps OpenGL's rows, bottom first: SV_Position.y counts from the bottom
        // of the picture, as gl_FragCoord does.
        const float row_from_bottom = float(4 - 1 - y);
        const glm::vec4 expected{1.0f - (float(x) + 0.5f) / 8.0f, 1.0f - (row_from_bottom + 0.5f) / 4.0f, 1.0f, 1.0f};
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(image->at(x, y)[c], expected[c], 1e-5f) << "pixel " << x << ", " << y << " channel " << c;
      }
  }
}

}  // namespace
}  // namespace xshade::tests
