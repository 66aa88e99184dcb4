// Runs the stability suite: every case, form, lane and precision asked for, and how each result
// compares with its prediction.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stability/case.h"

namespace xshade::stability {

// One case in one form on one lane at one precision.
struct Outcome {
  std::string case_id;
  std::string section;
  std::string form;
  bool seed = false;
  harness::Lane lane = harness::Lane::Gl;
  Precision precision = Precision::Float;
  std::vector<Measurement> measurements;
  std::optional<std::string> error;  // the case could not run
  Prediction prediction;

  // The inputs whose measurements broke their bound.
  std::set<std::string> failing_inputs() const;
  // It ran, and failed exactly where predicted (nowhere, for a form predicted to hold).
  bool as_predicted() const;
  // For an outcome not as predicted: the case, its inputs and the values that broke the bounds
  // (or the inputs that were predicted to break and did not), one per line.
  std::string explain() const;
};

struct SuiteOptions {
  std::vector<harness::Lane> lanes;   // empty: every lane
  harness::BackendOptions backend;    // how each lane's backend is made (validation, the gl route)
  std::vector<Precision> precisions;  // empty: both
  std::vector<std::string> case_ids;  // empty: every case
  std::filesystem::path shaders_dir;
  std::filesystem::path probes_dir;
  std::filesystem::path scenes_dir;
  std::function<void(const std::string&)> progress;  // one line per case and lane; may be empty
};

struct SuiteRun {
  std::vector<Outcome> outcomes;
  std::vector<std::pair<harness::Lane, harness::DriverInfo>> drivers;
  std::vector<std::string> skipped;  // what did not run and why (vk-hlsl in half emulation)
  size_t unexpected() const;
};

// Fails only when a lane's backend cannot be created or a case id is unknown; a case that cannot
// run is an Outcome with an error.
Result<SuiteRun> run_suite(const std::vector<Case>& cases, const SuiteOptions& options);

// The suite's result as docs/stability.md keeps it.
std::string stability_markdown(const std::vector<Case>& cases, const SuiteRun& run, const std::string& command_line);

}  // namespace xshade::stability
