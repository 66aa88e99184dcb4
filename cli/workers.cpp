#include "cli/workers.h"

#include <sys/resource.h>
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

namespace {

// The soft limit on this process's address space in bytes, or 0 for none.
uint64_t address_space_limit() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return uint64_t(limit.rlim_cur);
}

}  // namespace

Result<void> limit_memory(const char* setting) {
  // AddressSanitizer reserves terabytes of address space for its shadow memory.
#if defined(__SANITIZE_ADDRESS__)
  constexpr bool kSanitized = true;
#elif defined(__has_feature)
  constexpr bool kSanitized = __has_feature(address_sanitizer);
#else
  constexpr bool kSanitized = false;
#endif
  if (kSanitized) return {};
  uint64_t bytes = 0;
  if (setting && *setting) {
    char* end = nullptr;
    const double gib = std::strtod(setting, &end);
    if (end == setting || *end != '\0' || !(gib >= 0.0) || gib > 1e6)
      return fail(ErrorKind::Usage,
                  std::string("XSHADE_MEMORY_LIMIT=") + setting +
                      ": expected the address space each xshade process may take, in GiB (0: no limit)");
    if (gib == 0.0) return {};
    bytes = uint64_t(gib * double(uint64_t(1) << 30));
  } else {
    // Half the machine's memory: a run that goes past it has a fault to report, and what is left
    // keeps the machine (and the kernel's OOM killer) out of it.
    bytes = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE)) / 2;
  }
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0) return {};
  // Only ever lowered: a limit the user's shell set stays.
  if (limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur <= bytes) return {};
  limit.rlim_cur = bytes;
  if (limit.rlim_max != RLIM_INFINITY && limit.rlim_max < bytes) limit.rlim_cur = limit.rlim_max;
  setrlimit(RLIMIT_AS, &limit);
  return {};
}

int guarded_verb(const std::string& verb, const std::function<int()>& body) {
  const std::string name = verb.empty() ? std::string() : " " + verb;
  try {
    return body();
  } catch (const std::bad_alloc&) {
    std::string limit;
    if (const uint64_t bytes = address_space_limit()) {
      char gib[32];
      std::snprintf(gib, sizeof gib, "%.1f", double(bytes) / double(uint64_t(1) << 30));
      limit = std::string("; each xshade process may take ") + gib +
              " GiB of address space (XSHADE_MEMORY_LIMIT=GiB sets it, 0 for no limit)";
    }
    std::fprintf(stderr, "xshade%s: out of memory (an allocation failed%s); nothing more was done\n", name.c_str(),
                 limit.c_str());
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
