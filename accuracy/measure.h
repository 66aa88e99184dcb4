// Measuring a study on one lane: each configuration's error against the reference, and its time.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "accuracy/study.h"
#include "harness/backend/backend.h"
#include "harness/gate/run_results.h"
#include "harness/image/image.h"
#include "harness/render/lanes.h"

namespace xshade::accuracy {

struct Timing {
  double median_ms = 0.0;
  double q1_ms = 0.0;  // the quartiles of the repetitions: the spread shown beside the median
  double q3_ms = 0.0;
  size_t repetitions = 0;
};

struct ConfigurationResult {
  std::string label;
  harness::ImageMetrics error;    // against the reference, on this lane
  double failing_fraction = 0.0;  // of pixels beyond the scene's tolerance
  Timing time;                    // of the study's timed passes, warm-up excluded
  double compile_ms = 0.0;        // every variant of the configuration, no cache
  harness::FloatImage image;      // at the scene's size
};

struct StudyResult {
  std::string study;
  harness::Lane lane;
  ConfigurationResult reference;
  std::optional<ConfigurationResult> reference_check;  // its error is against the reference
  std::vector<ConfigurationResult> configurations;
  std::vector<std::string> skipped;  // configurations this lane cannot run, and why
};

struct MeasureOptions {
  std::filesystem::path scenes_dir;
  std::filesystem::path shaders_dir;
  std::vector<std::filesystem::path> shader_folders;  // searched before shaders_dir
  // Timing: `rounds` turns through the configurations; each turn renders `warmup_frames` untimed
  // (the first makes the scene's resources again) and then `frames_per_round` timed frames.
  uint32_t rounds = 5;
  uint32_t warmup_frames = 1;
  uint32_t frames_per_round = 3;
  bool reference_check = true;
};

Result<StudyResult> measure_study(const Study& study, harness::Lane lane, harness::Backend& backend,
                                  const MeasureOptions& options);

// The quartiles and median of `samples` (linear interpolation between order statistics).
Timing summarize(std::vector<double> samples);

// The mean of every k x k block: a supersampled render brought to its scene's size.
harness::FloatImage box_downsample(const harness::FloatImage& image, uint32_t k);

}  // namespace xshade::accuracy
