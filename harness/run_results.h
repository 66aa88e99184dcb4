// What a run found, scene by scene and lane by lane: the model every report (HTML, JUnit XML,
// JSON) is written from, and the exit code decided by.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "harness/backend.h"

namespace xshade::harness {

enum class Verdict {
  Pass,
  Fail,     // a check failed (exit 1)
  Error,    // bad input: a scene or shader that does not load or compile (exit 2)
  Crash,    // a backend or internal error (exit 3)
  Skipped,  // not run (e.g. the lane is not selected)
};
std::string_view verdict_name(Verdict verdict);  // "pass", "fail", "error", "crash", "skipped"

// One layer of the comparison model (DESIGN.md), or one of the other gate layers:
// "finite", "exact", "per_pixel", "position", "summary", "cross_lane", "determinism".
struct LayerResult {
  std::string layer;
  Verdict verdict = Verdict::Pass;
  std::string detail;  // one line a reviewer reads: what was measured against what bound
};

struct ImageMetrics {
  double max_difference = 0.0;  // linear, largest over channels
  uint32_t max_x = 0;
  uint32_t max_y = 0;
  double mean = 0.0;            // mean absolute difference, linear
  double rmse = 0.0;
  double psnr = 0.0;            // dB, on the 8-bit sRGB images; infinite when identical
  size_t failing_pixels = 0;    // beyond the channel tolerance
  double failing_fraction = 0.0;
};

struct NonFiniteCount {
  size_t nan = 0;
  size_t inf = 0;
  size_t negative = 0;
  std::optional<std::pair<uint32_t, uint32_t>> first;  // (x, y) of the first such pixel
  size_t total() const { return nan + inf + negative; }
};

struct PassTime {
  std::string pass;
  double milliseconds = 0.0;
};

struct LaneResult {
  std::string lane;
  Verdict verdict = Verdict::Pass;
  std::vector<LayerResult> layers;      // in the order they ran
  std::optional<ImageMetrics> against_golden;
  NonFiniteCount non_finite;
  // Files, relative to the report folder; empty when there is none.
  std::string image;          // the lane's PNG
  std::string image_exr;      // the lane's float image
  std::string golden;         // the golden it was compared with (a copy in the report)
  std::string diff;           // heat map of the difference against the golden
  std::string non_finite_mask;  // white where NaN/Inf/negative values are
  std::vector<PassTime> timings;
  double seconds = 0.0;       // compile + render + checks
  DriverInfo driver;
  std::string message;        // an error's text, or what failed, for a reviewer
};

struct CrossLaneResult {
  std::string first_lane;
  std::string second_lane;
  Verdict verdict = Verdict::Pass;
  ImageMetrics metrics;
  std::string diff;  // heat map, relative to the report folder
};

struct SceneResult {
  std::string scene;
  std::string description;
  Verdict verdict = Verdict::Pass;  // the worst of its lanes and cross-lane checks
  std::vector<LaneResult> lanes;
  std::vector<CrossLaneResult> cross_lane;
  std::string plan;     // describe_plan's text
  std::string message;  // when the scene failed before any lane ran (bad scene file, bad shader)
};

struct RunResults {
  std::vector<SceneResult> scenes;
  std::string started;     // ISO 8601, UTC
  double seconds = 0.0;
  std::string command;     // how the run was invoked
};

// The exit code of DESIGN.md for a verdict (0 pass, 1 fail, 2 error, 3 crash).
int exit_code(Verdict verdict);
Verdict worst(Verdict a, Verdict b);

}  // namespace xshade::harness
