// What the shared full-screen triangle feeds a fragment shader that has no vertex stage
// (docs/hlsl_like.md, "Full-screen passes"), read back on every lane: uv in a float vector, 0 in
// an integer, the identity in a float matrix (each element of an array alike).
#include <gtest/gtest.h>

#include "harness/render/evaluate.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

// Vulkan-Samples passes a view and a projection down as varyings; fed the identity, each
// product leaves its vector as it was, so the image is (u, v, 0.25 + i, 1) with i the integer.
constexpr const char* kFedInputsSource = R"(
#pragma fragment f
struct Fed {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
  [[vk::location(2)]] float4x4 view : MATRIX0;
  float3x4 rows[2] : MATRIX1;
  nointerpolation int i : INDEX0;
};
float4 f(Fed input) : SV_Target {
  float4 v = float4(input.uv, 0.25 + input.i, 1.0);
  return mul(input.rows[1], mul(input.view, v)).xyzz * float4(1, 1, 1, 0) + float4(0, 0, 0, 1);
}
)";

class FullscreenInputs : public LaneTest {};

TEST_F(FullscreenInputs, UvVectorsZeroIntegersAndIdentityMatricesOnEveryLane) {
  constexpr uint32_t kSize = 4;
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto module = hlsl::compile_text("fed.hlsl", kFedInputsSource, {});
    ASSERT_TRUE(module->ok());
    auto image = harness::evaluate(*module, lane, backend(lane), kSize, kSize);
    ASSERT_TRUE(image) << image.error().to_string();
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x) {
        // uv at the pixel's centre, (0,0) at the top-left.
        const glm::vec4 got = image->at(x, y);
        EXPECT_NEAR(got.x, (static_cast<float>(x) + 0.5f) / kSize, 1e-6f) << x << "," << y;
        EXPECT_NEAR(got.y, (static_cast<float>(y) + 0.5f) / kSize, 1e-6f) << x << "," << y;
        EXPECT_FLOAT_EQ(got.z, 0.25f) << x << "," << y;
        EXPECT_FLOAT_EQ(got.w, 1.0f) << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace xshade::tests
