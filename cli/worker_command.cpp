// xshade worker: lanes of scenes rendered for the run or bless that started it, each handed back
// in a folder (harness/gate/lane_workers.h): one given on the command line, or with --serve one
// per line of standard input until it ends. Hidden from --help: only xshade starts it.
#include <sys/prctl.h>

#include <csignal>
#include <iostream>
#include <memory>

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "base/interrupt.h"
#include "cli/commands.h"
#include "harness/gate/lane_workers.h"
#include "harness/render/driver_cache.h"

namespace xshade::cli {

int run_worker(const WorkerOptions& options) {
  // A worker whose supervisor is gone (killed, or stopped with ^C) has nobody to report to.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  // Forked from a run that catches ^C: a worker ends with it, as its supervisor stops.
  stop_catching_interrupts();
  auto platform = harness::parse_gl_platform(options.gl_platform);
  if (!platform) {
    fmt::print(stderr, "xshade worker: unknown gl platform '{}'\n", options.gl_platform);
    return kBadInput;
  }
  std::optional<harness::ShaderCache> cache;
  if (!options.cache_dir.empty()) cache.emplace(options.cache_dir, harness::compiler_identity());
  // The drivers' own shader cache lives in xshade's, in a folder of this build's: Mesa's keys
  // already tell its builds and LLVM's apart, and this one tells xshade's.
  const std::filesystem::path driver_cache =
      options.cache_dir.empty() ? std::filesystem::path() : harness::driver_cache_folder(options.cache_dir);
  harness::VariantCompiler compiler(harness::ShaderSearchPath(options.shader_folders), cache ? &*cache : nullptr);
  // Environments: built once in this worker, and with a cache once between runs.
  harness::EnvironmentCache environments(options.cache_dir, harness::compiler_identity());
  std::optional<harness::GoldenStore> goldens;
  if (!options.golden.empty()) goldens.emplace(options.golden);
  harness::SceneChecker checker(
      compiler,
      {.report_dir = options.report_dir,
       .goldens = goldens ? &*goldens : nullptr,
       .backend = {.validation = options.validation, .gl_platform = *platform, .driver_cache = driver_cache},
       .pass_images = options.pass_images,
       .half_emulation = options.half_emulation,
       .environments = &environments,
       .trace_nonfinite = options.trace_nonfinite},
      [](const std::string& line) { fmt::print("{}\n", line); });
  const auto render = [&](const std::string& scene, const std::string& lane_name, const std::string& result) {
    auto lane = harness::parse_lane(lane_name);
    if (!lane) {
      fmt::print(stderr, "xshade worker: unknown lane '{}'\n", lane_name);
      return int(kBadInput);
    }
    return harness::run_lane_worker(checker, scene, *lane, result);
  };
  if (!options.serve) return render(options.scene.string(), options.lane, options.result_dir.string());

  // One render a line, {"scene": FILE, "lane": LANE, "result": DIR}; each ends with the status
  // line "done CODE" once its output is written, so that the supervisor knows what is whose.
  for (std::string line; std::getline(std::cin, line);) {
    const nlohmann::json request = nlohmann::json::parse(line, nullptr, false);
    int code = kBadInput;
    if (request.is_object() && request.value("scene", "").size() && request.value("result", "").size())
      code = render(request.value("scene", ""), request.value("lane", ""), request.value("result", ""));
    else
      fmt::print(stderr, "xshade worker: a request it cannot read: {}\n", line);
    std::fflush(stdout);
    std::fflush(stderr);
    harness::report_worker_status("done " + std::to_string(code));
  }
  return kPass;
}

Verb add_worker_command(CLI::App& app) {
  // Started by run, bless and eval for each render (cli/worker_command.cpp); not in --help.
  auto options = std::make_shared<WorkerOptions>();
  CLI::App* worker = app.add_subcommand("worker", "One lane of one scene, for the run that started it");
  worker->group("");
  worker->add_option("--scene", options->scene);
  worker->add_option("--lane", options->lane);
  worker->add_option("--result", options->result_dir);
  worker->add_flag("--serve", options->serve);
  worker->add_option("--shader-folder", options->shader_folders)->allow_extra_args(false);
  worker->add_option("--golden", options->golden);
  worker->add_option("--report", options->report_dir)->required();
  worker->add_option("--cache", options->cache_dir);
  worker->add_option("--gl-platform", options->gl_platform);
  worker->add_flag("--vk-validation", options->validation);
  worker->add_flag("--pass-images", options->pass_images);
  worker->add_flag("--half-emulation", options->half_emulation);
  worker->add_flag("--trace-nonfinite", options->trace_nonfinite);
  return {worker, [options](const std::string&) { return run_worker(*options); }};
}

}  // namespace xshade::cli
