#include "harness/image/image_compare.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <thread>

#include <fmt/format.h>

#include "harness/image/image_codec.h"
#include "harness/image/image_io.h"
#include "harness/image/metric_layers.h"
#include "harness/image/srgb8_encoder.h"

namespace xshade::harness {

std::string_view verdict_name(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: return "pass";
    case Verdict::Fail: return "fail";
    case Verdict::Error: return "error";
    case Verdict::Crash: return "crash";
    case Verdict::Skipped: return "skipped";
  }
  return "crash";
}

std::optional<Verdict> verdict_from_name(std::string_view name) {
  for (Verdict verdict : {Verdict::Pass, Verdict::Fail, Verdict::Error, Verdict::Crash, Verdict::Skipped})
    if (verdict_name(verdict) == name) return verdict;
  return std::nullopt;
}

namespace {

// Where a difference of `steps` sits on the colour map; see Comparison::heat_map.
float heat_position(uint32_t steps, uint32_t tolerance) {
  if (steps == 0) return 0.0f;
  if (steps <= tolerance) return 0.05f + 0.25f * float(steps) / float(tolerance);
  const uint32_t span = 255 - tolerance;
  if (span < 2) return 0.5f;
  return 0.5f + 0.5f * float(std::log(double(steps - tolerance)) / std::log(double(span)));
}

}  // namespace

// The heat map's colour for each difference 0..255: the image library maps a 256-pixel ramp once,
// so the image itself is a table look-up per pixel. Its maps are matplotlib's, in sRGB.
Result<std::array<glm::vec4, 256>> heat_palette(uint32_t tolerance) {
  std::array<float, 256> positions{};
  for (uint32_t steps = 0; steps < 256; ++steps) positions[steps] = heat_position(steps, tolerance);
  return inferno_palette(positions);
}

Result<std::array<glm::vec4, 256>> inferno_palette(const std::array<float, 256>& at) {
  auto codec = image_codec();
  if (!codec) return fail(codec.error());
  const std::vector<float> positions(at.begin(), at.end());
  std::vector<float> rgb;
  if (std::string failed = (*codec)->color_map(positions, "inferno", rgb); !failed.empty())
    return fail(ErrorKind::Backend, "the heat map's colour map 'inferno': " + failed);
  std::array<glm::vec4, 256> palette{};
  for (size_t i = 1; i < 256; ++i)
    palette[i] = {srgb_to_linear(rgb[i * 3]), srgb_to_linear(rgb[i * 3 + 1]), srgb_to_linear(rgb[i * 3 + 2]), 1.0f};
  palette[0] = {0.0f, 0.0f, 0.0f, 1.0f};  // inferno's first colour is nearly, not quite, black
  return palette;
}

