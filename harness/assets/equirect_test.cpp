#include "harness/assets/equirect.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace xshade::harness {
namespace {

// Float rounding of atan2/acos results near 1 and of the division by 2 pi.
constexpr float kUvTolerance = 1e-6f;

TEST(EquirectUv, AxesLandWhereTheConventionPutsThem) {
  EXPECT_NEAR(equirect_uv({0, 1, 0}).y, 0.0f, kUvTolerance);   // up: the top row
  EXPECT_NEAR(equirect_uv({0, -1, 0}).y, 1.0f, kUvTolerance);  // down: the bottom row
  EXPECT_NEAR(equirect_uv({0, 0, 1}).x, 0.5f, kUvTolerance);   // +z: the middle column
  EXPECT_NEAR(equirect_uv({0, 0, 1}).y, 0.5f, kUvTolerance);
  EXPECT_NEAR(equirect_uv({1, 0, 0}).x, 0.75f, kUvTolerance);
  EXPECT_NEAR(equirect_uv({-1, 0, 0}).x, 0.25f, kUvTolerance);
  EXPECT_NEAR(equirect_uv({0, 0, -1}).x, 1.0f, kUvTolerance);  // -z: the seam, u = 1 (= 0)
  EXPECT_NEAR(equirect_uv({0, 0, -1}).y, 0.5f, kUvTolerance);
}

TEST(EquirectUv, DirectionIsItsInverse) {
  for (float u = 0.05f; u < 1.0f; u += 0.1f)
    for (float v = 0.05f; v < 1.0f; v += 0.1f) {
      glm::vec3 d = equirect_direction({u, v});
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);  // float rounding of sin and cos
      glm::vec2 back = equirect_uv(d);
      EXPECT_NEAR(back.x, u, 1e-5f) << u << " " << v;  // float rounding through sin, cos, atan2
      EXPECT_NEAR(back.y, v, 1e-5f) << u << " " << v;
    }
}

TEST(EquirectTexelSolidAngle, TheWholeImageIsTheSphere) {
  double total = 0.0;
  for (uint32_t y = 0; y < 64; ++y) total += 128 * equirect_texel_solid_angle(y, 128, 64);
  EXPECT_NEAR(total, 4.0 * std::numbers::pi, 1e-9);  // double rounding over 64 rows
  // A texel at the equator is nearly a (2 pi / W) x (pi / H) rectangle.
  EXPECT_NEAR(equirect_texel_solid_angle(31, 128, 64), (2 * std::numbers::pi / 128) * (std::numbers::pi / 64), 1e-5);
}

TEST(SampleEquirect, WrapsAcrossTheSeamAndClampsAtThePoles) {
  FloatImage image(4, 2);
  for (uint32_t x = 0; x < 4; ++x) {
    image.set(x, 0, glm::vec4(float(x)));
    image.set(x, 1, glm::vec4(10.0f + float(x)));
  }
  // u = 0 lies halfway between the centres of the last and the first column.
  EXPECT_FLOAT_EQ(sample_equirect(image, {0.0f, 0.25f}).x, 1.5f);
  // Above the first row's centre the top row is repeated, not blended with the bottom one.
  EXPECT_FLOAT_EQ(sample_equirect(image, {0.125f, 0.0f}).x, 0.0f);
  EXPECT_FLOAT_EQ(sample_equirect(image, {0.125f, 0.5f}).x, 5.0f);
}

TEST(ResampleEquirect, ShrinkingAveragesTheTexelsUnderEachOutputTexel) {
  FloatImage image(8, 4);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 8; ++x) image.set(x, y, glm::vec4(float(x + 8 * y)));
  FloatImage half = resample_equirect(image, 4, 2);
  ASSERT_EQ(half.width, 4u);
  ASSERT_EQ(half.height, 2u);
  // Output (1, 1) covers source texels (2..3, 2..3): values 18, 19, 26, 27.
  EXPECT_FLOAT_EQ(half.at(1, 1).x, (18.0f + 19.0f + 26.0f + 27.0f) / 4.0f);
}

}  // namespace
}  // namespace xshade::harness
