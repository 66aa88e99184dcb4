#include "harness/report_text.h"

#include <cmath>

#include <fmt/format.h>

namespace xshade::harness {

void VerdictCounts::add(Verdict verdict) {
  switch (verdict) {
    case Verdict::Pass: ++pass; break;
    case Verdict::Fail: ++fail; break;
    case Verdict::Error: ++error; break;
    case Verdict::Crash: ++crash; break;
    case Verdict::Skipped: ++skipped; break;
  }
}

VerdictCounts count_scenes(const RunResults& results) {
  VerdictCounts counts;
  for (const SceneResult& scene : results.scenes) counts.add(scene.verdict);
  return counts;
}

VerdictCounts count_checks(const RunResults& results) {
  VerdictCounts counts;
  for (const SceneResult& scene : results.scenes) {
    for (const LaneResult& lane : scene.lanes) counts.add(lane.verdict);
    for (const CrossLaneResult& pair : scene.cross_lane) counts.add(pair.verdict);
  }
  return counts;
}

bool is_problem(Verdict verdict) {
  return verdict == Verdict::Fail || verdict == Verdict::Error || verdict == Verdict::Crash;
}

int urgency(Verdict verdict) {
  switch (verdict) {
    case Verdict::Crash: return 4;
    case Verdict::Error: return 3;
    case Verdict::Fail: return 2;
    case Verdict::Pass: return 1;
    case Verdict::Skipped: return 0;
  }
  return 4;
}

Verdict run_verdict(const RunResults& results) {
  Verdict verdict = Verdict::Pass;
  for (const SceneResult& scene : results.scenes) verdict = worst(verdict, scene.verdict);
  return verdict;
}

std::string first_failure(const LaneResult& lane) {
  if (lane.verdict == Verdict::Pass) return {};
  // The message names the layer that decided; a failing layer that did not decide (a per-pixel
  // failure the position layer forgave) is not the reason.
  if (!lane.message.empty()) return std::string(first_line(lane.message));
  for (const LayerResult& layer : lane.layers) {
    if (is_problem(layer.verdict)) return layer.detail.empty() ? layer.layer : layer.layer + ": " + layer.detail;
  }
  return {};
}

std::string pair_name(const CrossLaneResult& pair) { return pair.first_lane + " vs " + pair.second_lane; }

std::string describe_metrics(const ImageMetrics& metrics) {
  return fmt::format("max difference {:.4g} at ({}, {}), {} failing pixels ({:.3g}%)", metrics.max_difference,
                     metrics.max_x, metrics.max_y, metrics.failing_pixels, metrics.failing_fraction * 100.0);
}

std::string describe_psnr(double psnr) {
  // Identical images have an infinite PSNR; NaN would mean a broken measurement, shown as such.
  if (std::isinf(psnr) && psnr > 0) return "identical";
  return fmt::format("{:.2f} dB", psnr);
}

std::string describe_duration(double seconds) {
  if (seconds < 1.0) return fmt::format("{:.0f} ms", seconds * 1000.0);
  if (seconds < 60.0) return fmt::format("{:.1f} s", seconds);
  const double minutes = std::floor(seconds / 60.0);
  return fmt::format("{:.0f} min {:.1f} s", minutes, seconds - minutes * 60.0);
}

std::string_view first_line(std::string_view text) { return text.substr(0, text.find('\n')); }

}  // namespace xshade::harness