namespace {

// ImageBufAlgo does part of this work but not in the form the model needs, so the layers below
// read the pixels themselves and use the image library only for the heat map's colour map:
// computePixelStats counts NaN and Inf but neither negatives nor where the first one is;
// compare's mean and RMSE become NaN at the first NaN, and its PSNR is relative to the
// brightest value in the images rather than to 255.

// The 8-bit code write_png stores for channel `c` of a pixel (encode_8bit, one value).
uint8_t code_of(float value, size_t c) {
  if (c < 3) return linear_to_srgb8_by_table(value);
  return value > 0.0f ? uint8_t(std::lround(std::min(value, 1.0f) * 255.0f)) : 0;
}

// An image as write_png would store it: RGB through linear_to_srgb8, alpha times 255 rounded.
std::vector<uint8_t> encode_8bit(const FloatImage& image) {
  std::vector<uint8_t> bytes(image.rgba.size());
  for (size_t i = 0; i < image.rgba.size(); ++i) bytes[i] = code_of(image.rgba[i], i % 4);
  return bytes;
}

// Whether every channel of two encoded pixels is within `tolerance` steps.
bool matches(const uint8_t* a, const uint8_t* b, uint32_t tolerance) {
  for (int c = 0; c < 4; ++c)
    if (uint32_t(std::abs(int(a[c]) - int(b[c]))) > tolerance) return false;
  return true;
}

std::string plural(size_t count, std::string_view one, std::string_view many) {
  return fmt::format("{} {}", count, count == 1 ? one : many);
}

// The most failing pixels the budget allows. The fraction is a decimal a person wrote, so a
// product that should be a whole number may land a hair below it; 1e-9 keeps it whole.
size_t failing_budget(double max_failing_fraction, size_t pixels) {
  return size_t(std::floor(max_failing_fraction * double(pixels) + 1e-9));
}

std::string describe_budget(const CompareSettings& settings, size_t budget) {
  return fmt::format("budget {:g}% = {}", settings.max_failing_fraction * 100.0, plural(budget, "pixel", "pixels"));
}

LayerResult finite_layer(const NonFiniteCount& test, const NonFiniteCount& reference) {
  if (test.total() == 0 && reference.total() == 0) return {"finite", Verdict::Pass, "no NaN, Inf or negative values"};
  std::string detail;
  if (test.total() > 0) detail = "test has " + describe_non_finite(test);
  if (reference.total() > 0)
    detail += (detail.empty() ? "" : "; ") + std::string("reference has ") + describe_non_finite(reference);
  return {"finite", Verdict::Fail, detail};
}

// What one pass over both images finds: everything but the position layer and the maximum.
struct PixelPass {
  std::vector<uint32_t> failing;  // pixel indices, row-major
  uint32_t worst_steps = 0;
  size_t worst_pixel = 0;
  double sum_absolute = 0.0;  // linear, over channel pairs where both values are finite
  double sum_squared = 0.0;
  size_t finite_pairs = 0;
  double sum_squared_steps = 0.0;  // 8-bit, every channel
  double sum_steps = 0.0;
};

// The float layer's pass: each channel pair with a value above 1 (colour; alpha is not HDR),
// its relative error against the larger magnitude.
struct FloatPass {
  size_t values = 0;
  std::vector<uint32_t> failing;  // pixel indices
  double max_relative = 0.0;
  size_t max_pixel = 0;
};

FloatPass compare_hdr(const FloatImage& test, const FloatImage& reference, double tolerance) {
  FloatPass pass;
  const size_t pixels = size_t(test.width) * test.height;
  for (size_t p = 0; p < pixels; ++p) {
    bool failed = false;
    for (size_t c = 0; c < 3; ++c) {
      const double a = test.rgba[p * 4 + c], b = reference.rgba[p * 4 + c];
      const double larger = std::max(std::fabs(a), std::fabs(b));
      if (!(larger > 1.0) || !std::isfinite(larger)) continue;  // displayable, or the finite layer's
      ++pass.values;
      const double relative = std::fabs(a - b) / larger;
      if (relative > pass.max_relative) {
        pass.max_relative = relative;
        pass.max_pixel = p;
      }
      failed = failed || relative > tolerance;
    }
    if (failed) pass.failing.push_back(uint32_t(p));
  }
  return pass;
}

// The per-pixel pass over rows [first_row, end_row): the codes are computed as they are compared
// rather than stored, which for a 2048 x 2048 pair saved two 16 MB buffers and their page faults.
PixelPass compare_rows(const FloatImage& test, const FloatImage& reference, uint32_t first_row, uint32_t end_row,
                       uint32_t tolerance, const std::array<glm::vec4, 256>& palette, FloatImage* heat_map) {
  PixelPass pass;
  // Sums in locals rather than in `pass`: the heat map's stores could alias its members, which
  // would keep the compiler from holding them in registers.
  double sum_absolute = 0.0, sum_squared = 0.0, sum_squared_steps = 0.0, sum_steps = 0.0;
  size_t finite_pairs = 0;
  const size_t end = size_t(end_row) * test.width;
  for (size_t p = size_t(first_row) * test.width; p < end; ++p) {
    const size_t i = p * 4;
    uint32_t steps = 0;
    for (size_t c = 0; c < 4; ++c) {
      const float va = test.rgba[i + c];
      const float vb = reference.rgba[i + c];
      const int step = std::abs(int(code_of(va, c)) - int(code_of(vb, c)));
      steps = std::max(steps, uint32_t(step));
      sum_squared_steps += double(step * step);
      sum_steps += double(step);
      if (std::isfinite(va) && std::isfinite(vb)) {
        const double difference = std::fabs(double(va) - double(vb));
        sum_absolute += difference;
        sum_squared += difference * difference;
        ++finite_pairs;
      }
    }
    if (steps > tolerance) pass.failing.push_back(uint32_t(p));
    if (steps > pass.worst_steps) {
      pass.worst_steps = steps;
      pass.worst_pixel = p;
    }
    const glm::vec4& colour = palette[steps];
    if (heat_map) std::copy(&colour.r, &colour.r + 4, &heat_map->rgba[i]);
  }
  pass.sum_absolute = sum_absolute;
  pass.sum_squared = sum_squared;
  pass.sum_squared_steps = sum_squared_steps;
  pass.sum_steps = sum_steps;
  pass.finite_pairs = finite_pairs;
  return pass;
}

// The per-pixel pass in blocks of rows shared among the cores. The blocks are fixed (not one per
// thread) and their results joined in row order, so that every sum is added in the same order
// and the metrics are the same bits on any machine.
PixelPass compare_pixels(const FloatImage& test, const FloatImage& reference, uint32_t tolerance,
                         const std::array<glm::vec4, 256>& palette, FloatImage* heat_map) {
  constexpr uint32_t kBlockRows = 32;
  const uint32_t block_count = (test.height + kBlockRows - 1) / kBlockRows;
  std::vector<PixelPass> blocks(block_count);
  std::atomic<uint32_t> next{0};
  const auto work = [&] {
    for (uint32_t block; (block = next.fetch_add(1)) < block_count;)
      blocks[block] = compare_rows(test, reference, block * kBlockRows, std::min(test.height, (block + 1) * kBlockRows),
                                   tolerance, palette, heat_map);
  };
  // A thread costs tens of microseconds: small images are compared on this one alone.
  const uint32_t threads = std::min({std::max(1u, std::thread::hardware_concurrency()), block_count,
                                     uint32_t(size_t(test.width) * test.height >> 16)});
  std::vector<std::thread> helpers;
  for (uint32_t t = 1; t < threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& helper : helpers) helper.join();

  PixelPass pass;
  for (PixelPass& block : blocks) {
    pass.failing.insert(pass.failing.end(), block.failing.begin(), block.failing.end());
    if (block.worst_steps > pass.worst_steps) {
      pass.worst_steps = block.worst_steps;
      pass.worst_pixel = block.worst_pixel;
    }
    pass.sum_absolute += block.sum_absolute;
    pass.sum_squared += block.sum_squared;
    pass.sum_squared_steps += block.sum_squared_steps;
    pass.sum_steps += block.sum_steps;
    pass.finite_pairs += block.finite_pairs;
  }
  return pass;
}

// A failing pixel is forgiven when a reference pixel within the radius (Chebyshev distance)
// matches it within the tolerance: an edge that moved by a pixel, not a wrong colour.
size_t forgiven_pixels(const std::vector<uint32_t>& failing, const std::vector<uint8_t>& test8,
                       const std::vector<uint8_t>& reference8, uint32_t width, uint32_t height,
                       const CompareSettings& settings) {
  const int64_t radius = settings.position_radius;
  size_t forgiven = 0;
  for (uint32_t p : failing) {
    const int64_t x = p % width;
    const int64_t y = p / width;
    const uint8_t* pixel = &test8[size_t(p) * 4];
    bool matched = false;
    for (int64_t ny = std::max<int64_t>(0, y - radius); ny <= std::min<int64_t>(height - 1, y + radius) && !matched;
         ++ny)
      for (int64_t nx = std::max<int64_t>(0, x - radius); nx <= std::min<int64_t>(width - 1, x + radius) && !matched;
           ++nx)
        matched = matches(pixel, &reference8[(size_t(ny) * width + size_t(nx)) * 4], settings.channel_tolerance);
    if (matched) ++forgiven;
  }
  return forgiven;
}

}  // namespace

