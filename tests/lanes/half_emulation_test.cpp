// Half-precision emulation on the lanes that can do it: a half result past 65504 overflows to
// infinity, 1/3 (a file-scope constant) keeps fp16's 11 significant bits and 2048 + 1 in a
// compound assignment stays 2048, as fp16 hardware would compute them, while the same shader
// without emulation computes in fp32 (what CPU drivers do with half). And the emulation's
// rounding is the driver's own float-to-fp16 conversion, value for value, at every exponent.
#include <bit>
#include <cmath>
#include <cstdint>

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

// `shader` evaluated for one pixel on `lane`.
harness::FloatImage evaluate_on(harness::Lane lane, bool half_emulation, const char* shader = kShader) {
  auto module = hlsl::compile_text("half.hlsl", shader, {});
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

// ++ and -- write a new half value, and so does a float added in place to a half: each is
// rounded as it is stored. At 2048 fp16's numbers are 2 apart, so 2048 + 1 is a tie that rounds
// to even, 2048; post-increment's value is the old one.
constexpr const char* kInPlaceShader = R"(
#pragma fragment frag
float _One = 1.0;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  half pre = 2048.0 * (half)_One;
  ++pre;
  half post = 2048.0 * (half)_One;
  half old = post++;
  half added = 2048.0 * (half)_One;
  added += _One;
  half down = -2048.0 * (half)_One;
  for (int i = 0; i < 1; i++) down--;
  return float4(pre, old + post - 2048.0, added, down);
}
)";

glm::vec4 in_place_on(harness::Lane lane, bool half_emulation) {
  const harness::FloatImage image = evaluate_on(lane, half_emulation, kInPlaceShader);
  return image.width == 1 ? image.at(0, 0) : glm::vec4(0.0f);
}

TEST_P(HalfEmulation, IncrementsAndAFloatAddedInPlaceAreRoundedAsTheyAreStored) {
  EXPECT_EQ(in_place_on(GetParam(), true), glm::vec4(2048.0f, 2048.0f, 2048.0f, -2048.0f));
  EXPECT_EQ(in_place_on(GetParam(), false), glm::vec4(2049.0f, 2049.0f, 2049.0f, -2049.0f));
}

INSTANTIATE_TEST_SUITE_P(GlslLanes, HalfEmulation, ::testing::Values(harness::Lane::Gl, harness::Lane::Vk),
                         [](const ::testing::TestParamInfo<harness::Lane>& lane) {
                           return lane.param == harness::Lane::Gl ? std::string("gl") : std::string("vk");
                         });

// Each pixel (x, y) of 256 x 256 gives a float's top 16 bits, i = 256 y + x: its sign, its whole
// exponent and 7 bits of mantissa; the columns of an 8-wide row of such squares give its low 16
// bits: exact in fp16, the tie below a kept bit that is even or odd (0x1000, 0xf000; with i = 0x477f
// the latter is 65520, halfway from fp16's largest number to infinity), the ties of fp16's
// subnormals (0x2000, 0x8000, where fewer bits are kept), one below and one above a tie,
// and a hash. Red is the emulated (half)x, green f16tof32(f32tof16(x)): the driver's conversion.
constexpr const char* kEveryExponentShader = R"(
#pragma fragment frag
static const uint kLowBits[8] = {0x0000, 0x1000, 0xf000, 0x2000, 0x8000, 0x0fff, 0x1001, 0};
float4 frag(float4 position : SV_Position) : SV_Target {
  uint x = (uint)position.x;
  uint y = (uint)position.y;
  uint i = (y << 8) | (x & 255);
  uint low = (x >> 8) == 7 ? ((i * 2654435761u) >> 16) : kLowBits[x >> 8];
  float value = asfloat((i << 16) | low);
  half emulated = (half)value;
  return float4((float)emulated, f16tof32(f32tof16(value)), value, 1.0);
}
)";

TEST_P(HalfEmulation, RoundsAsTheDriversOwnConversionAtEveryExponent) {
  auto module = hlsl::compile_text("every_exponent.hlsl", kEveryExponentShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto backend = harness::create_backend(GetParam());
  ASSERT_TRUE(backend) << backend.error().to_string();
  auto image = harness::evaluate(*module, GetParam(), **backend, 8 * 256, 256, {}, {.half_emulation = true});
  ASSERT_TRUE(image) << image.error().to_string();
  uint32_t differing = 0;
  for (uint32_t y = 0; y < image->height; ++y)
    for (uint32_t x = 0; x < image->width; ++x) {
      const glm::vec4 p = image->at(x, y);
      const bool same =
          std::bit_cast<uint32_t>(p.r) == std::bit_cast<uint32_t>(p.g) || (std::isnan(p.r) && std::isnan(p.g));
      if (!same && ++differing <= 5)
        ADD_FAILURE() << "(half)" << std::hexfloat << p.b << " is " << p.r << ", the driver's conversion gives " << p.g;
    }
  EXPECT_EQ(differing, 0u) << "of " << image->width * image->height << " values";
}

TEST(HalfEmulation, TheVkHlslLaneSaysItCannot) {
  auto module = hlsl::compile_text("half.hlsl", kShader, {});
  auto program = harness::program_for_lane(*module, harness::Lane::VkHlsl, {.half_emulation = true});
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("cannot emulate half"), std::string::npos) << program.error().message;
}

}  // namespace
}  // namespace xshade::tests
