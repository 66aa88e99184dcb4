// xshade diff A B: the comparison model's layers on any two images a user already has (PNG, EXR,
// HDR), as a run holds a render against its golden: B is held against A. Exit 0 when B passes,
// 1 when it does not (or the sizes differ), 2 when an image cannot be read; idiff's pass, fail
// and error.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <future>
#include <memory>

#include "cli/commands.h"
#include "harness/gate/result_json.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"
#include "harness/image/metric_layers.h"

namespace xshade::cli {
namespace {

using nlohmann::json;

json non_finite_json(const harness::NonFiniteCount& count) {
  return {{"nan", count.nan}, {"inf", count.inf}, {"negative", count.negative}};
}

json rgba_json(const std::array<float, 4>& value) {
  json out = json::array();
  for (float channel : value) out.push_back(std::isfinite(channel) ? json(channel) : json(nullptr));
  return out;
}

// White where the per-pixel layer found the pixel beyond the tolerance, black elsewhere.
harness::FloatImage failing_mask(const harness::FloatImage& like, const std::vector<uint32_t>& failing) {
  harness::FloatImage mask(like.width, like.height);
  for (size_t p = 0; p < size_t(like.width) * like.height; ++p) mask.rgba[p * 4 + 3] = 1.0f;
  for (uint32_t p : failing) std::fill_n(&mask.rgba[size_t(p) * 4], 3, 1.0f);
  return mask;
}

std::string rgba_text(const std::array<float, 4>& value) {
  return fmt::format("({:g}, {:g}, {:g}, {:g})", value[0], value[1], value[2], value[3]);
}

// --metric: the verdict is the metric's. Sizes that differ fail as the layers' "size" does.
int run_metric_diff(const DiffOptions& options, const harness::FloatImage& a, const harness::FloatImage& b) {
  const std::optional<harness::Metric> metric = harness::metric_named(options.metric);
  harness::MetricSettings settings;
  settings.metric = *metric;  // the option's check admits only the metrics' names
  settings.threshold = options.threshold.value_or(harness::default_metric_threshold(*metric));
  settings.pixel_threshold = options.pixel_threshold;
  settings.incorrect_fraction = options.incorrect_fraction;
  settings.pixels_per_degree = options.pixels_per_degree;
  if (a.width != b.width || a.height != b.height) {
    fmt::print("FAIL: {} against {}: the sizes differ ({}x{} against {}x{})\n", options.b.string(), options.a.string(),
               b.width, b.height, a.width, a.height);
    return kTestFailed;
  }
  auto result = harness::run_metric(b, a, settings);
  if (!result) {
    fmt::print(stderr, "xshade diff: {}\n", result.error().to_string());
    return exit_code_of(result.error().kind);
  }
  int written = kPass;
  if (!options.heat_map.empty()) {
    auto heat = harness::metric_heat_map(*result);
    auto saved = heat ? harness::write_png(*heat, options.heat_map) : Result<void>(fail(heat.error()));
    if (!saved) {
      fmt::print(stderr, "xshade diff: {}\n", saved.error().to_string());
      written = exit_code_of(saved.error().kind);
    }
  }
  const bool pass = result->layer.verdict == harness::Verdict::Pass;
  if (options.json) {
    json measured = harness::metric_to_json(result->figures);
    measured["detail"] = result->layer.detail;
    const json document = {{"a", options.a.string()},
                           {"b", options.b.string()},
                           {"verdict", harness::verdict_name(result->layer.verdict)},
                           {"decided_by", result->layer.layer},
                           {"metric", std::move(measured)},
                           {"width", b.width},
                           {"height", b.height}};
    fmt::print("{}\n", document.dump(2, ' ', false, json::error_handler_t::replace));
  } else {
    fmt::print("{}: {} against {}: {} ({})\n  {}\n", pass ? "PASS" : "FAIL", options.b.string(), options.a.string(),
               harness::verdict_name(result->layer.verdict), result->layer.layer, result->layer.detail);
  }
  if (written != kPass) return written;
  return pass ? kPass : kTestFailed;
}

}  // namespace

int run_diff(const DiffOptions& options) {
  // The two files are read at once: reading is most of a comparison's time, and much of it
  // (the file, copying rows out of OpenEXR's buffers) runs on one core per file.
  auto reading_b = std::async(std::launch::async, [&] { return harness::read_image(options.b); });
  auto a = harness::read_image(options.a);
  auto b = reading_b.get();
  if (!a) {
    fmt::print(stderr, "xshade diff: {}\n", a.error().to_string());
    return kBadInput;
  }
  if (!b) {
    fmt::print(stderr, "xshade diff: {}\n", b.error().to_string());
    return kBadInput;
  }
  if (!options.metric.empty()) return run_metric_diff(options, *a, *b);
  harness::CompareSettings settings;
  settings.channel_tolerance = options.tolerance;
  settings.max_failing_fraction = options.budget;
  settings.position_radius = options.radius;
  settings.float_tolerance = options.float_tolerance;
  const harness::Comparison comparison = harness::compare_images(*b, *a, settings, !options.heat_map.empty());
  const bool same_size = comparison.decided_by != "size";

  // The images asked for; a heat map or mask of images of different sizes does not exist.
  int written = kPass;
  const auto write = [&](const std::filesystem::path& path, const harness::FloatImage& image) {
    if (path.empty()) return;
    if (!same_size) {
      fmt::print(stderr, "xshade diff: {} not written: the images differ in size\n", path.string());
      return;
    }
    if (auto result = harness::write_png(image, path); !result) {
      fmt::print(stderr, "xshade diff: {}\n", result.error().to_string());
      written = kBadInput;
    }
  };
  write(options.heat_map, comparison.heat_map);
  if (!options.mask.empty() && same_size) write(options.mask, failing_mask(*b, comparison.failing_pixels));

  const harness::ImageMetrics& m = comparison.metrics;
  if (options.json) {
    json layers = json::array();
    for (const harness::LayerResult& layer : comparison.layers)
      layers.push_back(
          {{"layer", layer.layer}, {"verdict", harness::verdict_name(layer.verdict)}, {"detail", layer.detail}});
    json document = {{"a", options.a.string()},
                     {"b", options.b.string()},
                     {"verdict", harness::verdict_name(comparison.verdict)},
                     {"decided_by", comparison.decided_by},
                     {"layers", std::move(layers)},
                     {"width", b->width},
                     {"height", b->height},
                     {"non_finite",
                      {{"a", non_finite_json(comparison.reference_non_finite)},
                       {"b", non_finite_json(comparison.test_non_finite)}}}};
    if (same_size) {
      document["metrics"] = harness::metrics_to_json(m);
      document["worst"] = {{"x", m.worst_x},
                           {"y", m.worst_y},
                           {"steps", m.max_steps},
                           {"a", rgba_json(m.worst_reference)},
                           {"b", rgba_json(m.worst_test)}};
    }
    fmt::print("{}\n", document.dump(2, ' ', false, json::error_handler_t::replace));
  } else {
    fmt::print("{}: {} against {}: {} ({})\n", comparison.verdict == harness::Verdict::Pass ? "PASS" : "FAIL",
               options.b.string(), options.a.string(), harness::verdict_name(comparison.verdict),
               comparison.decided_by);
    for (const harness::LayerResult& layer : comparison.layers)
      fmt::print("  {:<9} {:<7} {}\n", layer.layer, harness::verdict_name(layer.verdict), layer.detail);
    if (same_size && m.max_steps > 0)
      fmt::print("  worst pixel ({}, {}): A {} B {}\n", m.worst_x, m.worst_y, rgba_text(m.worst_reference),
                 rgba_text(m.worst_test));
  }
  if (written != kPass) return written;
  return comparison.verdict == harness::Verdict::Pass ? kPass : kTestFailed;
}

Verb add_diff_command(CLI::App& app) {
  auto options = std::make_shared<DiffOptions>();
  CLI::App* diff = app.add_subcommand(
      "diff",
      "Hold image B against image A (PNG, EXR, HDR) with the layers a run uses on a golden: exit 0 pass, 1 "
      "fail, 2 an image that does not read");
  diff->add_option("a", options->a, "The reference image (a golden)")->required()->type_name("A");
  diff->add_option("b", options->b, "The image under test")->required()->type_name("B");
  diff->add_option("--tolerance", options->tolerance, "Steps of 8-bit sRGB a channel may differ")
      ->type_name("STEPS")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  diff->add_option("--budget", options->budget, "Fraction of the pixels that may fail, 0 to 1")
      ->type_name("FRACTION")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  diff->add_option("--radius", options->radius,
                   "A failing pixel passes when A has a matching pixel this near (an edge that moved)")
      ->type_name("PIXELS")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  diff->add_option("--float-tolerance", options->float_tolerance, "Relative error allowed a value above 1")
      ->type_name("RELATIVE")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  diff->add_option("--heat-map", options->heat_map, "Write the difference's heat map (PNG) here")->type_name("FILE");
  CLI::Option* mask =
      diff->add_option("--mask", options->mask, "Write the failing pixels' mask (PNG, white where failing) here")
          ->type_name("FILE");
  diff->add_flag("--json", options->json, "Print the verdict, layers and metrics as JSON");
  diff->add_option("--metric", options->metric,
                   "Decide by a perceptual metric instead of the per-pixel layers: flip (NVIDIA's FLIP; HDR-FLIP "
                   "when an image holds values above 1), ssim, or deltae (CIEDE2000 with Unity's thresholds)")
      ->type_name("METRIC")
      ->check(CLI::IsMember({"flip", "ssim", "deltae"}))
      ->excludes(mask);  // the mask is the per-pixel layer's; a metric writes its --heat-map
  diff->add_option("--threshold", options->threshold,
                   "--metric's bound: flip the highest mean (default 0.0005), ssim the lowest mean (0.999), deltae the "
                   "highest average CIEDE2000 above --pixel-threshold (0)")
      ->type_name("VALUE");
  diff->add_option("--pixel-threshold", options->pixel_threshold,
                   "deltae: a pixel's CIEDE2000 below this is ignored (1 is the just noticeable difference)")
      ->type_name("DELTA_E")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  diff->add_option("--incorrect-fraction", options->incorrect_fraction,
                   "deltae: the fraction of the pixels that may be above --pixel-threshold, 0 to 1")
      ->type_name("FRACTION")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  diff->add_option(
          "--ppd", options->pixels_per_degree,
          "flip: the viewing distance in pixels per degree (default 67.02: 0.7 m from a 0.7 m wide 4K monitor)")
      ->type_name("PPD")
      ->check(CLI::PositiveNumber);
  return {diff, [options](const std::string&) { return run_diff(*options); }};
}

}  // namespace xshade::cli