NonFiniteCount count_non_finite(const FloatImage& image) {
  NonFiniteCount count;
  const size_t pixels = size_t(image.width) * image.height;
  for (size_t p = 0; p < pixels; ++p) {
    const float* value = &image.rgba[p * 4];
    // One test per channel for the usual pixel: NaN fails both comparisons.
    auto usual = [](float v) { return v >= 0.0f && v <= std::numeric_limits<float>::max(); };
    if (usual(value[0]) && usual(value[1]) && usual(value[2]) && usual(value[3])) continue;
    for (size_t c = 0; c < 4; ++c) {
      if (std::isnan(value[c]))
        ++count.nan;
      else if (std::isinf(value[c]))
        ++count.inf;
      else if (value[c] < 0.0f)
        ++count.negative;
    }
    if (!count.first) count.first = {uint32_t(p % image.width), uint32_t(p / image.width)};
  }
  return count;
}

FloatImage non_finite_mask(const FloatImage& image) {
  FloatImage mask(image.width, image.height);
  const size_t pixels = size_t(image.width) * image.height;
  for (size_t p = 0; p < pixels; ++p) {
    const float* value = &image.rgba[p * 4];
    const bool bad = std::any_of(value, value + 4, [](float v) { return !std::isfinite(v) || v < 0.0f; });
    const float shade = bad ? 1.0f : 0.0f;
    float* out = &mask.rgba[p * 4];
    out[0] = out[1] = out[2] = shade;
    out[3] = 1.0f;
  }
  return mask;
}

