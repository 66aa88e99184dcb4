// xshade accuracy: for each knob of SHADERS.md section 6, error against a reference and time, per
// lane, as tables and Pareto charts.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <memory>

#include "accuracy/accuracy_report.h"
#include "base/file_io.h"
#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"

namespace xshade::cli {
namespace {

bool write(const std::filesystem::path& path, const std::string& text) {
  std::error_code ignored;
  std::filesystem::create_directories(path.parent_path(), ignored);
  if (auto written = write_file_atomically(path, text); !written) {
    fmt::print(stderr, "xshade accuracy: {}\n", written.error().to_string());
    return false;
  }
  return true;
}

}  // namespace

int run_accuracy(const AccuracyOptions& options) {
  std::vector<accuracy::Study> studies;
  for (accuracy::Study& study : accuracy::all_studies()) {
    const bool named = std::find(options.studies.begin(), options.studies.end(), study.id) != options.studies.end();
    // A study of Unity shaders runs only when named: its scene needs Unity's include files.
    const bool by_default = !study.unity && (!options.quick || study.quick);
    if (options.studies.empty() ? by_default : named) studies.push_back(std::move(study));
  }
  for (const std::string& id : options.studies)
    if (std::none_of(studies.begin(), studies.end(), [&](const accuracy::Study& s) { return s.id == id; })) {
      std::string known;
      for (const accuracy::Study& s : accuracy::all_studies()) known += (known.empty() ? "" : ", ") + s.id;
      fmt::print(stderr, "xshade accuracy: no study '{}'; the studies are: {}\n", id, known);
      return kBadInput;
    }
  auto lanes = resolve_lanes(options.selection);
  if (!lanes) {
    fmt::print(stderr, "xshade accuracy: {}\n", lanes.error().to_string());
    return kBadInput;
  }

  accuracy::AccuracyRun run;
  run.command_line = options.command_line;
  run.options.scenes_dir = options.scenes_dir;
  run.options.shaders_dir = options.shaders_dir;
  run.options.shader_folders = options.shader_folders;
  run.options.rounds = options.quick ? 1 : options.rounds;
  run.options.reference_check = !options.quick;
  for (harness::Lane lane : *lanes) {
    auto backend = harness::create_backend(lane, backend_options(options.selection));
    if (!backend) {
      fmt::print(stderr, "xshade accuracy: {}: {}\n", harness::lane_name(lane), backend.error().to_string());
      return kBackendError;
    }
    run.drivers.emplace_back(lane, (*backend)->driver_info());
    for (const accuracy::Study& study : studies) {
      auto result = accuracy::measure_study(study, lane, **backend, run.options);
      if (!result) {
        fmt::print(stderr, "xshade accuracy: {} on {}: {}\n", study.id, harness::lane_name(lane),
                   result.error().to_string());
        return kBackendError;
      }
      std::string line = fmt::format("{} on {}:", study.id, harness::lane_name(lane));
      for (const accuracy::ConfigurationResult& c : result->configurations)
        line += fmt::format(" {} {:.3g} in {:.2f} ms;", c.label, accuracy::chart_error(c), c.time.median_ms);
      fmt::print("{}\n", line);
      std::fflush(stdout);
      for (const std::string& message : (*backend)->take_driver_messages())
        fmt::print("{}: driver message: {}\n", harness::lane_name(lane), message);
      run.results.push_back(std::move(*result));
    }
  }
  run.studies = std::move(studies);

  bool written = write(options.report_dir / "accuracy.csv", accuracy::accuracy_csv(run)) &&
                 write(options.report_dir / "index.html", accuracy::accuracy_html(run, "charts"));
  for (const accuracy::Study& study : run.studies)
    written =
        written && write(options.report_dir / "charts" / (study.id + ".svg"), accuracy::study_chart_svg(study, run));
  if (!options.markdown.empty()) {
    // The charts go beside the Markdown file, in a folder named after it.
    const std::string chart_dir = options.markdown.stem().string();
    written = written && write(options.markdown, accuracy::accuracy_markdown(run, chart_dir));
    for (const accuracy::Study& study : run.studies)
      written = written && write(options.markdown.parent_path() / chart_dir / (study.id + ".svg"),
                                 accuracy::study_chart_svg(study, run));
  }
  if (!written) return kBackendError;
  fmt::print("report: {}\n", (options.report_dir / "index.html").string());

  bool converged = true;
  for (const accuracy::StudyResult& result : run.results)
    if (auto c = accuracy::convergence(result); c && !c->converged) {
      fmt::print(
          "{} on {}: the reference does not converge: its check differs by {:.3g}, more than the smallest error it "
          "judges ({:.3g})\n",
          result.study, harness::lane_name(result.lane), c->check_error, c->smallest_error);
      converged = false;
    }
  return converged ? kPass : kTestFailed;
}

Verb add_accuracy_command(CLI::App& app) {
  auto options = std::make_shared<AccuracyOptions>();
  CLI::App* accuracy = app.add_subcommand(
      "accuracy",
      "For each accuracy knob (DoF kernel, BRDF forms, precision, indirect specular, supersampling, "
      "shadow-map resolution), render its scene in every configuration on each lane and measure error "
      "against a reference and time; tables and Pareto charts");
  accuracy
      ->add_option("study", options->studies,
                   "Study ids (dof_kernel, brdf_forms, precision, indirect_specular, supersampling, shadow_map); "
                   "default: all but shadow_map, whose scene of Unity shaders needs --scenes and --shader-folder")
      ->type_name("STUDY");
  add_lane_options(*accuracy, options->selection);
  accuracy->add_flag("--quick", options->quick, "One round of timing, no reference check, and only the quick studies");
  accuracy
      ->add_option("--rounds", options->rounds,
                   "Rounds of timing: the configurations take turns, each turn 1 warm-up frame and 3 timed frames")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  accuracy->add_option("--report", options->report_dir, "Folder for index.html, accuracy.csv and charts/")
      ->type_name("DIR")
      ->capture_default_str();
  accuracy
      ->add_option("--markdown", options->markdown,
                   "Also write the tables as Markdown, with the charts in a folder beside it named after it "
                   "(docs/accuracy.md is this output)")
      ->type_name("FILE");
  accuracy
      ->add_option("--scenes", options->scenes_dir,
                   "Folder of the studies' scenes (default: xshade's own fixed scenes)")
      ->type_name("DIR");
  accuracy->add_option("--shaders", options->shaders_dir, "The shader library (default: xshade's own)")
      ->type_name("DIR");
  accuracy
      ->add_option("--shader-folder", options->shader_folders,
                   "A shader folder searched before the library; repeat for more (a study of Unity shaders, named "
                   "on the command line, needs its .shader files and Unity's include files)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  return {accuracy, [options](const std::string& command_line) {
            options->command_line = command_line;
            return run_accuracy(*options);
          }};
}

}  // namespace xshade::cli
