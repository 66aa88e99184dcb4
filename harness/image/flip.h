// FLIP, NVIDIA's difference evaluator for images shown one after the other (Andersson et al., "FLIP:
// A Difference Evaluator for Alternating Images", HPG 2020; HDR-FLIP, "Visualizing Errors in
// Rendered High Dynamic Range Images", Eurographics 2021), as its reference implementation
// (NVlabs/flip, FLIP.h) computes it: the colour difference of the images as the eye's contrast
// sensitivity filters them, at a viewing distance in pixels per degree, raised by the difference
// of their edges and points. Each pixel's value is in [0, 1]: 0 where the two cannot be told apart
// as they alternate, 1 at the largest difference (green against blue).
#pragma once

#include <cstdint>
#include <vector>

#include "harness/image/image.h"

namespace xshade::harness {

// 0.7 m from a 0.7 m wide monitor of 3840 pixels across: the reference implementation's default.
double flip_default_pixels_per_degree();

struct FlipMeasure {
  std::vector<float> per_pixel;  // row-major, one value per pixel, each in [0, 1]
  double mean = 0.0;
  // The reference tool's weighted percentiles: a value's weight is the value itself, so the median
  // is where half of the image's total error lies below.
  double weighted_median = 0.0;
  double weighted_first_quartile = 0.0;
  double weighted_third_quartile = 0.0;
  double min = 0.0;
  double max = 0.0;
  uint32_t max_x = 0;  // the first pixel with the largest value
  uint32_t max_y = 0;
  // HDR-FLIP only: the exposures tone-mapped (ACES) and compared, the pixel's value the largest.
  bool hdr = false;
  double start_exposure = 0.0;
  double stop_exposure = 0.0;
  uint32_t exposures = 0;
};

// LDR-FLIP of two images of one size, their linear colours clamped to [0, 1] (alpha aside).
FlipMeasure measure_flip(const FloatImage& test, const FloatImage& reference, double pixels_per_degree);

// HDR-FLIP: LDR-FLIP at each exposure from the one that maps the reference's brightest value to
// the tone mapper's 85% to the one that does so to its median luminance, one stop apart or less.
FlipMeasure measure_hdr_flip(const FloatImage& test, const FloatImage& reference, double pixels_per_degree);

}  // namespace xshade::harness
