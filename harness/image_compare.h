// Comparing a rendered image with a reference (a golden, or another lane's image of the same
// scene): the layers of DESIGN.md's comparison model, run in order, each with a verdict and one
// line for the report, and the layer whose verdict decided the comparison.
//
// Layers 3 and 4 compare the images as write_png stores them (colour through linear_to_srgb8,
// alpha times 255 rounded), not as floats: a golden is an 8-bit PNG, so an exact re-render of
// it must compare equal with a tolerance of 0 steps.
#pragma once

#include <string>
#include <vector>

#include "harness/image.h"
#include "harness/run_results.h"
#include "harness/scene.h"

namespace xshade::harness {

struct Comparison {
  Verdict verdict = Verdict::Pass;  // Pass or Fail
  // The layer whose verdict is the comparison's: "size", "finite", "exact", "per_pixel" or
  // "position".
  std::string decided_by;
  // "size" alone when the sizes differ; otherwise "finite", "exact", "per_pixel", "position",
  // "summary" in that order. Layers after a failed "finite" still run, for the report; after a
  // passed "exact" the per-pixel and position layers are skipped.
  std::vector<LayerResult> layers;
  ImageMetrics metrics;  // all zero when the sizes differ
  NonFiniteCount test_non_finite;
  NonFiniteCount reference_non_finite;
  // The test image's size (empty when the sizes differ), alpha 1. Each pixel shows its largest
  // 8-bit channel difference d (alpha included) through OpenImageIO's "inferno" colour map, at a
  // position that depends on the channel tolerance t:
  //   d = 0            black;
  //   1 <= d <= t      0.05 + 0.25 * d / t: dark purple, within the tolerance;
  //   d > t            0.5 + 0.5 * ln(d - t) / ln(255 - t): from red-purple at t + 1 (already
  //                    plain to see, even one step beyond) through orange to pale yellow at 255.
  // The map's colours are sRGB; they are stored linear, so that write_png shows them as they are.
  FloatImage heat_map;
};

// Runs every layer on `test` against `reference` with the scene's tolerances.
Comparison compare_images(const FloatImage& test, const FloatImage& reference, const CompareSettings& settings);

// NaN, infinite and negative channel values (alpha included; -0 is not negative), and the first
// pixel in row-major order that has any.
NonFiniteCount count_non_finite(const FloatImage& image);

// White (alpha 1) where any channel of the pixel is NaN, infinite or negative, black elsewhere.
FloatImage non_finite_mask(const FloatImage& image);

}  // namespace xshade::harness
