#include "harness/image/srgb8_encoder.h"

#include <bit>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

TEST(Srgb8Encoder, EachCodeStartsExactlyWhereLinearToSrgb8ReachesIt) {
  EXPECT_EQ(srgb8_code_start(0), 0.0f);
  for (int code = 1; code < 256; ++code) {
    const float start = srgb8_code_start(uint8_t(code));
    const float before = std::nextafter(start, 0.0f);
    EXPECT_EQ(linear_to_srgb8(start), code) << code;
    EXPECT_EQ(linear_to_srgb8(before), code - 1) << code;
    EXPECT_EQ(linear_to_srgb8_by_table(start), code) << code;
    EXPECT_EQ(linear_to_srgb8_by_table(before), code - 1) << code;
  }
}

TEST(Srgb8Encoder, AgreesWithLinearToSrgb8AcrossTheUnitInterval) {
  // Every 997th float in (0, 1): about a million values spread over every exponent, which also
  // checks that linear_to_srgb8 never decreases, the table's premise. 997 is prime so that the
  // samples do not fall on a pattern of mantissa bits.
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  uint8_t previous = 0;
  for (uint32_t bits = 1; bits < one; bits += 997) {
    const float value = std::bit_cast<float>(bits);
    const uint8_t code = linear_to_srgb8(value);
    ASSERT_EQ(linear_to_srgb8_by_table(value), code) << value;
    ASSERT_GE(code, previous) << value;
    previous = code;
  }
}

TEST(Srgb8Encoder, AgreesOnDecodedCodesAndOutOfRangeValues) {
  for (int code = 0; code < 256; ++code)
    EXPECT_EQ(linear_to_srgb8_by_table(srgb8_to_linear(uint8_t(code))), code) << code;
  const float inf = std::numeric_limits<float>::infinity();
  for (float value : {-inf, -1.0f, -0.0f, 0.0f, 1.0f, 1.5f, inf, std::numeric_limits<float>::quiet_NaN()})
    EXPECT_EQ(linear_to_srgb8_by_table(value), linear_to_srgb8(value)) << value;
}

}  // namespace
}  // namespace xshade::harness
