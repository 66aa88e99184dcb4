// xshade watch: check the scenes as `run` does, serve the report on 127.0.0.1, and after each save
// of a file the scenes read, check again the scenes it reaches, with the same workers (their
// drivers and compilers warm) and the shader cache; open pages update themselves. A mistake in a
// scene or a shader is shown on the console and the page, and watching goes on; Ctrl-C ends it
// and its workers.
#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <map>
#include <memory>

#include "base/interrupt.h"
#include "base/subprocess.h"
#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "cli/scene_runs.h"
#include "cli/workers.h"
#include "harness/live/file_watcher.h"
#include "harness/live/live_server.h"
#include "harness/live/scene_reads.h"
#include "harness/render/driver_cache.h"
#include "harness/report/report.h"
#include "harness/report/report_html.h"
#include "harness/report/report_lock.h"

namespace xshade::cli {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// A save can be a burst of events (a write, a rename, a change of attributes) that come within
// milliseconds of each other; it is over once the folder has been quiet this long. 30 ms is small
// against a render, and a save spread wider costs only a second round, never a lost change.
constexpr auto kSaveSettles = 30ms;
// How often the loop looks up from waiting, to see a Ctrl-C.
constexpr auto kWakeUp = 500ms;

// The watch's state between rounds: each scene's last result and page data, and what it read.
class SceneWatch {
 public:
  SceneWatch(const WatchOptions& options, const SceneFolders& folders, const harness::GoldenStore& goldens,
             std::vector<fs::path> files, std::vector<harness::Lane> lanes, harness::SceneChecker& checker,
             harness::LaneWorkerPool& pool)
      : options_(options),
        folders_(folders),
        goldens_(goldens),
        files_(std::move(files)),
        lanes_(std::move(lanes)),
        checker_(checker),
        pool_(pool) {}

  // Checks `scenes` (a subset of the watched ones) and writes the whole report; the pages that
  // changed, or nothing when a Ctrl-C stopped it.
  std::optional<std::vector<std::string>> check(const std::vector<fs::path>& scenes) {
    std::set<fs::path> changed;
    size_t done = 0;  // `scenes` are concluded in their order
    harness::check_in_workers(
        checker_, pool_, scenes, lanes_,
        [&](harness::CheckedScene&& checked) {
          if (!checked.result.message.empty())
            fmt::print(stderr, "xshade watch: {}: {}\n", checked.result.scene, checked.result.message);
          print_lane_details("watch", checked.result);
          const fs::path& file = scenes[done++];
          reads_.set(file, harness::scene_reads(file, checked, folders_.project_file, &goldens_));
          viewers_[file] = viewer_page_of(checked, options_.report_dir);
          results_[file] = std::move(checked.result);
          changed.insert(file);
        },
        [](const std::string& text) { fmt::print(stderr, "{}", text); });
    if (interrupt_signal()) return std::nullopt;
    return write_report(changed);
  }

  const harness::SceneReadIndex& reads() const { return reads_; }
  const std::vector<fs::path>& files() const { return files_; }
  // The scenes watched from now on: a scene no longer among them leaves the report at the next
  // round, a new one is checked by it (its own file reaches it).
  void set_files(std::vector<fs::path> files) {
    for (const fs::path& file : files_)
      if (std::find(files.begin(), files.end(), file) == files.end()) {
        results_.erase(file);
        viewers_.erase(file);
        reads_.forget(file);
      }
    files_ = std::move(files);
    rewrite_all_ = true;  // a page's name depends on the others' (report_html.h's scene_page_names)
  }

  // "3 of 4 scenes pass" over every watched scene.
  std::string summary() const {
    size_t passed = 0;
    for (const auto& [file, result] : results_) passed += result.verdict == harness::Verdict::Pass;
    return fmt::format("{} of {} scenes pass", passed, results_.size());
  }

