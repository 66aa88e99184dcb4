// xshade run: check each scene on each of its lanes (against its golden, against the other
// lanes, against itself rendered twice), write the images and the reports, and exit with the
// worst verdict.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <map>
#include <memory>
#include <system_error>

#include "base/interrupt.h"
#include "base/subprocess.h"
#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "cli/scene_runs.h"
#include "cli/workers.h"
#include "harness/gate/scene_check.h"
#include "harness/render/driver_cache.h"
#include "harness/report/report.h"
#include "harness/report/report_lock.h"

namespace xshade::cli {
namespace {

namespace fs = std::filesystem;

// "i/N" with 1 <= i <= N.
Result<std::pair<size_t, size_t>> parse_shard(const std::string& shard) {
  size_t index = 0, count = 0;
  char slash = 0;
  int consumed = 0;
  if (std::sscanf(shard.c_str(), "%zu%c%zu%n", &index, &slash, &count, &consumed) != 3 || slash != '/' ||
      size_t(consumed) != shard.size() || count == 0 || index == 0 || index > count)
    return fail(ErrorKind::Usage, "--shard takes i/N with 1 <= i <= N, not '" + shard + "'");
  return std::pair{index, count};
}

}  // namespace

int run_run(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto inputs = resolve_scene_run(options.selection, options.folders, options.scenes,
                                  options.plan_only ? GoldenUse::None : GoldenUse::Read);
  if (!inputs) {
    fmt::print(stderr, "xshade run: {}\n", inputs.error().to_string());
    return kBadInput;
  }
  const std::vector<harness::Lane>& lanes = inputs->lanes;
  const SceneFolders& folders = inputs->folders;
  std::vector<fs::path>& files = inputs->files;
  if (!options.shard.empty()) {
    auto shard = parse_shard(options.shard);
    if (!shard) {
      fmt::print(stderr, "xshade run: {}\n", shard.error().to_string());
      return kBadInput;
    }
    // Every N-th scene in name order: a scene always lands in the same shard.
    std::vector<fs::path> mine;
    for (size_t i = 0; i < files.size(); ++i)
      if (i % shard->second == shard->first - 1) mine.push_back(files[i]);
    if (mine.empty()) {
      fmt::print(stderr, "xshade run: shard {} holds no scene: there are {} scenes, so N must be at most {}\n",
                 options.shard, files.size(), files.size());
      return kBadInput;
    }
    files = std::move(mine);
  }

  // Two runs into one report folder would leave one run's report saying it is both. A plan
  // writes no report, and takes no lock.
  std::optional<harness::ReportLock> report_lock;
  if (!options.plan_only) {
    auto taken = harness::ReportLock::take(options.report_dir, options.command_line);
    if (!taken) {
      fmt::print(stderr, "xshade run: {}\n", taken.error().to_string());
      return taken.error().kind == ErrorKind::Backend ? kBackendError : kBadInput;
    }
    report_lock = std::move(*taken);
  }
  const std::filesystem::path cache_dir =
      options.no_cache ? std::filesystem::path() : private_cache_dir(shader_cache_dir(options.cache_dir), "run");
  std::optional<harness::ShaderCache> cache;
  if (!cache_dir.empty()) cache.emplace(cache_dir, harness::compiler_identity());
  harness::VariantCompiler compiler(folders.shaders, cache ? &*cache : nullptr);
  const harness::GoldenStore goldens(folders.golden);
  const bool half = options.precision == "half";

  harness::RunResults results;
  results.started = utc_now();
  results.command = options.command_line;
  size_t done = 0;
  harness::SceneChecker checker(compiler,
                                {.report_dir = options.report_dir,
                                 .goldens = &goldens,
                                 .backend = backend_options(options.selection),
                                 .pass_images = options.pass_images,
                                 .plan_only = options.plan_only,
                                 .half_emulation = half,
                                 .trace_nonfinite = options.trace_nonfinite},
                                [&](const std::string& line) {
                                  fmt::print("[{}/{}] {}\n", done + 1, files.size(), line);
                                  std::fflush(stdout);
                                });
  std::vector<harness::ViewerPage> viewers;
  auto record = [&](harness::CheckedScene&& checked) {
    if (options.plan_only && checked.result.message.empty()) fmt::print("{}", checked.result.plan);
    if (!checked.result.message.empty())
      fmt::print(stderr, "xshade run: {}: {}\n", checked.result.scene, checked.result.message);
    print_lane_details("run", checked.result);
    // The page's viewer data now, from the renders in hand, while the workers go on.
    if (!options.plan_only) viewers.push_back(viewer_page_of(checked, options.report_dir));
    results.scenes.push_back(std::move(checked.result));
    ++done;
  };
  harness::WorkerTotals totals;
  if (options.plan_only) {
    for (const fs::path& file : files) record(checker.prepare(file, lanes));
  } else {
    const WorkerOptions shared{.shader_folders = folders.shaders.folders(),
                               .golden = folders.golden,
                               .report_dir = options.report_dir,
                               .cache_dir = cache_dir,
                               .gl_platform = options.selection.gl_platform,
                               .validation = options.selection.validation,
                               .pass_images = options.pass_images,
                               .half_emulation = half,
                               .trace_nonfinite = options.trace_nonfinite};
    catch_interrupts();
    totals = harness::check_in_workers(checker, scene_workers(shared, options.workers), files, lanes, record,
                                       [](const std::string& text) { fmt::print(stderr, "{}", text); });
    if (!cache_dir.empty()) harness::record_driver_cache(harness::driver_cache_folder(cache_dir));
    if (const int signal = interrupt_signal()) {
      fmt::print(stderr,
                 "xshade run: stopped by {} after {} of {} scenes; its workers and their files are gone, "
                 "and no report was written\n",
                 describe_signal(signal), results.scenes.size(), files.size());
      return kInterrupted + signal;
    }
  }
  results.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  harness::Verdict verdict = harness::Verdict::Pass;
  for (const harness::SceneResult& scene : results.scenes) verdict = harness::worst(verdict, scene.verdict);
  if (options.plan_only) return harness::exit_code(verdict);

  auto report_written = harness::write_reports(results, options.report_dir, &viewers);
  if (!report_written) {
    fmt::print(stderr, "xshade run: the report is not whole: {}\n", report_written.error().to_string());
    verdict = harness::worst(verdict, harness::Verdict::Crash);
  }
  size_t passed = 0;
  for (const harness::SceneResult& scene : results.scenes) passed += scene.verdict == harness::Verdict::Pass;
  fmt::print(
      "{} of {} scenes passed in {:.1f} s; {} renders in {} worker{}; shaders: {} compiled, {} from the cache{}\n",
      passed, results.scenes.size(), results.seconds, totals.renders, totals.workers_started,
      totals.workers_started == 1 ? "" : "s", totals.compiled, totals.cached,
      cache ? " (" + cache->directory().string() + ")" : std::string(" (cache off)"));
  if (!totals.cache_write_error.empty()) fmt::print("warning: {}\n", totals.cache_write_error);
  if (!totals.cache_damage.empty()) fmt::print("warning: {}\n", totals.cache_damage);
  if (report_written) fmt::print("report: {}\n", (options.report_dir / "index.html").string());
  return harness::exit_code(verdict);
}

Verb add_run_command(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* run =
      app.add_subcommand("run", "Render scenes on each of their lanes, write PNG and EXR images, compare the lanes");
  run->add_option("scene", options->scenes, "Scene names (in --scenes) or .toml files; default: every scene")
      ->type_name("SCENE");
  add_lane_options(*run, options->selection);
  run->add_option("--report", options->report_dir, "Folder for images and the report")
      ->type_name("DIR")
      ->capture_default_str();
  add_folder_options(*run, options->folders);
  run->add_option("--cache", options->cache_dir,
                  "Compiled-shader cache (default: $XSHADE_CACHE_DIR, else $XDG_CACHE_HOME/xshade or ~/.cache/xshade)")
      ->type_name("DIR");
  run->add_flag("--no-cache", options->no_cache, "Compile every shader, read and write no cache");
  run->add_option("--precision", options->precision,
                  "half: round every half/min16float/fixed result to fp16 on gl and vk (vk-hlsl is skipped); "
                  "goldens are fp32 renders and are not compared")
      ->check(CLI::IsMember({"float", "half"}))
      ->capture_default_str();
  run->add_option("--shard", options->shard, "Run every N-th scene from the i-th (name order), for CI matrices")
      ->type_name("i/N");
  run->add_flag("--trace-nonfinite", options->trace_nonfinite,
                "Render every gl and vk lane again with the tracing variant and report where its NaN, Inf and negative "
                "values were born (without it, only lanes whose images have them are traced)");
  run->add_flag("--pass-images", options->pass_images,
                "Also write every pass's own output as REPORT/SCENE/passes/PASS.LANE.exr, to find where lanes part");
  add_worker_options(*run, options->workers, "scene-and-lane renders");
  run->add_flag("--plan", options->plan_only,
                "Print each scene's plan (variants to compile or found in the cache, passes, what is left out) "
                "and render nothing");
  return {run, [options](const std::string& command_line) {
            options->command_line = command_line;
            return run_run(*options);
          }};
}

}  // namespace xshade::cli
