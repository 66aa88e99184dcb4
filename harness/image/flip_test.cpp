#include "harness/image/flip.h"

#include <gtest/gtest.h>

#include <glm/vec3.hpp>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace flip_test {

FloatImage flat(glm::vec3 srgb, uint32_t size = 24) {
  FloatImage image(size, size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x)
      image.set(x, y, {srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b), 1.0f});
  return image;
}

TEST(Flip, TheDefaultViewingDistanceIsTheReferenceImplementations) {
  // 0.7 m from a 0.7 m wide monitor 3840 pixels across (FLIP.h's calculatePPD defaults): 67.02.
  EXPECT_NEAR(flip_default_pixels_per_degree(), 67.0206, 1e-4);
}

TEST(Flip, FlatImagesGiveTheirColoursRedistributedDifference) {
  // On flat images the contrast filters (gain 1) change nothing and the feature filters find no
  // edge, so every pixel is the colour term alone: HyAB of the Hunt-adjusted CIELAB colours,
  // raised to 0.7 and redistributed (Andersson et al. 2020, eq. 2-4). The expected values are that
  // closed form worked in double from FLIP.h's constants (NVlabs/flip, src/cpp/FLIP.h at 8144bd5);
  // green against blue is 1 by the definition of the largest difference. The reference pairs the
  // FLIP repository tests with (images/reference.png against test.png, mean 0.159691) are image
  // files outside this project. 2e-4: float arithmetic, as FLIP.h's, and the feature filters'
  // rounding residue on a flat image (the square root of about 1e-8).
  const struct {
    glm::vec3 reference, test;
    double expected;
  } cases[] = {
      {{0, 0, 0}, {1, 1, 1}, 0.967380},
      {{0, 0, 0}, {0.5f, 0.5f, 0.5f}, 0.931496},
      {{0.5f, 0.5f, 0.5f}, {0.6f, 0.6f, 0.6f}, 0.285013},
      {{1, 0, 0}, {0, 1, 0}, 0.986662},
      {{0, 1, 0}, {0, 0, 1}, 1.0},
      {{1, 1, 1}, {1, 1, 0}, 0.966308},
      {{0.2f, 0.4f, 0.6f}, {0.2f, 0.4f, 0.65f}, 0.158860},
  };
  for (const auto& c : cases) {
    const FlipMeasure measure = measure_flip(flat(c.test), flat(c.reference), flip_default_pixels_per_degree());
    EXPECT_NEAR(measure.mean, c.expected, 2e-4) << c.reference.r << " " << c.test.r;
    EXPECT_NEAR(measure.min, c.expected, 2e-4);
    EXPECT_NEAR(measure.max, c.expected, 2e-4);
  }
}

TEST(Flip, IdenticalImagesAreZeroEverywhere) {
  FloatImage image(20, 16);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 20; ++x) image.set(x, y, {float(x) / 20.0f, float(y) / 16.0f, 0.5f, 1.0f});
  const FlipMeasure measure = measure_flip(image, image, flip_default_pixels_per_degree());
  EXPECT_EQ(measure.max, 0.0);
  EXPECT_EQ(measure.mean, 0.0);
  const FlipMeasure hdr = measure_hdr_flip(image, image, flip_default_pixels_per_degree());
  EXPECT_EQ(hdr.max, 0.0);
  EXPECT_TRUE(hdr.hdr);
}

TEST(Flip, AMovedEdgeIsSeenWhereItMovedAndFeaturesRaiseIt) {
  // A vertical edge at x = 16 in one image and x = 17 in the other.
  FloatImage reference(32, 32), test(32, 32);
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 32; ++x) {
      reference.set(x, y, glm::vec4(x < 16 ? 0.05f : 0.8f, x < 16 ? 0.05f : 0.8f, x < 16 ? 0.05f : 0.8f, 1.0f));
      test.set(x, y, glm::vec4(x < 17 ? 0.05f : 0.8f, x < 17 ? 0.05f : 0.8f, x < 17 ? 0.05f : 0.8f, 1.0f));
    }
  const FlipMeasure measure = measure_flip(test, reference, flip_default_pixels_per_degree());
  EXPECT_GT(measure.max, 0.1);
  EXPECT_GE(measure.max_x, 14u);
  EXPECT_LE(measure.max_x, 18u);
  EXPECT_LT(measure.per_pixel[size_t(16) * 32 + 0], measure.max / 4);  // far from the edge
  // The weighted percentiles are ordered and within the values.
  EXPECT_LE(measure.min, measure.weighted_first_quartile);
  EXPECT_LE(measure.weighted_first_quartile, measure.weighted_median);
  EXPECT_LE(measure.weighted_median, measure.weighted_third_quartile);
  EXPECT_LE(measure.weighted_third_quartile, measure.max);
}

TEST(Flip, HdrFlipSeesADifferenceAboveOneThatLdrFlipClampsAway) {
  FloatImage reference(24, 24), test(24, 24);
  for (uint32_t y = 0; y < 24; ++y)
    for (uint32_t x = 0; x < 24; ++x) {
      const float base = x < 12 ? 0.1f : 0.3f;
      reference.set(x, y, {base, base, base, 1.0f});
      test.set(x, y, {base, base, base, 1.0f});
    }
  reference.set(5, 5, {4.0f, 4.0f, 4.0f, 1.0f});
  test.set(5, 5, {16.0f, 16.0f, 16.0f, 1.0f});  // both white on a display
  EXPECT_EQ(measure_flip(test, reference, flip_default_pixels_per_degree()).max, 0.0);
  const FlipMeasure hdr = measure_hdr_flip(test, reference, flip_default_pixels_per_degree());
  EXPECT_GT(hdr.max, 0.05);
  EXPECT_EQ(hdr.max_x, 5u);
  EXPECT_GE(hdr.exposures, 2u);
  EXPECT_LT(hdr.start_exposure, hdr.stop_exposure);
}

}  // namespace flip_test
}  // namespace xshade::harness