 private:
  // The report of every scene as last checked; the page names of `changed` (scene files), with
  // the index, which shows them all.
  std::vector<std::string> write_report(const std::set<fs::path>& changed) {
    harness::RunResults results;
    results.started = utc_now();
    results.command = options_.command_line;
    std::vector<harness::ViewerPage> viewers;
    std::vector<bool> written_already;  // the pages of the scenes this round did not check
    for (const fs::path& file : files_) {
      if (!results_.count(file)) continue;
      results.scenes.push_back(results_.at(file));
      viewers.push_back(viewers_.at(file));
      written_already.push_back(!rewrite_all_ && !changed.count(file));
    }
    const std::vector<std::string> names = harness::scene_page_names(results);
    std::vector<std::string> pages = {"index.html"};
    for (size_t i = 0; i < names.size(); ++i)
      if (!written_already[i]) pages.push_back(names[i]);
    rewrite_all_ = false;
    if (auto written = harness::write_reports(results, options_.report_dir, &viewers, &written_already); !written)
      fmt::print(stderr, "xshade watch: the report is not whole: {}\n", written.error().to_string());
    return pages;
  }

  const WatchOptions& options_;
  const SceneFolders& folders_;
  const harness::GoldenStore& goldens_;
  std::vector<fs::path> files_;
  std::vector<harness::Lane> lanes_;
  harness::SceneChecker& checker_;
  harness::LaneWorkerPool& pool_;
  harness::SceneReadIndex reads_;
  std::map<fs::path, harness::SceneResult> results_;
  std::map<fs::path, harness::ViewerPage> viewers_;
  bool rewrite_all_ = false;  // the scenes changed: every page is written again
};

// "toon.hlsl, brdf.hlsl" for the console.
std::string file_names(const std::set<fs::path>& files) {
  std::string names;
  for (const fs::path& file : files) names += (names.empty() ? "" : ", ") + file.filename().string();
  return names;
}

}  // namespace

