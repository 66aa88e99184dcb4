// CIEDE2000 colour difference per pixel: how far apart two colours look, in units where about 1
// is the smallest difference an observer notices side by side. With it the settings Unity's
// Graphics Test Framework gives an image comparison (ImageComparisonSettings): a per-pixel
// threshold below which a difference is ignored, the average of what is left above it, and the
// fraction of pixels above it. (The framework itself measures in JzAzBz; xshade uses the CIE's
// standard formula, whose scale reviewers know: docs/reports.md.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "harness/image/image.h"

namespace xshade::harness {

// A CIELAB colour relative to D65 white.
struct Lab {
  double L = 0.0;
  double a = 0.0;
  double b = 0.0;
};

// The CIELAB colour of a linear sRGB colour, each channel clamped to [0, 1] as a display shows it.
Lab lab_from_linear_srgb(glm::vec3 linear);

// CIEDE2000 with kL = kC = kH = 1 (CIE 142-2001; Sharma, Wu and Dalal 2005). Hue angles are
// worked in degrees, so that a hue difference of exactly 180 degrees takes the branch the
// formula means (in radians it can land an ulp past pi).
double ciede2000(const Lab& first, const Lab& second);

// The colours of two images of one size compared pixel by pixel (alpha aside).
struct DeltaEMeasure {
  std::vector<float> per_pixel;  // row-major, one difference per pixel
  double mean = 0.0;
  double max = 0.0;
  uint32_t max_x = 0;  // the first pixel with the largest difference
  uint32_t max_y = 0;
  // Unity's settings: the mean over every pixel of max(0, difference - per-pixel threshold), and
  // the pixels whose difference exceeds the threshold.
  double average_excess = 0.0;
  size_t incorrect_pixels = 0;
  double incorrect_fraction = 0.0;
};
// `test` and `reference` have the same size. A non-finite channel counts as the largest possible
// difference there (the finite layer reports it).
DeltaEMeasure measure_delta_e(const FloatImage& test, const FloatImage& reference, double per_pixel_threshold);

}  // namespace xshade::harness
