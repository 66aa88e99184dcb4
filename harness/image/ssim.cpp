#include "harness/image/ssim.h"

#include <array>
#include <cmath>
#include <string>

#include "harness/image/srgb8_encoder.h"

namespace xshade::harness {

namespace {

constexpr uint32_t kWindow = 2 * kSsimRadius + 1;

// ssim_index.m's fspecial('gaussian', 11, 1.5), separated: the 2D window is the outer product.
std::array<double, kWindow> gaussian_taps() {
  std::array<double, kWindow> taps{};
  double sum = 0.0;
  for (uint32_t i = 0; i < kWindow; ++i) {
    const double x = double(i) - double(kSsimRadius);
    taps[i] = std::exp(-x * x / (2.0 * 1.5 * 1.5));
    sum += taps[i];
  }
  for (double& tap : taps) tap /= sum;
  return taps;
}

// The window's weighted mean of `plane` at every position that fits: filter2(window, plane, 'valid').
std::vector<double> windowed_mean(const std::vector<double>& plane, uint32_t width, uint32_t height) {
  static const std::array<double, kWindow> taps = gaussian_taps();
  const uint32_t out_width = width - 2 * kSsimRadius;
  const uint32_t out_height = height - 2 * kSsimRadius;
  std::vector<double> rows(size_t(out_width) * height);  // filtered along x
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < out_width; ++x) {
      double sum = 0.0;
      for (uint32_t i = 0; i < kWindow; ++i) sum += taps[i] * plane[size_t(y) * width + x + i];
      rows[size_t(y) * out_width + x] = sum;
    }
  std::vector<double> out(size_t(out_width) * out_height);
  for (uint32_t y = 0; y < out_height; ++y)
    for (uint32_t x = 0; x < out_width; ++x) {
      double sum = 0.0;
      for (uint32_t i = 0; i < kWindow; ++i) sum += taps[i] * rows[size_t(y + i) * out_width + x];
      out[size_t(y) * out_width + x] = sum;
    }
  return out;
}

std::vector<double> display_luma(const FloatImage& image) {
  std::vector<double> luma(size_t(image.width) * image.height);
  for (size_t p = 0; p < luma.size(); ++p) {
    const float* c = &image.rgba[p * 4];
    luma[p] = 0.299 * linear_to_srgb8_by_table(c[0]) + 0.587 * linear_to_srgb8_by_table(c[1]) +
              0.114 * linear_to_srgb8_by_table(c[2]);
  }
  return luma;
}

}  // namespace

Result<SsimMeasure> ssim_of_planes(const std::vector<double>& first, const std::vector<double>& second, uint32_t width,
                                   uint32_t height) {
  if (width < kWindow || height < kWindow)
    return fail(ErrorKind::UserInput, "SSIM needs an image of at least " + std::to_string(kWindow) + "x" +
                                          std::to_string(kWindow) + " pixels (its window); this one is " +
                                          std::to_string(width) + "x" + std::to_string(height));
  const size_t size = size_t(width) * height;
  std::vector<double> first_squared(size), second_squared(size), product(size);
  for (size_t p = 0; p < size; ++p) {
    first_squared[p] = first[p] * first[p];
    second_squared[p] = second[p] * second[p];
    product[p] = first[p] * second[p];
  }
  const std::vector<double> mu1 = windowed_mean(first, width, height);
  const std::vector<double> mu2 = windowed_mean(second, width, height);
  const std::vector<double> e11 = windowed_mean(first_squared, width, height);
  const std::vector<double> e22 = windowed_mean(second_squared, width, height);
  const std::vector<double> e12 = windowed_mean(product, width, height);

  constexpr double c1 = (0.01 * 255.0) * (0.01 * 255.0);
  constexpr double c2 = (0.03 * 255.0) * (0.03 * 255.0);
  SsimMeasure measure;
  measure.map_width = width - 2 * kSsimRadius;
  measure.map_height = height - 2 * kSsimRadius;
  measure.map.resize(mu1.size());
  double sum = 0.0;
  for (size_t i = 0; i < mu1.size(); ++i) {
    const double variance1 = e11[i] - mu1[i] * mu1[i];
    const double variance2 = e22[i] - mu2[i] * mu2[i];
    const double covariance = e12[i] - mu1[i] * mu2[i];
    const double value = ((2.0 * mu1[i] * mu2[i] + c1) * (2.0 * covariance + c2)) /
                         ((mu1[i] * mu1[i] + mu2[i] * mu2[i] + c1) * (variance1 + variance2 + c2));
    measure.map[i] = float(value);
    sum += value;
    if (i == 0 || value < measure.min) {
      measure.min = value;
      measure.min_x = uint32_t(i % measure.map_width) + kSsimRadius;
      measure.min_y = uint32_t(i / measure.map_width) + kSsimRadius;
    }
  }
  measure.mean = sum / double(mu1.size());
  return measure;
}

Result<SsimMeasure> measure_ssim(const FloatImage& test, const FloatImage& reference) {
  return ssim_of_planes(display_luma(test), display_luma(reference), test.width, test.height);
}

}  // namespace xshade::harness
