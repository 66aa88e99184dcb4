// Half-precision emulation on the lanes that can do it: a half result past 65504 overflows to
// infinity, 1/3 (a file-scope constant) keeps fp16's 11 significant bits and 2048 + 1 in a
// compound assignment stays 2048, as fp16 hardware would compute them, while the same shader
// without emulation computes in fp32 (what CPU drivers do with half).
#include <cmath>

#include <gtest/gtest.h>

#include "harness/render/evaluate.h"
#include "hlsl_like/compiler.h"

namespace xshade::tests {
namespace {

constexpr const char* kShader = R"(
#pragma fragment frag
float _One = 1.0;
static const half kThird = 0.33333333;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  half big = 65504.0;
  half over = big * (half)_One * 2.0;  // past fp16's largest finite value
  half third = (half)_One * kThird;
  float exact = _One / 3.0;            // float stays float
  half sum = 2048.0 * (half)_One;
  sum += (half)_One;                   // fp16 numbers are 2 apart at 2048: the tie rounds to even
  return float4(over, third, exact, sum);
}
)";

// fp16's nearest value to 1/3: 0x3555 = 1365/4096.
constexpr float kThirdInHalf = 1365.0f / 4096.0f;

harness::FloatImage evaluate_on(harness::Lane lane, bool half_emulation) {
  auto module = hlsl::compile_text("half.hlsl", kShader, {});
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto backend = harness::create_backend(lane);
  EXPECT_TRUE(backend) << backend.error().to_string();
  if (!backend) return {};
  auto image = harness::evaluate(*module, lane, **backend, 1, 1, {}, {.half_emulation = half_emulation});
  EXPECT_TRUE(image) << image.error().to_string();
  return image ? *image : harness::FloatImage{};
}

class HalfEmulation : public ::testing::TestWithParam<harness::Lane> {};

TEST_P(HalfEmulation, RoundsHalfResultsToFp16) {
  const harness::FloatImage image = evaluate_on(GetParam(), true);
  ASSERT_EQ(image.width, 1u);
  const glm::vec4 p = image.at(0, 0);
  EXPECT_TRUE(std::isinf(p.r) && p.r > 0) << p.r;
  EXPECT_EQ(p.g, kThirdInHalf);
  EXPECT_EQ(p.b, 1.0f / 3.0f);
  EXPECT_EQ(p.a, 2048.0f);
}

TEST_P(HalfEmulation, WithoutItHalfIsFp32) {
  const harness::FloatImage image = evaluate_on(GetParam(), false);
  ASSERT_EQ(image.width, 1u);
  const glm::vec4 p = image.at(0, 0);
  EXPECT_EQ(p.r, 131008.0f);
  EXPECT_EQ(p.g, 1.0f / 3.0f);
  EXPECT_EQ(p.a, 2049.0f);
}

INSTANTIATE_TEST_SUITE_P(GlslLanes, HalfEmulation, ::testing::Values(harness::Lane::Gl, harness::Lane::Vk),
                         [](const ::testing::TestParamInfo<harness::Lane>& lane) {
                           return lane.param == harness::Lane::Gl ? std::string("gl") : std::string("vk");
                         });

TEST(HalfEmulation, TheVkHlslLaneSaysItCannot) {
  auto module = hlsl::compile_text("half.hlsl", kShader, {});
  auto program = harness::program_for_lane(*module, harness::Lane::VkHlsl, {.half_emulation = true});
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("cannot emulate half"), std::string::npos) << program.error().message;
}

}  // namespace
}  // namespace xshade::tests
