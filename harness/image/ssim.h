// SSIM, the structural similarity index (Wang, Bovik, Sheikh and Simoncelli, "Image quality
// assessment: from error visibility to structural similarity", IEEE TIP 13(4), 2004), as their
// reference implementation ssim_index.m computes it: an 11x11 Gaussian window of standard
// deviation 1.5, K1 = 0.01, K2 = 0.03, a dynamic range of 255, population statistics, the map
// over the windows that fit inside the image (no padding), and its mean. 1 is identical; a
// reviewer's rule of thumb is that above 0.98 a difference is hard to see.
#pragma once

#include <cstdint>
#include <vector>

#include "base/result.h"
#include "harness/image/image.h"

namespace xshade::harness {

struct SsimMeasure {
  double mean = 1.0;
  double min = 1.0;
  uint32_t min_x = 0;  // the centre of the least similar window, in the image's pixels
  uint32_t min_y = 0;
  // One value per window, (width - 10) x (height - 10), row-major: the value at (x, y) is the
  // window centred on the image's pixel (x + 5, y + 5).
  uint32_t map_width = 0;
  uint32_t map_height = 0;
  std::vector<float> map;
};

// The window's reach either side of its centre; an image narrower or shorter than 2 * 5 + 1
// pixels has no window.
inline constexpr uint32_t kSsimRadius = 5;

// SSIM of two grey planes of `width` x `height` values in 0..255, row-major.
Result<SsimMeasure> ssim_of_planes(const std::vector<double>& first, const std::vector<double>& second, uint32_t width,
                                   uint32_t height);

// SSIM of two images of one size on their luma as a display shows them: each channel as
// write_png stores it (8-bit sRGB), weighted 0.299, 0.587, 0.114 (BT.601, the luma SSIM tools
// measure).
Result<SsimMeasure> measure_ssim(const FloatImage& test, const FloatImage& reference);

}  // namespace xshade::harness
