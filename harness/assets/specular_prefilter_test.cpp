#include "harness/assets/specular_prefilter.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "harness/assets/equirect.h"

namespace xshade::harness {
namespace {

FloatImage constant_image(float value) {
  FloatImage image(kPrefilteredWidth, kPrefilteredHeight);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) image.set(x, y, {value, 2 * value, 3 * value, 1});
  return image;
}

// The mean over the sphere, each texel weighted by its solid angle.
double sphere_mean(const FloatImage& image) {
  double sum = 0.0;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      sum += image.at(x, y).x * equirect_texel_solid_angle(y, image.width, image.height);
  return sum / (4.0 * std::numbers::pi);
}

TEST(PrefilteredMip, FollowsUnitysRoughnessMapping) {
  EXPECT_FLOAT_EQ(prefiltered_mip_for_roughness(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(prefiltered_mip_for_roughness(1.0f), 6.0f);
  EXPECT_FLOAT_EQ(prefiltered_mip_for_roughness(0.5f), 0.5f * 1.35f * 6.0f);
  for (float level = 0.0f; level <= 6.0f; level += 0.5f)
    EXPECT_NEAR(prefiltered_mip_for_roughness(prefiltered_roughness_for_mip(level)), level, 1e-5f);  // float rounding
}

TEST(PrefilterSpecular, HasSevenLevelsOfHalvingSize) {
  TextureData texture = prefilter_specular(constant_image(1.0f));
  EXPECT_EQ(texture.format, TextureFormat::Rgba32Float);
  EXPECT_EQ(texture.width, 256u);
  EXPECT_EQ(texture.height, 128u);
  ASSERT_EQ(texture.levels.size(), 7u);
  for (uint32_t i = 0; i < 7; ++i)
    EXPECT_EQ(texture.levels[i].size(), size_t(256 >> i) * (128 >> i) * 16) << "level " << i;
}

TEST(PrefilterSpecular, ConstantEnvironmentStaysConstantAtEveryLevel) {
  TextureData texture = prefilter_specular(constant_image(0.7f));
  for (uint32_t i = 0; i < kPrefilteredLevels; ++i) {
    FloatImage level = prefiltered_level(texture, i);
    for (uint32_t y = 0; y < level.height; ++y)
      for (uint32_t x = 0; x < level.width; ++x) {
        glm::vec4 value = level.at(x, y);
        // Normalised weighted sums of equal values: float rounding only.
        EXPECT_NEAR(value.x, 0.7f, 1e-6f) << "level " << i << " texel " << x << "," << y;
        EXPECT_NEAR(value.z, 2.1f, 3e-6f) << "level " << i << " texel " << x << "," << y;
        EXPECT_EQ(value.w, 1.0f);
      }
  }
}

// A small bright cap (0.15 radians across) on a black environment.
struct BrightCap {
  FloatImage image{kPrefilteredWidth, kPrefilteredHeight};
  glm::vec3 direction = glm::normalize(glm::vec3(0.6f, 0.3f, -0.4f));
  BrightCap() {
    for (uint32_t y = 0; y < image.height; ++y)
      for (uint32_t x = 0; x < image.width; ++x)
        if (glm::dot(equirect_texel_direction(x, y, image.width, image.height), direction) > std::cos(0.15f))
          image.set(x, y, {100.0f, 0, 0, 1});
  }
};

double ggx(double alpha, double n_dot_h) {
  double a2 = alpha * alpha;
  double denominator = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (std::numbers::pi * denominator * denominator);
}

// The split-sum prefilter by brute force over every source texel: the integral of
// L(l) D(n.h) (n.l) divided by the integral of D(n.h) (n.l), both over l with n.l > 0.
double reference_prefilter(const FloatImage& source, glm::dvec3 n, double alpha) {
  double sum = 0.0, weight_sum = 0.0;
  for (uint32_t y = 0; y < source.height; ++y) {
    const double solid_angle = equirect_texel_solid_angle(y, source.width, source.height);
    for (uint32_t x = 0; x < source.width; ++x) {
      glm::dvec3 l = equirect_texel_direction(x, y, source.width, source.height);
      double n_dot_l = glm::dot(n, l);
      if (n_dot_l <= 0.0) continue;
      double weight = ggx(alpha, glm::dot(n, glm::normalize(n + l))) * n_dot_l * solid_angle;
      sum += weight * source.at(x, y).x;
      weight_sum += weight;
    }
  }
  return sum / weight_sum;
}

TEST(PrefilterSpecular, KeepsTheEnvironmentsPowerAndWidensItsLobeLevelByLevel) {
  BrightCap bright;
  TextureData texture = prefilter_specular(bright.image);
  const double source_mean = sphere_mean(bright.image);
  double previous_spread = 0.0;
  for (uint32_t i = 0; i < kPrefilteredLevels; ++i) {
    FloatImage level = prefiltered_level(texture, i);
    // The kernel depends only on the angle between n and l, so it integrates to 1 over n as over
    // l: the mean over the sphere is unchanged. Each texel holds the value at its centre, so the
    // mean is a midpoint rule on the level's grid; 3% covers it down to level 5 (8 x 4 texels
    // under a lobe about a radian wide). Level 6's 4 x 2 grid is too coarse to measure it.
    if (i < kPrefilteredLevels - 1) {
      EXPECT_NEAR(sphere_mean(level), source_mean, 0.03 * source_mean) << "level " << i;
    }
    // The mean angle between the bright direction and where its light landed.
    double spread = 0.0, total = 0.0;
    for (uint32_t y = 0; y < level.height; ++y)
      for (uint32_t x = 0; x < level.width; ++x) {
        double weight = level.at(x, y).x * equirect_texel_solid_angle(y, level.width, level.height);
        double cosine = glm::dot(equirect_texel_direction(x, y, level.width, level.height), bright.direction);
        spread += weight * std::acos(std::clamp(cosine, -1.0, 1.0));
        total += weight;
      }
    spread /= total;
    if (i > 0) {
      EXPECT_GT(spread, previous_spread) << "level " << i;
    }
    previous_spread = spread;
  }
}

TEST(PrefilterSpecular, LevelsFollowTheGgxKernel) {
  BrightCap bright;
  TextureData texture = prefilter_specular(bright.image);
  for (uint32_t i : {3u, 4u, 6u}) {
    const double alpha = prefiltered_roughness_for_mip(float(i));
    FloatImage level = prefiltered_level(texture, i);
    const double peak = reference_prefilter(bright.image, glm::dvec3(bright.direction), alpha);
    for (uint32_t y = 0; y < level.height; ++y)
      for (uint32_t x = 0; x < level.width; ++x) {
        glm::dvec3 n = equirect_texel_direction(x, y, level.width, level.height);
        double expected = reference_prefilter(bright.image, n, alpha);
        // Filtered importance sampling reads each of its 256 samples from a mip level one step
        // coarser than the sample's share of the lobe, which blurs the lobe a little beyond
        // GGX; 15% of the peak bounds that blur for a source this small.
        EXPECT_NEAR(level.at(x, y).x, expected, 0.15 * peak) << "level " << i << " texel " << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace xshade::harness
