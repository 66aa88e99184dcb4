// Comparing a rendered image with a reference (a golden, or another lane's image of the same
// scene): the layers of DESIGN.md's comparison model, run in order, each with a verdict and one
// line for the report, and the layer whose verdict decided the comparison.
//
// Layers 3 and 4 compare the images as write_png stores them (colour through linear_to_srgb8,
// alpha times 255 rounded), not as floats: the displayable range is judged as a viewer sees it,
// and an 8-bit golden's re-render compares equal with a tolerance of 0 steps. Layer 5 compares
// the values above 1 as floats, relative, which the 8-bit layers cannot see.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"
#include "harness/image/image.h"
#include "harness/image/metric_settings.h"

namespace xshade::harness {

// How closely a lane must match the golden image and the other lanes (DESIGN.md, comparison
// model). The defaults allow one 8-bit step per channel and nothing else: llvmpipe's GL and
// Vulkan paths may round a value that lies exactly on an sRGB step boundary to different sides.
struct CompareSettings {
  static constexpr uint32_t default_channel_tolerance = 1;
  static constexpr double default_max_failing_fraction = 0.0;
  static constexpr uint32_t default_position_radius = 0;
  // Relative error allowed a value above 1 (a highlight, an HDR input a bloom or a tone mapper
  // downstream reads). 0.5%: about half of what the default one 8-bit sRGB step is at 1 (254 vs
  // 255 is 0.89% in linear), so an HDR value may move no more than a displayable one; and twice
  // the most the lanes' own values above 1 differ on the fixed scenes, 0.26% in five highlight
  // values of material_grid_guarded (gl against vk and vk-hlsl; at most 8.2e-5 in every other
  // scene), measured by `xshade run` (results.json, cross_lane metrics.above_one.worst_relative).
  static constexpr double default_float_tolerance = 0.005;

  uint32_t channel_tolerance = default_channel_tolerance;      // 8-bit sRGB steps, 0..255
  double max_failing_fraction = default_max_failing_fraction;  // of the pixels, 0..1
  uint32_t position_radius = default_position_radius;          // pixels, 0..8
  double float_tolerance = default_float_tolerance;            // relative, for values above 1; 0..1
  std::string reason;                                          // why; required whenever a tolerance is given
  bool tolerances_given = false;                               // any of the three numbers was written in the scene
  // A perceptual metric that decides in place of the per-pixel, position and float layers
  // (`[compare] metric`; metric_layers.h); those still run, for the report.
  std::optional<MetricSettings> metric = std::nullopt;
};

enum class Verdict {
  Pass,
  Fail,     // a check failed (exit 1)
  Error,    // bad input: a scene or shader that does not load or compile (exit 2)
  Crash,    // a backend or internal error (exit 3)
  Skipped,  // not run (e.g. the lane is not selected)
};
std::string_view verdict_name(Verdict verdict);                   // "pass", "fail", "error", "crash", "skipped"
std::optional<Verdict> verdict_from_name(std::string_view name);  // verdict_name's inverse

// One layer of the comparison model (DESIGN.md), or one of the other gate layers:
// "finite", "exact", "per_pixel", "position", "summary", "cross_lane", "determinism".
struct LayerResult {
  std::string layer;
  Verdict verdict = Verdict::Pass;
  std::string detail;  // one line a reviewer reads: what was measured against what bound
};

// What a comparison measured. The gate's summary is in the per-pixel layer's domain, 8-bit sRGB
// steps of the images as write_png stores them (steps, worst, first failing, mean and RMSE in
// steps, PSNR); the float layer's in relative error of the values above 1. The linear fields are
// the float values' own differences, for the accuracy studies, which report both domains.
struct ImageMetrics {
  double max_difference = 0.0;  // linear, largest over channels
  uint32_t max_x = 0;
  uint32_t max_y = 0;
  double mean = 0.0;  // mean absolute difference, linear
  double rmse = 0.0;
  double psnr = 0.0;          // dB, on the 8-bit sRGB images; infinite when identical
  size_t failing_pixels = 0;  // beyond the channel tolerance (per-pixel layer)
  double failing_fraction = 0.0;

  uint32_t max_steps = 0;  // the worst pixel's largest channel difference, sRGB steps
  uint32_t worst_x = 0;    // the first pixel with max_steps
  uint32_t worst_y = 0;
  std::array<float, 4> worst_test{};  // the worst pixel's values, RGBA as compared
  std::array<float, 4> worst_reference{};
  double mean_steps = 0.0;  // over every channel of every pixel
  double rmse_steps = 0.0;
  std::optional<std::pair<uint32_t, uint32_t>> first_failing =
      std::nullopt;  // the first pixel the per-pixel layer failed

