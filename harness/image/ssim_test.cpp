#include "harness/image/ssim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace xshade::harness {
namespace ssim_test {

constexpr uint32_t kSize = 64;

std::vector<double> plane(const std::function<double(uint32_t x, uint32_t y)>& value) {
  std::vector<double> out(size_t(kSize) * kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) out[size_t(y) * kSize + x] = value(x, y);
  return out;
}

double ssim(const std::vector<double>& a, const std::vector<double>& b) {
  auto measure = ssim_of_planes(a, b, kSize, kSize);
  EXPECT_TRUE(measure) << measure.error().to_string();
  return measure ? measure->mean : NAN;
}

TEST(Ssim, ConstantPlanesGiveThePapersClosedForm) {
  // Without variance SSIM is its luminance term, (2ab + C1) / (a^2 + b^2 + C1), C1 = (0.01 x 255)^2
  // (Wang et al. 2004, eq. 6 and 13).
  const double c1 = 6.5025;
  EXPECT_NEAR(ssim(plane([](auto, auto) { return 100.0; }), plane([](auto, auto) { return 150.0; })),
              (2 * 100.0 * 150.0 + c1) / (100.0 * 100.0 + 150.0 * 150.0 + c1), 1e-12);
  EXPECT_NEAR(ssim(plane([](auto, auto) { return 0.0; }), plane([](auto, auto) { return 255.0; })),
              c1 / (255.0 * 255.0 + c1), 1e-15);
}

TEST(Ssim, MatchesTheReferenceImplementationOnGeneratedPlanes) {
  // The reference values are ssim_index.m's (Zhou Wang's MATLAB implementation, utlive/ssim) as
  // scikit-image 0.19.3 computes it, structural_similarity(a, b, data_range=255,
  // gaussian_weights=True, sigma=1.5, use_sample_covariance=False), which agrees with a direct
  // transcription of ssim_index.m to 10 digits, on these 64x64 planes. 1e-9: the sums run in
  // double here too, in another order.
  const auto ramp = [](uint32_t x, uint32_t) { return 4.0 * x; };
  EXPECT_NEAR(ssim(plane(ramp), plane(ramp)), 1.0, 1e-12);
  EXPECT_NEAR(ssim(plane(ramp), plane([](uint32_t x, uint32_t) { return 4.0 * x + 10; })), 0.9911002376, 1e-9);
  EXPECT_NEAR(ssim(plane(ramp), plane([](uint32_t x, uint32_t) { return 2.0 * x; })), 0.7307871249, 1e-9);
  EXPECT_NEAR(ssim(plane(ramp), plane([](uint32_t x, uint32_t) { return 252.0 - 4.0 * x; })), -0.0665492554, 1e-9);
  EXPECT_NEAR(ssim(plane(ramp), plane([](uint32_t, uint32_t y) { return 4.0 * y; })), 0.3484393601, 1e-9);
  EXPECT_NEAR(ssim(plane([](uint32_t x, uint32_t y) { return ((x / 8 + y / 8) % 2) * 255.0; }),
                   plane([](auto, auto) { return 128.0; })),
              0.0056028523, 1e-9);
  EXPECT_NEAR(ssim(plane(ramp), plane([](uint32_t x, uint32_t y) { return 4.0 * x + ((x + y) % 2) * 8.0; })),
              0.8891517888, 1e-9);
}

TEST(Ssim, TheMapHasAValuePerWindowAndFindsTheLeastSimilar) {
  // A flat plane and one pixel changed: the window centred on it weighs it most.
  std::vector<double> a = plane([](auto, auto) { return 100.0; });
  std::vector<double> b = a;
  b[size_t(40) * kSize + 20] += 120.0;
  auto measure = ssim_of_planes(a, b, kSize, kSize);
  ASSERT_TRUE(measure);
  EXPECT_EQ(measure->map_width, kSize - 10);
  EXPECT_EQ(measure->map_height, kSize - 10);
  EXPECT_EQ(measure->min_x, 20u);
  EXPECT_EQ(measure->min_y, 40u);
  EXPECT_LT(measure->min, 0.9);
  EXPECT_EQ(measure->map[0], 1.0f);  // a window that does not reach the change
}

TEST(Ssim, AnImageSmallerThanTheWindowIsRefused) {
  const std::vector<double> small(10 * 10, 0.0);
  auto measure = ssim_of_planes(small, small, 10, 10);
  ASSERT_FALSE(measure);
  EXPECT_NE(measure.error().message.find("at least 11x11"), std::string::npos) << measure.error().message;
}

TEST(Ssim, ImagesAreMeasuredOnTheirDisplayedLuma) {
  FloatImage a(16, 16);
  FloatImage b(16, 16);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      a.set(x, y, {0.2f, 0.2f, 0.2f, 1.0f});
      b.set(x, y, {0.2f, 0.2f, 0.2f, 1.0f});
    }
  auto same = measure_ssim(a, b);
  ASSERT_TRUE(same);
  EXPECT_DOUBLE_EQ(same->mean, 1.0);
  // A value above 1 displays as white: the same as 1.
  for (uint32_t x = 0; x < 16; ++x) {
    a.set(x, 3, {1.0f, 1.0f, 1.0f, 1.0f});
    b.set(x, 3, {5.0f, 5.0f, 5.0f, 1.0f});
  }
  EXPECT_DOUBLE_EQ(measure_ssim(a, b)->mean, 1.0);
  b.set(8, 8, {0.0f, 0.0f, 1.0f, 1.0f});
  EXPECT_LT(measure_ssim(a, b)->mean, 1.0);
}

}  // namespace ssim_test
}  // namespace xshade::harness
