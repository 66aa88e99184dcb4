// xshade report merge: the reports of several runs (the shards of a CI matrix, the per-test
// folders of a CTest run) as one report, with one index, one junit.xml and one results.json.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <memory>
#include <system_error>

#include "base/file_io.h"
#include "cli/commands.h"
#include "harness/report/report.h"
#include "harness/report/report_lock.h"
#include "harness/report/report_merge.h"
#include "harness/report/report_text.h"

namespace xshade::cli {

namespace fs = std::filesystem;

int run_report_merge(const ReportMergeOptions& options) {
  auto found = harness::find_reports(options.folders);
  if (!found) {
    fmt::print(stderr, "xshade report merge: {}\n", found.error().to_string());
    return kBadInput;
  }
  // Writing into a report being read would mix the merge with its own input.
  std::error_code error;
  for (const harness::FoundReport& report : *found)
    if (fs::equivalent(report.folder, options.out, error)) {
      fmt::print(stderr,
                 "xshade report merge: --out {} is one of the reports being merged; merge into another folder\n",
                 options.out.string());
      return kBadInput;
    }

  // A run or another merge into the same folder would leave a report that is neither.
  auto lock = harness::ReportLock::take(options.out, options.command_line);
  if (!lock) {
    fmt::print(stderr, "xshade report merge: {}\n", lock.error().to_string());
    return lock.error().kind == ErrorKind::Backend ? kBackendError : kBadInput;
  }

  harness::MergedReport merged = harness::merge_reports(*found);
  merged.results.command = options.command_line;
  for (const harness::MergedFile& file : merged.files) {
    const fs::path to = options.out / file.to;
    fs::create_directories(to.parent_path(), error);
    // Whole or not at all (a full disk leaves no truncated image).
    if (auto copied = copy_file_whole(file.from, to); !copied) {
      fmt::print(stderr, "xshade report merge: cannot copy {}: {}\n", file.from.string(), copied.error().message);
      return kBackendError;
    }
  }
  if (options.cross_lane)
    for (std::string& warning : harness::compare_lanes_across_reports(merged.results, options.out))
      merged.warnings.push_back(std::move(warning));
  for (const std::string& warning : merged.warnings) fmt::print(stderr, "warning: {}\n", warning);
  if (auto written = harness::write_reports(merged.results, options.out); !written) {
    fmt::print(stderr, "xshade report merge: {}\n", written.error().to_string());
    return kBackendError;
  }

  const harness::VerdictCounts scenes = harness::count_scenes(merged.results);
  const harness::VerdictCounts checks = harness::count_checks(merged.results);
  const harness::Verdict verdict = harness::run_verdict(merged.results);
  fmt::print(
      "merged {} reports: {} scenes ({} pass, {} fail, {} error, {} crash, {} skipped), {} checks ({} pass); {}\n",
      found->size(), scenes.total(), scenes.pass, scenes.fail, scenes.error, scenes.crash, scenes.skipped,
      checks.total(), checks.pass, harness::verdict_name(verdict));
  fmt::print("report: {}\n", (options.out / "index.html").string());
  return options.exit_code ? harness::exit_code(verdict) : kPass;
}

Verb add_report_command(CLI::App& app) {
  auto options = std::make_shared<ReportMergeOptions>();
  CLI::App* report = app.add_subcommand("report", "Work on reports that runs wrote");
  report->require_subcommand(1);
  CLI::App* merge = report->add_subcommand(
      "merge",
      "Merge the reports of several runs (the shards of a CI matrix, a CTest run's per-test folders) into "
      "one index, junit.xml and results.json");
  merge
      ->add_option("report", options->folders,
                   "A report folder (it holds results.json), or a folder of them (each of its folders that holds one)")
      ->required()
      ->type_name("DIR");
  merge->add_option("--out", options->out, "Folder for the merged report")->required()->type_name("DIR");
  merge->add_flag("--cross-lane", options->cross_lane,
                  "Hold the lanes of each scene whose lanes came from separate runs (one per lane, as CTest's tests) "
                  "against each other, as one run of all of them would");
  merge->add_flag("--exit-code", options->exit_code,
                  "Exit with the merged results' code, as xshade run would (default: 0 once the report is written)");
  return {merge, [options](const std::string& command_line) {
            options->command_line = command_line;
            return run_report_merge(*options);
          }};
}

}  // namespace xshade::cli
