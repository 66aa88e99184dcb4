// xshade stability: the hard numeric cases of SHADERS.md section 5 on every lane and precision.
#include <fmt/core.h>

#include "base/file_io.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "stability/cases.h"
#include "stability/suite.h"

namespace xshade::cli {

int run_stability(const StabilityOptions& options) {
  const std::vector<stability::Case> cases = stability::all_cases();
  if (options.list) {
    for (const stability::Case& c : cases) {
      std::string forms;
      for (const stability::Form& form : c.forms) forms += (forms.empty() ? "" : ", ") + form.name;
      fmt::print("{:<26} {:<5} {}\n{:<32} forms: {}\n", c.id, c.section, c.title, "", forms);
    }
    return kPass;
  }
  auto lanes = resolve_lanes(options.selection);
  if (!lanes) {
    fmt::print(stderr, "xshade stability: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  stability::SuiteOptions suite;
  suite.lanes = *lanes;
  suite.backend = backend_options(options.selection);
  if (options.precision == "float") suite.precisions = {stability::Precision::Float};
  if (options.precision == "half") suite.precisions = {stability::Precision::Half};
  suite.case_ids = options.cases;
  suite.shaders_dir = options.shaders_dir;
  suite.probes_dir = options.probes_dir;
  suite.scenes_dir = options.scenes_dir;
  suite.progress = [](const std::string& line) {
    fmt::print("{}\n", line);
    std::fflush(stdout);
  };
  auto run = stability::run_suite(cases, suite);
  if (!run) {
    fmt::print(stderr, "xshade stability: {}\n", run.error().to_string());
    // A case that does not exist is the user's; anything else is a lane that could not run.
    return run.error().kind == ErrorKind::Usage ? kBadInput : kBackendError;
  }
  for (const std::string& skipped : run->skipped) fmt::print("skipped: {}\n", skipped);
  if (!options.markdown.empty()) {
    if (auto written =
            write_file_atomically(options.markdown, stability::stability_markdown(cases, *run, options.command_line));
        !written) {
      fmt::print(stderr, "xshade stability: {}\n", written.error().to_string());
      return kBackendError;
    }
    fmt::print("wrote {}\n", options.markdown.string());
  }
  bool could_not_run = false;
  for (const stability::Outcome& outcome : run->outcomes)
    if (!outcome.as_predicted()) {
      fmt::print("{}", outcome.explain());
      could_not_run = could_not_run || outcome.error.has_value();
    }
  fmt::print("{} outcomes, {} not as predicted\n", run->outcomes.size(), run->unexpected());
  if (could_not_run) return kBackendError;
  return run->unexpected() == 0 ? kPass : kTestFailed;
}

}  // namespace xshade::cli
