// xshade worker: one lane of one scene, rendered for the run or bless that started it and handed
// back in a folder (harness/gate/lane_workers.h). Hidden from --help: only xshade starts it.
#include <sys/prctl.h>

#include <csignal>

#include <fmt/core.h>

#include "cli/commands.h"
#include "harness/gate/lane_workers.h"

namespace xshade::cli {

int run_worker(const WorkerOptions& options) {
  // A worker whose supervisor is gone (killed, or stopped with ^C) has nobody to report to.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  auto lane = harness::parse_lane(options.lane);
  auto platform = harness::parse_gl_platform(options.gl_platform);
  if (!lane || !platform) {
    fmt::print(stderr, "xshade worker: unknown lane '{}' or gl platform '{}'\n", options.lane, options.gl_platform);
    return kBadInput;
  }
  std::optional<harness::ShaderCache> cache;
  if (!options.cache_dir.empty()) cache.emplace(options.cache_dir, harness::compiler_identity());
  harness::VariantCompiler compiler(harness::ShaderSearchPath(options.shader_folders), cache ? &*cache : nullptr);
  std::optional<harness::GoldenStore> goldens;
  if (!options.golden.empty()) goldens.emplace(options.golden);
  harness::SceneChecker checker(compiler,
                                {.report_dir = options.report_dir,
                                 .goldens = goldens ? &*goldens : nullptr,
                                 .backend = {.validation = options.validation, .gl_platform = *platform},
                                 .pass_images = options.pass_images,
                                 .half_emulation = options.half_emulation},
                                [](const std::string& line) { fmt::print("{}\n", line); });
  return harness::run_lane_worker(checker, options.scene, *lane, options.result_dir);
}

}  // namespace xshade::cli
