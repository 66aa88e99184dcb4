// xshade stability: the hard numeric cases of SHADERS.md section 5 on every lane and precision.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <memory>

#include "base/file_io.h"
#include "cli/command_options.h"
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

Verb add_stability_command(CLI::App& app) {
  auto options = std::make_shared<StabilityOptions>();
  CLI::App* stability = app.add_subcommand(
      "stability",
      "Run the library's shader code on the hard numeric cases of SHADERS.md section 5 and check each "
      "case's property on every lane, in fp32 and in fp16 emulation");
  stability->add_option("case", options->cases, "Case ids (see --list); default: every case")->type_name("CASE");
  add_lane_options(*stability, options->selection);
  stability
      ->add_option("--precision", options->precision,
                   "float, half (fp16 emulation on gl and vk; vk-hlsl cannot) or all")
      ->check(CLI::IsMember({"float", "half", "all"}))
      ->capture_default_str();
  stability->add_flag("--list", options->list, "Print the cases with their forms and run nothing");
  stability
      ->add_option("--markdown", options->markdown, "Write the results as Markdown (docs/stability.md is this output)")
      ->type_name("FILE");
  stability->add_option("--shaders", options->shaders_dir, "The shader library (default: xshade's own)")
      ->type_name("DIR");
  stability->add_option("--probes", options->probes_dir, "The suite's probe shaders (default: xshade's own)")
      ->type_name("DIR");
  stability
      ->add_option("--scenes", options->scenes_dir,
                   "Folder of the scenes the suite renders (default: xshade's own fixed scenes)")
      ->type_name("DIR");
  return {stability, [options](const std::string& command_line) {
            options->command_line = command_line;
            return run_stability(*options);
          }};
}

}  // namespace xshade::cli
