// SV_ClipDistance and SV_CullDistance drawn on every lane (docs/hlsl_like.md, "System values"):
// a vertex stage's distances clip and cull where Direct3D and Vulkan say, and the fragment stage
// reads the clip distance interpolated.
#include <string>

#include <gtest/gtest.h>

#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::FloatImage;
using harness::Lane;

constexpr uint32_t kClipWidth = 8, kClipHeight = 2;

// A plane that covers the target (its uv is its clip position), clipped where uv.x < 0.5 by the
// first distance; the second component (1) never clips. The red channel is the distance the
// fragment receives, green its second component.
constexpr const char* kClippedMaterial = R"(#pragma vertex vert
#pragma fragment frag
struct Varyings {
  float4 position : SV_Position;
  float2 clip : SV_ClipDistance0;
};
Varyings vert(float2 uv : TEXCOORD0) {
  Varyings o;
  o.position = float4(uv * 2.0 - 1.0, 0.5, 1.0);
  o.clip = float2(uv.x - 0.5, 1.0);
  return o;
}
float4 frag(Varyings i) : SV_Target { return float4(i.clip.x, i.clip.y, 0.0, 1.0); }
)";

// The same plane with a cull distance below zero at every vertex: every primitive is dropped.
constexpr const char* kCulledMaterial = R"(#pragma vertex vert
#pragma fragment frag
struct Varyings {
  float4 position : SV_Position;
  float cull : SV_CullDistance0;
};
Varyings vert(float2 uv : TEXCOORD0) {
  Varyings o;
  o.position = float4(uv * 2.0 - 1.0, 0.5, 1.0);
  o.cull = -1.0;
  return o;
}
float4 frag(Varyings i) : SV_Target { return float4(1.0, 1.0, 1.0, 1.0); }
)";

std::string clip_scene(const std::string& material) {
  return probe_scene_head("clip and cull distances", kClipWidth, kClipHeight) +
         "[[object]]\nmesh = \"plane\"\nmaterial = \"" + material + "\"\n";
}

class ClipDistances : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void SetUp() override {
    probe_.write("clipped.hlsl", kClippedMaterial);
    probe_.write("culled.hlsl", kCulledMaterial);
  }
  void TearDown() override { expect_no_driver_messages(); }
  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(ClipDistances, AVertexStagesDistancesClipAndCullOnEveryLane) {
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto clipped = probe_.render(clip_scene("clipped.hlsl"), lane, suite_backend(lane));
    ASSERT_TRUE(clipped) << clipped.error().to_string();
    auto culled = probe_.render(clip_scene("culled.hlsl"), lane, suite_backend(lane));
    ASSERT_TRUE(culled) << culled.error().to_string();
    const glm::vec4 background = culled->at(0, 0);
    for (uint32_t y = 0; y < kClipHeight; ++y)
      for (uint32_t x = 0; x < kClipWidth; ++x) {
        EXPECT_EQ(culled->at(x, y), background) << "culled everywhere: " << x << "," << y;
        const glm::vec4 got = clipped->at(x, y);
        const float distance = (static_cast<float>(x) + 0.5f) / kClipWidth - 0.5f;
        if (distance < 0.0f) {
          EXPECT_EQ(got, background) << "clipped: " << x << "," << y;
        } else {
          // Interpolated across the plane: float32 rounding of a linear ramp.
          EXPECT_NEAR(got.r, distance, 1e-5f) << x << "," << y;
          EXPECT_FLOAT_EQ(got.g, 1.0f) << x << "," << y;
        }
      }
    EXPECT_NE(background.g, 1.0f) << "the background differs from the drawn plane";
  }
}

}  // namespace
}  // namespace xshade::tests
