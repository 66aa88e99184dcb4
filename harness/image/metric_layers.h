// The perceptual metrics (FLIP, SSIM, CIEDE2000) as comparison layers: each measured on a test
// image against its reference, held to a threshold, and described in one line, with a heat map
// of its per-pixel values. A scene chooses one in `[compare] metric`; `xshade diff --metric` runs
// one on any two images. Which to choose is in docs/reports.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"
#include "harness/image/image.h"
#include "harness/image/image_compare.h"
#include "harness/image/metric_settings.h"

namespace xshade::harness {

struct MetricResult {
  LayerResult layer;  // "flip", "ssim" or "deltae", its verdict and one line
  // Its name, the number held to the threshold (mean FLIP, mean SSIM, average excess ΔE), the
  // threshold, and its own figures by name, for results.json and the page.
  MetricFigures figures;
  // Per pixel, in [0, 1] where 1 is the worst the metric can say: FLIP itself, 1 - SSIM (of the
  // window centred there; 0 at the edge the windows do not reach), CIEDE2000 / 10 clamped.
  std::vector<float> heat;
  uint32_t width = 0;
  uint32_t height = 0;
};

// Fails when the metric cannot measure the images (SSIM of an image smaller than its window).
// The images have the same size.
Result<MetricResult> run_metric(const FloatImage& test, const FloatImage& reference, const MetricSettings& settings);

// The metric heat map's 256 colours (linear RGB, alpha 1): inferno from 0 to 1 in even steps, 0
// itself black. Fails when the image library (image_codec.h) cannot be loaded.
Result<std::array<glm::vec4, 256>> metric_palette();

// `result.heat` through metric_palette, each value to the nearest of its 256 steps.
Result<FloatImage> metric_heat_map(const MetricResult& result);

}  // namespace xshade::harness
