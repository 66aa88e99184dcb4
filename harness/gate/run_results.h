// What a run found, scene by scene and lane by lane: the model every report (HTML, JUnit XML,
// JSON) is written from, and the exit code decided by.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/image/image_compare.h"  // Verdict, LayerResult, ImageMetrics
#include "harness/render/nonfinite_origins.h"

namespace xshade::harness {

struct PassTime {
  std::string pass;
  double milliseconds = 0.0;
};

// Where one pass's non-finite pixels were born (render/nonfinite_origins.h), as a report shows it.
struct PassOrigins {
  std::string pass;
  bool output = false;  // the last pass: its image is the lane's, and its counts add up to the finite layer's
  std::vector<NonfiniteOrigin> origins;  // most pixels first
  size_t unattributed_pixels = 0;
  size_t recovered_pixels = 0;
  std::string map;  // the origins map's PNG, relative to the report folder
};

// The lane rendered again with the tracing variant: because its finite layer failed, or because
// the run asked (--trace-nonfinite).
struct NonfiniteTraceResult {
  // The output's pass first, then each earlier pass whose image has non-finite pixels, in order.
  std::vector<PassOrigins> passes;
  double traced_milliseconds = 0.0;  // the traced render, start to read-back
  double plain_milliseconds = 0.0;   // the plain render's passes (the lane's timings)
  bool identical = true;             // the traced image bit-identical to the plain one
  std::string traced_image;          // where it is not: the traced image's EXR in the report
  std::string note;                  // set when the lane was not traced, saying why
};

struct LaneResult {
  std::string lane;
  Verdict verdict = Verdict::Pass;
  std::vector<LayerResult> layers;  // in the order they ran
  std::optional<ImageMetrics> against_golden;
  NonFiniteCount non_finite;
  // Files, relative to the report folder; empty when there is none.
  std::string image;            // the lane's PNG
  std::string image_exr;        // the lane's float image
  std::string golden;           // the golden it was compared with (a copy in the report)
  std::string golden_exr;       // the golden's float image, where it has one (values above 1)
  std::string diff;             // heat map of the difference against the golden
  std::string metric_map;       // heat map of the scene's metric against the golden, when it chose one
  std::string non_finite_mask;  // white where NaN/Inf/negative values are
  std::vector<PassTime> timings;
  double seconds = 0.0;  // compile + render + checks
  DriverInfo driver;
  std::string message;  // an error's text, or what failed, for a reviewer
  std::optional<NonfiniteTraceResult> trace;
};

struct CrossLaneResult {
  std::string first_lane;
  std::string second_lane;
  Verdict verdict = Verdict::Pass;
  ImageMetrics metrics;
  std::string diff;        // heat map, relative to the report folder; none for identical images
  bool identical = false;  // bit-identical images (a heat map of them would be black)
};

struct SceneResult {
  std::string scene;
  std::string description;
  Verdict verdict = Verdict::Pass;  // the worst of its lanes and cross-lane checks
  std::vector<LaneResult> lanes;
  std::vector<CrossLaneResult> cross_lane;
  std::string plan;  // describe_plan's text
  // The front end's warnings about the scene's sources (Plan::warnings): run prints them, the
  // report shows them.
  std::vector<std::string> warnings;
  std::string message;      // when the scene failed before any lane ran (bad scene file, bad shader)
  CompareSettings compare;  // the tolerances its images were held to
};

// One of the runs a merged report was made from (xshade report merge).
struct MergedRun {
  std::string folder;  // as given to the merge
  std::string started;
  double seconds = 0.0;
  std::string command;
};

struct RunResults {
  std::vector<SceneResult> scenes;
  std::string started;  // ISO 8601, UTC
  double seconds = 0.0;
  std::string command;                 // how the run was invoked
  std::vector<MergedRun> merged_from;  // empty for a run; the runs a merged report holds
};

// The exit code of DESIGN.md for a verdict (0 pass, 1 fail, 2 error, 3 crash).
int exit_code(Verdict verdict);
Verdict worst(Verdict a, Verdict b);

}  // namespace xshade::harness
