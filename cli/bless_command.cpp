// xshade bless: render a scene and accept the image as its golden. The only way a golden is
// ever written: it needs a reason, the lanes must agree (for the common golden) and render
// deterministically, and it shows what it is about to replace before committing it (GoldenStore:
// under the folder's lock, the manifest renamed into place last).
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "base/interrupt.h"
#include "base/subprocess.h"
#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"
#include "cli/workers.h"
#include "harness/gate/scene_check.h"
#include "harness/image/image_compare.h"
#include "harness/render/driver_cache.h"
#include "harness/report/report_text.h"

namespace xshade::cli {
namespace {

bool blank(const std::string& text) { return text.find_first_not_of(" \t\r\n") == std::string::npos; }

// Who blesses: $XSHADE_BLESSED_BY, else git's user.name (what the commit will say), else the
// login name.
std::string who() {
  if (const char* value = std::getenv("XSHADE_BLESSED_BY"); value && *value) return value;
  if (FILE* pipe = popen("git config user.name 2>/dev/null", "r")) {
    char line[256] = {};
    const bool read = std::fgets(line, sizeof line, pipe) != nullptr;
    pclose(pipe);
    std::string name = read ? line : "";
    while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
    if (!name.empty()) return name;
  }
  for (const char* name : {"USER", "LOGNAME"})
    if (const char* value = std::getenv(name); value && *value) return value;
  return "unknown";
}

}  // namespace

int run_bless(const BlessOptions& options) {
  if (blank(options.reason)) {
    fmt::print(stderr, "xshade bless: a golden is evidence: say why with --reason \"...\"\n");
    return kBadInput;
  }
  LaneSelection selection;
  if (!options.lane.empty()) selection.lanes = {options.lane};
  selection.gl_platform = options.gl_platform;
  auto lanes = resolve_lanes(selection);
  if (!lanes) {
    fmt::print(stderr, "xshade bless: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  auto folders = resolve_folders(options.folders, std::filesystem::current_path(), GoldenUse::Write);
  if (!folders) {
    fmt::print(stderr, "xshade bless: {}\n", folders.error().to_string());
    return kBadInput;
  }
  auto files = scene_files({options.scene}, *folders);
  if (!files) {
    fmt::print(stderr, "xshade bless: {}\n", files.error().to_string());
    return kBadInput;
  }

  const std::filesystem::path cache_dir = private_cache_dir(shader_cache_dir(options.cache_dir), "bless");
  std::optional<harness::ShaderCache> cache;
  if (!cache_dir.empty()) cache.emplace(cache_dir, harness::compiler_identity());
  harness::VariantCompiler compiler(folders->shaders, cache ? &*cache : nullptr);
  harness::SceneChecker checker(compiler, {options.report_dir, nullptr, backend_options(selection), false, false},
                                [](const std::string& line) { fmt::print("{}\n", line); });
  // Rendered as run renders, each lane in a worker: a shader that hangs or a driver that crashes
  // is reported, not the end of bless.
  const WorkerOptions shared{.shader_folders = folders->shaders.folders(),
                             .report_dir = options.report_dir,
                             .cache_dir = cache_dir,
                             .gl_platform = options.gl_platform};
  harness::CheckedScene checked;
  catch_interrupts();
  const harness::WorkerTotals totals = harness::check_in_workers(
      checker, scene_workers(shared, options.workers), *files, *lanes,
      [&](harness::CheckedScene&& scene) { checked = std::move(scene); },
      [](const std::string& text) { fmt::print(stderr, "{}", text); });
  if (!cache_dir.empty()) harness::record_driver_cache(harness::driver_cache_folder(cache_dir));
  if (const int signal = interrupt_signal()) {
    fmt::print(stderr, "xshade bless: stopped by {} before it rendered; no golden changed\n", describe_signal(signal));
    return kInterrupted + signal;
  }
  const harness::SceneResult& result = checked.result;
  if (!result.message.empty()) {
    fmt::print(stderr, "xshade bless: {}: {}\n", result.scene, result.message);
    return kBadInput;
  }
  if (checked.images.empty()) {
    fmt::print(stderr, "xshade bless: {} did not render on {}\n", result.scene,
               options.lane.empty() ? std::string("any of its lanes") : options.lane);
    return kBackendError;
  }
  if (const auto refusal = harness::bless_refusal(result)) {
    fmt::print(stderr, "xshade bless: refused: {}\n", refusal->message);
    return harness::exit_code(refusal->verdict);
  }

  // A second bless into the folder waits for the first to commit; saying so explains the pause.
  const harness::GoldenStore goldens(
      folders->golden, [](const std::string& message) { fmt::print(stderr, "xshade bless: {}\n", message); });
  const std::optional<std::string> lane = options.lane.empty() ? std::nullopt : std::optional(options.lane);
  const harness::FloatImage& image = checked.images.begin()->second;
  const std::string compared_lane = lane ? *lane : std::string(harness::lane_name(checked.images.begin()->first));
  if (lane) {
    // A lane's own golden is for a lane that differs from the common one, with the reason why.
    auto common = goldens.find(result.scene, "");
    if (common && *common) {
      const harness::Comparison comparison = harness::compare_images(image, (*common)->image, checked.scene->compare);
      if (comparison.verdict == harness::Verdict::Pass) {
        fmt::print(stderr,
                   "xshade bless: refused: {} on {} matches the common golden {} ({}); a lane's own golden is for a "
                   "lane that differs from it, so nothing was written\n",
                   result.scene, *lane, (*common)->path.string(), harness::describe_metrics(comparison.metrics));
        return kBadInput;
      }
    }
  }
  auto old = goldens.find(result.scene, compared_lane);
  if (!old) {
    // A golden whose files are damaged or gone (its entry intact) is what bless repairs: said,
    // then replaced in the same transaction as any bless. A manifest that does not read is not
    // overwritten: GoldenStore::bless refuses it below.
    fmt::print(stderr, "xshade bless: the golden it replaces cannot be used: {}; blessing writes it again\n",
               old.error().to_string());
  } else if (*old) {
    const harness::Comparison comparison = harness::compare_images(image, (*old)->image, checked.scene->compare);
    fmt::print("against the golden it replaces ({}): {}\n", (*old)->path.string(),
               harness::describe_metrics(comparison.metrics));
    for (const harness::LayerResult& layer : comparison.layers)
      fmt::print("  {}: {}: {}\n", layer.layer, harness::verdict_name(layer.verdict), layer.detail);
  } else {
    fmt::print("no golden yet for {}{}\n", result.scene, lane ? " on " + *lane : std::string());
  }
  auto blessed = goldens.bless(result.scene, lane, image, options.reason, who());
  if (!blessed) {
    fmt::print(stderr, "xshade bless: {}\n", blessed.error().to_string());
    // A folder that cannot be locked or written is the machine's, not the user's.
    const ErrorKind kind = blessed.error().kind;
    return kind == ErrorKind::Backend || kind == ErrorKind::Internal ? kBackendError : kBadInput;
  }
  if (!totals.cache_write_error.empty()) fmt::print("warning: {}\n", totals.cache_write_error);
  if (!totals.cache_damage.empty()) fmt::print("warning: {}\n", totals.cache_damage);
  fmt::print("blessed {} ({}), reason: {}\n", blessed->path.string(), blessed->replaced ? "replaced" : "new",
             options.reason);
  return kPass;
}

Verb add_bless_command(CLI::App& app) {
  auto options = std::make_shared<BlessOptions>();
  CLI::App* bless = app.add_subcommand(
      "bless", "Render a scene and accept it as its golden (the common one from lanes that agree, or one lane's)");
  bless->add_option("scene", options->scene, "Scene name (in --scenes) or .toml file")->required()->type_name("SCENE");
  bless->add_option("--lane", options->lane, "Bless this lane's own golden (needs a reason it differs)")
      ->check(CLI::IsMember({"gl", "vk", "vk-hlsl"}))
      ->type_name("LANE");
  add_gl_platform_option(*bless, options->gl_platform);
  bless->add_option("--reason", options->reason, "Why this image is right (recorded in golden/MANIFEST.toml)")
      ->required()
      ->type_name("TEXT");
  add_folder_options(*bless, options->folders);
  bless->add_option("--cache", options->cache_dir, "Compiled-shader cache (as for run)")->type_name("DIR");
  bless->add_option("--report", options->report_dir, "Folder for the rendered images")
      ->type_name("DIR")
      ->capture_default_str();
  add_worker_options(*bless, options->workers, "lanes");
  return {bless, [options](const std::string&) { return run_bless(*options); }};
}

}  // namespace xshade::cli