Comparison compare_images(const FloatImage& test, const FloatImage& reference, const CompareSettings& settings,
                          bool heat_map) {
  Comparison result;
  if (test.width != reference.width || test.height != reference.height) {
    result.verdict = Verdict::Fail;
    result.decided_by = "size";
    result.layers.push_back({"size", Verdict::Fail,
                             fmt::format("test is {}x{} but the reference is {}x{}", test.width, test.height,
                                         reference.width, reference.height)});
    return result;
  }
  const size_t pixels = size_t(test.width) * test.height;
  const uint32_t tolerance = settings.channel_tolerance;
  const std::string tolerance_steps = plural(tolerance, "sRGB step", "sRGB steps");
  const size_t budget = failing_budget(settings.max_failing_fraction, pixels);

  // 1. finite
  result.test_non_finite = count_non_finite(test);
  result.reference_non_finite = count_non_finite(reference);
  result.layers.push_back(finite_layer(result.test_non_finite, result.reference_non_finite));
  const bool finite = result.layers.back().verdict == Verdict::Pass;

  // 2. exact
  const bool identical = bitwise_equal(test, reference);
  // Not identical is no failure: the exact layer is the fast path, and the next layer decides.
  result.layers.push_back(
      identical ? LayerResult{"exact", Verdict::Pass, "bit-identical"}
                : LayerResult{"exact", Verdict::Skipped,
                              fmt::format("not bit-identical; the {} layer decides",
                                          settings.metric ? metric_name(settings.metric->metric) : "per-pixel")});

  // 3. per_pixel, with the summary's sums and the heat map from the same pass
  // Without its palette (the image library could not be loaded) there is no heat map; whoever
  // writes one fails on the same library with its reason.
  auto palette = heat_map ? heat_palette(tolerance) : std::array<glm::vec4, 256>{};
  if (heat_map && palette) result.heat_map = FloatImage(test.width, test.height);
  PixelPass pass = compare_pixels(test, reference, tolerance, palette ? *palette : std::array<glm::vec4, 256>{},
                                  heat_map && palette ? &result.heat_map : nullptr);
  const size_t failing = pass.failing.size();
  const bool per_pixel_passed = failing <= budget;
  if (identical) {
    result.layers.push_back({"per_pixel", Verdict::Skipped, "bit-identical"});
  } else {
    result.layers.push_back({"per_pixel", per_pixel_passed ? Verdict::Pass : Verdict::Fail,
                             fmt::format("{} of {} differ by more than {} ({}); worst {} at ({}, {})", failing,
                                         plural(pixels, "pixel", "pixels"), tolerance_steps,
                                         describe_budget(settings, budget), plural(pass.worst_steps, "step", "steps"),
                                         pass.worst_pixel % test.width, pass.worst_pixel / test.width)});
  }

  // 4. position
  bool position_passed = per_pixel_passed;
  if (identical) {
    result.layers.push_back({"position", Verdict::Skipped, "bit-identical"});
  } else if (settings.position_radius == 0) {
    result.layers.push_back({"position", Verdict::Skipped, "position_radius is 0"});
  } else {
    const size_t forgiven =
        forgiven_pixels(pass.failing, encode_8bit(test), encode_8bit(reference), test.width, test.height, settings);
    const size_t remaining = failing - forgiven;
    position_passed = remaining <= budget;
    result.layers.push_back(
        {"position", position_passed ? Verdict::Pass : Verdict::Fail,
         fmt::format("{} of {} failing pixels match a reference pixel within {} and {}; {} remain ({})", forgiven,
                     failing, plural(settings.position_radius, "pixel", "pixels"), tolerance_steps, remaining,
                     describe_budget(settings, budget))});
  }

  // 5. float: the values above 1, which the 8-bit layers see as 255 whatever they are.
  FloatPass hdr;
  bool float_passed = true;
  if (identical) {
    result.layers.push_back({"float", Verdict::Skipped, "bit-identical"});
  } else {
    hdr = compare_hdr(test, reference, settings.float_tolerance);
    float_passed = hdr.failing.size() <= budget;
    if (hdr.values == 0)
      result.layers.push_back({"float", Verdict::Pass, "no value above 1 in either image"});
    else
      result.layers.push_back(
          {"float", float_passed ? Verdict::Pass : Verdict::Fail,
           fmt::format("{} of {} with values above 1 differ by more than {:g} relative ({}); worst {:.4g} at ({}, {})",
                       hdr.failing.size(), plural(hdr.values, "value", "values"), settings.float_tolerance,
                       describe_budget(settings, budget), hdr.max_relative, hdr.max_pixel % test.width,
                       hdr.max_pixel / test.width)});
  }

  // 5. the scene's perceptual metric, which decides in place of layers 3 and 4 (identical images
  // need no measuring: no metric finds a difference there).
  std::optional<Verdict> metric_verdict;
  if (settings.metric) {
    const std::string name(metric_name(settings.metric->metric));
    MetricFigures figures{name, settings.metric->metric == Metric::Ssim ? 1.0 : 0.0, settings.metric->threshold, {}};
    if (identical) {
      result.layers.push_back({name, Verdict::Skipped, "bit-identical"});
    } else if (auto measured = run_metric(test, reference, *settings.metric)) {
      if (heat_map)
        if (auto image = harness::metric_heat_map(*measured)) result.metric_heat_map = std::move(*image);
      figures = std::move(measured->figures);
      metric_verdict = measured->layer.verdict;
      result.layers.push_back(std::move(measured->layer));
    } else {
      metric_verdict = Verdict::Fail;  // what cannot be measured has not passed
      result.layers.push_back({name, Verdict::Fail, measured.error().message});
    }
    result.metrics.metric = std::move(figures);
  }

  // The first layer that settles the question decides: a non-finite value fails whatever the
  // differences are, a scene's metric decides what is left, the position layer only matters when
  // the per-pixel layer failed, and the float layer when the displayable range passed.
  auto decide = [&](bool passed, std::string layer) {
    result.verdict = passed ? Verdict::Pass : Verdict::Fail;
    result.decided_by = std::move(layer);
  };
  const bool displayable_passed = per_pixel_passed || (settings.position_radius > 0 && position_passed);
  if (!finite)
    decide(false, "finite");
  else if (identical)
    decide(true, "exact");
  else if (metric_verdict)
    decide(*metric_verdict == Verdict::Pass, std::string(metric_name(settings.metric->metric)));
  else if (!displayable_passed)
    decide(false, settings.position_radius == 0 ? "per_pixel" : "position");
  else if (!float_passed)
    decide(false, "float");
  else
    decide(true, per_pixel_passed ? "per_pixel" : "position");

  // 6. summary
  ImageMetrics& metrics = result.metrics;
  const ImageDifference largest = max_difference(test, reference);
  metrics.max_difference = largest.max;
  metrics.max_x = largest.x;
  metrics.max_y = largest.y;
  if (pass.finite_pairs > 0) {
    metrics.mean = pass.sum_absolute / double(pass.finite_pairs);
    metrics.rmse = std::sqrt(pass.sum_squared / double(pass.finite_pairs));
  }
  const double mean_squared_steps = pixels > 0 ? pass.sum_squared_steps / double(pixels * 4) : 0.0;
  metrics.psnr = mean_squared_steps > 0.0 ? 10.0 * std::log10(255.0 * 255.0 / mean_squared_steps)
                                          : std::numeric_limits<double>::infinity();
  metrics.failing_pixels = failing;
  metrics.failing_fraction = pixels > 0 ? double(failing) / double(pixels) : 0.0;
  metrics.max_steps = pass.worst_steps;
  metrics.worst_x = uint32_t(pass.worst_pixel % test.width);
  metrics.worst_y = uint32_t(pass.worst_pixel / test.width);
  if (pixels > 0) {
    std::copy_n(&test.rgba[pass.worst_pixel * 4], 4, metrics.worst_test.begin());
    std::copy_n(&reference.rgba[pass.worst_pixel * 4], 4, metrics.worst_reference.begin());
  }
  metrics.mean_steps = pixels > 0 ? pass.sum_steps / double(pixels * 4) : 0.0;
  metrics.rmse_steps = std::sqrt(mean_squared_steps);
  if (!pass.failing.empty())
    metrics.first_failing = {pass.failing.front() % test.width, pass.failing.front() / test.width};
  metrics.hdr_values = hdr.values;
  metrics.float_failing_pixels = hdr.failing.size();
  metrics.float_max_relative = hdr.max_relative;
  metrics.float_x = uint32_t(hdr.max_pixel % test.width);
  metrics.float_y = uint32_t(hdr.max_pixel / test.width);
  std::string summary = fmt::format(
      "in 8-bit sRGB steps, the per-pixel layer's values: worst {} at ({}, {}); mean {:.4g}; RMSE {:.4g}; PSNR {:.2f} "
      "dB; "
      "{} ({:.4g}%) differ by more than {}",
      plural(metrics.max_steps, "step", "steps"), metrics.worst_x, metrics.worst_y, metrics.mean_steps,
      metrics.rmse_steps, metrics.psnr, plural(failing, "pixel", "pixels"), metrics.failing_fraction * 100.0,
      tolerance_steps);
  if (metrics.first_failing)
    summary += fmt::format(", the first at ({}, {})", metrics.first_failing->first, metrics.first_failing->second);
  if (hdr.values > 0)
    summary +=
        fmt::format("; above 1, relative: worst {:.4g} at ({}, {}), {} beyond {:g}", hdr.max_relative, metrics.float_x,
                    metrics.float_y, plural(hdr.failing.size(), "pixel", "pixels"), settings.float_tolerance);
  result.layers.push_back({"summary", Verdict::Pass, std::move(summary)});
  result.failing_pixels = std::move(pass.failing);
  return result;
}

std::string describe_metrics(const ImageMetrics& metrics) {
  std::string text =
      fmt::format("worst {} sRGB steps at ({}, {}), {} failing pixels ({:.3g}%)", metrics.max_steps, metrics.worst_x,
                  metrics.worst_y, metrics.failing_pixels, metrics.failing_fraction * 100.0);
  if (metrics.float_failing_pixels > 0)
    text += fmt::format("; above 1: {} pixels beyond the float tolerance, worst {:.4g} relative at ({}, {})",
                        metrics.float_failing_pixels, metrics.float_max_relative, metrics.float_x, metrics.float_y);
  return text;
}

std::string describe_non_finite(const NonFiniteCount& count) {
  return fmt::format("{} NaN, {} Inf, {} negative channel values, first at ({}, {})", count.nan, count.inf,
                     count.negative, count.first->first, count.first->second);
}

}  // namespace xshade::harness