int run_watch(const WatchOptions& options) {
  auto inputs = resolve_scene_run(options.selection, options.folders, options.scenes, GoldenUse::Read);
  if (!inputs) {
    fmt::print(stderr, "xshade watch: {}\n", inputs.error().to_string());
    return kBadInput;
  }
  const std::vector<harness::Lane>& lanes = inputs->lanes;
  const SceneFolders& folders = inputs->folders;
  const std::vector<fs::path>& files = inputs->files;
  auto report_lock = harness::ReportLock::take(options.report_dir, options.command_line);
  if (!report_lock) {
    fmt::print(stderr, "xshade watch: {}\n", report_lock.error().to_string());
    return exit_code_of(report_lock.error().kind);
  }
  auto watcher = harness::FileWatcher::make();
  if (!watcher) {
    fmt::print(stderr, "xshade watch: {}\n", watcher.error().to_string());
    return exit_code_of(watcher.error().kind);
  }

  const fs::path cache_dir = private_cache_dir(shader_cache_dir(options.cache_dir), "watch");
  std::optional<harness::ShaderCache> cache;
  if (!cache_dir.empty()) cache.emplace(cache_dir, harness::compiler_identity());
  harness::VariantCompiler compiler(folders.shaders, cache ? &*cache : nullptr);
  const harness::GoldenStore goldens(folders.golden);
  harness::SceneChecker checker(
      compiler, {.report_dir = options.report_dir, .goldens = &goldens, .backend = backend_options(options.selection)},
      [](const std::string& line) {
        fmt::print("  {}\n", line);
        std::fflush(stdout);
      });
  // The workers' command before the server's threads start: a worker is then started as a
  // program, never forked from a process with threads (base/subprocess.h).
  const WorkerOptions shared{.shader_folders = folders.shaders.folders(),
                             .golden = folders.golden,
                             .report_dir = options.report_dir,
                             .cache_dir = cache_dir,
                             .gl_platform = options.selection.gl_platform,
                             .validation = options.selection.validation};
  harness::LaneWorkerPool pool(scene_workers(shared, options.workers));

  auto server = harness::LiveServer::start(options.report_dir, options.port);
  if (!server) {
    fmt::print(stderr, "xshade watch: {}\n", server.error().to_string());
    return exit_code_of(server.error().kind);
  }
  catch_interrupts();
  const std::string address = fmt::format("http://127.0.0.1:{}/", (*server)->port());
  fmt::print("xshade watch: {} scene{} on {}; the report is at {}\n", files.size(), files.size() == 1 ? "" : "s",
             address, options.report_dir.string());
  std::fflush(stdout);

  SceneWatch watch(options, folders, goldens, files, lanes, checker, pool);
  if (options.scenes.empty())
    if (auto watching = watcher->watch_new_files(folders.scenes, ".toml"); !watching)
      fmt::print(stderr, "xshade watch: {}; a scene added is not seen\n", watching.error().to_string());
  std::vector<fs::path> to_check = files;
  std::string cause = "start";
  for (unsigned round = 1;; ++round) {
    const auto started = std::chrono::steady_clock::now();
    const auto pages = watch.check(to_check);
    if (!pages) break;
    // What to watch, before the round is announced: every file a scene read, and the scene files
    // themselves (one that did not load read nothing else). A save while the round ran is seen
    // too: its folder was watched already, and its event waits in the kernel's queue.
    std::set<fs::path> watched = watch.reads().all_files();
    for (const fs::path& file : watch.files()) watched.insert(harness::normal_file_path(file));
    if (!folders.project_file.empty()) watched.insert(harness::normal_file_path(folders.project_file));
    if (auto watching = watcher->watch_only(watched); !watching)
      fmt::print(stderr, "xshade watch: {}; changes to it are not seen\n", watching.error().to_string());

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const std::string line = fmt::format("round {} ({}): {} scene{} in {:.2f} s; {}; {}", round, cause, to_check.size(),
                                         to_check.size() == 1 ? "" : "s", seconds, watch.summary(), address);
    fmt::print("{}\n", line);
    std::fflush(stdout);
    (*server)->announce(nlohmann::json{{"round", round}, {"pages", *pages}, {"console", line}});
    if (!cache_dir.empty()) harness::record_driver_cache(harness::driver_cache_folder(cache_dir));

    to_check.clear();
    bool scenes_changed = false;
    while (to_check.empty() && !scenes_changed && !interrupt_signal()) {
      const std::set<fs::path> changed = watcher->wait(kWakeUp, kSaveSettles);
      if (changed.empty()) continue;
      // Every scene of the folder is watched: one added or removed changes the list.
      if (options.scenes.empty())
        if (auto now = scene_files(options.scenes, folders); now && *now != watch.files()) {
          watch.set_files(std::move(*now));
          scenes_changed = true;
        }
      to_check = watch.reads().reached(changed, watch.files());
      cause = file_names(changed) + " changed";
      if (!folders.project_file.empty() && changed.count(harness::normal_file_path(folders.project_file)))
        fmt::print(stderr,
                   "xshade watch: the project file changed; its folders are read once, at the start: restart "
                   "xshade watch to use new ones\n");
    }
    if (interrupt_signal()) break;
    fmt::print("{}: {}\n", cause,
               to_check.empty()       ? std::string("writing the report again")
               : to_check.size() == 1 ? "checking " + to_check.front().stem().string()
                                      : fmt::format("checking {} scenes", to_check.size()));
    if (scenes_changed)
      fmt::print("now watching {} scene{}\n", watch.files().size(), watch.files().size() == 1 ? "" : "s");
    std::fflush(stdout);
  }
  const int signal = interrupt_signal();
  fmt::print(stderr, "xshade watch: stopped by {}; its workers are gone, the report stays in {}\n",
             describe_signal(signal), options.report_dir.string());
  return kInterrupted + signal;
}

Verb add_watch_command(CLI::App& app) {
  auto options = std::make_shared<WatchOptions>();
  CLI::App* watch = app.add_subcommand(
      "watch",
      "Run the scenes, serve the report on 127.0.0.1, and after each save render again the scenes the file reaches; "
      "open pages update themselves. Ctrl-C ends it");
  watch->add_option("scene", options->scenes, "Scene names (in --scenes) or .toml files; default: every scene")
      ->type_name("SCENE");
  add_lane_options(*watch, options->selection);
  watch->add_option("--port", options->port, "The port on 127.0.0.1 to serve the report on; 0: any free one")
      ->type_name("N")
      ->capture_default_str();
  watch->add_option("--report", options->report_dir, "Folder for images and the report")
      ->type_name("DIR")
      ->capture_default_str();
  add_folder_options(*watch, options->folders);
  watch
      ->add_option("--cache", options->cache_dir,
                   "Compiled-shader cache (default: $XSHADE_CACHE_DIR, else $XDG_CACHE_HOME/xshade or ~/.cache/xshade)")
      ->type_name("DIR");
  add_worker_options(*watch, options->workers, "scene-and-lane renders");
  return {watch, [options](const std::string& command_line) {
            options->command_line = command_line;
            return run_watch(*options);
          }};
}

}  // namespace xshade::cli
