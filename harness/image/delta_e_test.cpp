#include "harness/image/delta_e.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xshade::harness {
namespace delta_e_test {

struct SharmaPair {
  Lab first;
  Lab second;
  double delta_e;
};

// The 34 pairs of Sharma, Wu and Dalal, "The CIEDE2000 color-difference formula: implementation
// notes, supplementary test data, and mathematical observations", Color Research & Application
// 30(1), 2005, Table 1: L*a*b* of each colour and the published difference, to four decimals.
// They test the hue's wrap past 0 and 360 degrees (13-15), a hue difference of exactly 180
// degrees (9, 10), a colour without chroma (7, 8) and the blue region's rotation term (19).
const SharmaPair kSharmaPairs[] = {
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},
    {{50.0000, -1.0000, 2.0000}, {50.0000, 0.0000, 0.0000}, 2.3669},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0009}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0010}, 7.1792},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0011}, 7.2195},
    {{50.0000, 2.4900, -0.0010}, {50.0000, -2.4900, 0.0012}, 7.2195},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0009, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0010, -2.4900}, 4.8045},
    {{50.0000, -0.0010, 2.4900}, {50.0000, 0.0011, -2.4900}, 4.7461},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 0.0000, -2.5000}, 4.3065},
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.1736, 0.5854}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2972, 0.0000}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 1.8634, 0.5757}, 1.0000},
    {{50.0000, 2.5000, 0.0000}, {50.0000, 3.2592, 0.3350}, 1.0000},
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644},
    {{63.0109, -31.0961, -5.8663}, {62.8187, -29.7946, -4.0864}, 1.2630},
    {{61.2901, 3.7196, -5.3901}, {61.4292, 2.2480, -4.9620}, 1.8731},
    {{35.0831, -44.1164, 3.7933}, {35.0232, -40.0716, 1.5901}, 1.8645},
    {{22.7233, 20.0904, -46.6940}, {23.0331, 14.9730, -42.5619}, 2.0373},
    {{36.4612, 47.8580, 18.3852}, {36.2715, 50.5065, 21.2231}, 1.4146},
    {{90.8027, -2.0831, 1.4410}, {91.1528, -1.6435, 0.0447}, 1.4441},
    {{90.9257, -0.5406, -0.9208}, {88.6381, -0.8985, -0.7239}, 1.5381},
    {{6.7747, -0.2908, -2.4247}, {5.8714, -0.0985, -2.2286}, 0.6377},
    {{2.0776, 0.0795, -1.1350}, {0.9033, -0.0636, -0.5514}, 0.9082},
};

TEST(DeltaE, Ciede2000MatchesTheFormulasPublishedTestData) {
  for (size_t i = 0; i < std::size(kSharmaPairs); ++i) {
    const SharmaPair& pair = kSharmaPairs[i];
    // 5e-5: the table rounds to four decimals; the formula in double is exact well below that.
    EXPECT_NEAR(ciede2000(pair.first, pair.second), pair.delta_e, 5e-5) << "pair " << i + 1;
    EXPECT_NEAR(ciede2000(pair.second, pair.first), pair.delta_e, 5e-5) << "pair " << i + 1 << " swapped";
  }
}

TEST(DeltaE, LabOfDisplayWhiteAndBlack) {
  const Lab white = lab_from_linear_srgb(glm::vec3(1.0f));
  EXPECT_NEAR(white.L, 100.0, 1e-9);
  EXPECT_NEAR(white.a, 0.0, 1e-9);
  EXPECT_NEAR(white.b, 0.0, 1e-9);
  EXPECT_NEAR(lab_from_linear_srgb(glm::vec3(0.0f)).L, 0.0, 1e-9);
  // Above 1 is clamped as a display shows it: a highlight is white.
  EXPECT_NEAR(lab_from_linear_srgb(glm::vec3(4.0f)).L, 100.0, 1e-9);
}

TEST(DeltaE, UnitysSettingsCountWhatIsLeftAboveThePerPixelThreshold) {
  FloatImage reference(4, 1);
  FloatImage test(4, 1);
  for (uint32_t x = 0; x < 4; ++x) {
    reference.set(x, 0, {0.5f, 0.5f, 0.5f, 1.0f});
    test.set(x, 0, {0.5f, 0.5f, 0.5f, 1.0f});
  }
  test.set(2, 0, {0.5f, 0.5f, 0.6f, 1.0f});
  const DeltaEMeasure measure = measure_delta_e(test, reference, 1.0);
  const double expected = ciede2000(lab_from_linear_srgb({0.5f, 0.5f, 0.6f}), lab_from_linear_srgb({0.5f, 0.5f, 0.5f}));
  ASSERT_GT(expected, 1.0);
  EXPECT_FLOAT_EQ(measure.per_pixel[2], float(expected));
  EXPECT_EQ(measure.per_pixel[0], 0.0f);
  EXPECT_DOUBLE_EQ(measure.max, expected);
  EXPECT_EQ(measure.max_x, 2u);
  EXPECT_DOUBLE_EQ(measure.mean, expected / 4.0);
  EXPECT_DOUBLE_EQ(measure.average_excess, (expected - 1.0) / 4.0);
  EXPECT_EQ(measure.incorrect_pixels, 1u);
  EXPECT_DOUBLE_EQ(measure.incorrect_fraction, 0.25);
  // A threshold above the difference leaves nothing.
  EXPECT_EQ(measure_delta_e(test, reference, expected + 0.01).incorrect_pixels, 0u);
}

TEST(DeltaE, ANonFinitePixelIsTheLargestDifference) {
  FloatImage reference(2, 1);
  FloatImage test(2, 1);
  test.set(1, 0, {NAN, 0.0f, 0.0f, 1.0f});
  const DeltaEMeasure measure = measure_delta_e(test, reference, 0.0);
  EXPECT_NEAR(measure.max, ciede2000(lab_from_linear_srgb(glm::vec3(0.0f)), lab_from_linear_srgb(glm::vec3(1.0f))),
              1e-12);
  EXPECT_EQ(measure.max_x, 1u);
}

}  // namespace delta_e_test
}  // namespace xshade::harness
