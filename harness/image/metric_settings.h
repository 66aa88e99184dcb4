// Which perceptual metric decides a comparison, and its thresholds (metric_layers.h measures them):
// the part of a scene's `[compare]` that chooses one, and of `xshade diff --metric`.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace xshade::harness {

enum class Metric { Flip, Ssim, DeltaE };
std::string_view metric_name(Metric metric);  // "flip", "ssim", "deltae"
std::optional<Metric> metric_named(std::string_view name);

struct MetricSettings {
  Metric metric = Metric::Flip;
  // flip: the highest mean FLIP; ssim: the lowest mean SSIM; deltae: the highest average of what
  // each pixel's CIEDE2000 leaves above `pixel_threshold` (Unity's AverageCorrectnessThreshold).
  double threshold = 0.0;
  // deltae: a pixel's difference below this is ignored (PerPixelCorrectnessThreshold), and the
  // fraction of pixels above it may be at most `incorrect_fraction` (IncorrectPixelsThreshold).
  double pixel_threshold = 1.0;
  double incorrect_fraction = 0.0;
  // flip: the viewing distance, pixels per degree.
  double pixels_per_degree = 0.0;  // 0: the reference implementation's 67.02
};

// The threshold a metric is held to when none is given, and why (docs/reports.md).
double default_metric_threshold(Metric metric);

// What a comparison's metric measured, for results.json and the report.
struct MetricFigures {
  std::string name;    // metric_name
  double value = 0.0;  // the number held to the threshold
  double threshold = 0.0;
  // The metric's own figures by name ("mean", "weighted_median", ...), in the order shown.
  std::vector<std::pair<std::string, double>> figures;
};

}  // namespace xshade::harness
