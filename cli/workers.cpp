#include "cli/workers.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>

#include "base/subprocess.h"
#include "harness/image/image_codec.h"

namespace xshade::cli {

std::string this_program() {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string("xshade") : self.string();
}

int guarded_verb(const std::string& verb, const std::function<int()>& body) {
  const std::string name = verb.empty() ? std::string() : " " + verb;
  try {
    return body();
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "xshade%s: out of memory (an allocation failed); nothing more was done\n", name.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "xshade%s: internal error: %s\n", name.c_str(), error.what());
  } catch (...) {
    std::fprintf(stderr, "xshade%s: internal error: an unknown exception\n", name.c_str());
  }
  return kBackendError;
}

unsigned worker_jobs(const WorkerLimits& limits) { return limits.jobs ? limits.jobs : usable_cores(); }

double worker_timeout(const WorkerLimits& limits) {
  return limits.timeout_seconds > 0.0 ? limits.timeout_seconds : harness::kDefaultTimeoutSeconds;
}

std::vector<std::string> worker_environment(unsigned jobs) {
  if (std::getenv("LP_NUM_THREADS")) return {};
  return {"LP_NUM_THREADS=" + std::to_string(harness::driver_threads_per_worker(usable_cores(), jobs))};
}

harness::SceneWorkers scene_workers(const WorkerOptions& shared, const WorkerLimits& limits) {
  // The workers write images: the image library loaded here, once, before they are forked, is
  // theirs too (a third of a second each otherwise), and a run or bless that stops before this,
  // at a user's mistake, never loads it. The idle threads it starts as it loads become part of
  // what the process started with. A library that cannot be loaded is reported where an image is
  // first written.
  (void)harness::image_codec();
  remember_startup_threads();
  std::vector<std::string> command = {this_program(), "worker"};
  for (const std::filesystem::path& folder : shared.shader_folders) {
    command.push_back("--shader-folder");
    command.push_back(folder.string());
  }
  if (!shared.golden.empty()) command.insert(command.end(), {"--golden", shared.golden.string()});
  command.insert(command.end(), {"--report", shared.report_dir.string(), "--gl-platform", shared.gl_platform});
  if (!shared.cache_dir.empty()) command.insert(command.end(), {"--cache", shared.cache_dir.string()});
  if (shared.validation) command.push_back("--vk-validation");
  if (shared.pass_images) command.push_back("--pass-images");
  if (shared.half_emulation) command.push_back("--half-emulation");
  if (shared.trace_nonfinite) command.push_back("--trace-nonfinite");
  const unsigned jobs = worker_jobs(limits);
  WorkerOptions serving = shared;
  serving.serve = true;
  return {.command = std::move(command),
          .serve = [serving] { return guarded_verb("worker", [&] { return run_worker(serving); }); },
          .jobs = jobs,
          .timeout_seconds = worker_timeout(limits),
          .environment = worker_environment(jobs)};
}

}  // namespace xshade::cli