  size_t hdr_values = 0;            // channel pairs with a value above 1, which the float layer compares
  size_t float_failing_pixels = 0;  // with a value beyond the float tolerance
  double float_max_relative = 0.0;  // the largest relative error among them
  uint32_t float_x = 0;             // where it is
  uint32_t float_y = 0;

  std::optional<MetricFigures> metric = std::nullopt;  // the scene's perceptual metric, when it chose one
};

// "worst 3 sRGB steps at (3, 4), 12 failing pixels (0.29%)", and the float layer's failures.
std::string describe_metrics(const ImageMetrics& metrics);

struct NonFiniteCount {
  size_t nan = 0;
  size_t inf = 0;
  size_t negative = 0;
  std::optional<std::pair<uint32_t, uint32_t>> first;  // (x, y) of the first such pixel
  size_t total() const { return nan + inf + negative; }
};

struct Comparison {
  Verdict verdict = Verdict::Pass;  // Pass or Fail
  // The layer whose verdict is the comparison's: "size", "finite", "exact", "per_pixel",
  // "position", "float", or the scene's metric ("flip", "ssim", "deltae").
  std::string decided_by;
  // "size" alone when the sizes differ; otherwise "finite", "exact", "per_pixel", "position",
  // "float", the metric's when the scene chose one, "summary" in that order. Layers after a failed "finite" still run,
  // for the report; after a passed "exact" the per-pixel, position and float layers are skipped. The float layer holds
  // the values above 1 (which the 8-bit layers see as 255) to their relative tolerance.
  std::vector<LayerResult> layers;
  ImageMetrics metrics;  // all zero when the sizes differ
  // The pixels the per-pixel layer found beyond the channel tolerance, as row-major indices
  // (before the position layer forgives any): the failing-pixel mask.
  std::vector<uint32_t> failing_pixels;
  NonFiniteCount test_non_finite;
  NonFiniteCount reference_non_finite;
  // The test image's size (empty when the sizes differ), alpha 1. Each pixel shows its largest
  // 8-bit channel difference d (alpha included) through matplotlib's "inferno" colour map (the image library's), at a
  // position that depends on the channel tolerance t:
  //   d = 0            black;
  //   1 <= d <= t      0.05 + 0.25 * d / t: dark purple, within the tolerance;
  //   d > t            0.5 + 0.5 * ln(d - t) / ln(255 - t): from red-purple at t + 1 (already
  //                    plain to see, even one step beyond) through orange to pale yellow at 255.
  // The map's colours are sRGB; they are stored linear, so that write_png shows them as they are.
  FloatImage heat_map;
  // The scene's metric per pixel through inferno (metric_heat_map), when it chose one, the images
  // differ and a heat map was asked for.
  FloatImage metric_heat_map;
};

// The heat map's colour (linear RGB, alpha 1) for each largest channel difference of 0..255
// 8-bit steps, for a channel tolerance: Comparison::heat_map's colours, and its legend's.
// Fails when the image library (image_codec.h) cannot be loaded.
Result<std::array<glm::vec4, 256>> heat_palette(uint32_t channel_tolerance);
// Inferno's colours (linear RGB, alpha 1) at 256 positions in 0..1, the first black: the heat
// maps' colour map, from the image library.
Result<std::array<glm::vec4, 256>> inferno_palette(const std::array<float, 256>& positions);

// Runs every layer on `test` against `reference` with the scene's tolerances. Without
// `heat_map`, Comparison::heat_map stays empty (a caller that writes none saves its memory).
Comparison compare_images(const FloatImage& test, const FloatImage& reference, const CompareSettings& settings,
                          bool heat_map = true);

// "3 NaN, 0 Inf, 1 negative channel values, first at (4, 7)"; `count` has some.
std::string describe_non_finite(const NonFiniteCount& count);

// NaN, infinite and negative channel values (alpha included; -0 is not negative), and the first
// pixel in row-major order that has any.
NonFiniteCount count_non_finite(const FloatImage& image);

// White (alpha 1) where any channel of the pixel is NaN, infinite or negative, black elsewhere.
FloatImage non_finite_mask(const FloatImage& image);

}  // namespace xshade::harness
