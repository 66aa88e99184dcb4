// Compiles the variants a plan lists for a lane, through the shader cache when there is one.
// The front end runs at most once per variant and contents of the files it read in a process,
// whatever the number of lanes: a long-lived process (a worker of `xshade watch`) compiles a
// variant again once a file it read has changed.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "harness/render/planner.h"
#include "harness/render/shader_cache.h"
#include "hlsl_like/compiler.h"

namespace xshade::harness {

class VariantCompiler {
 public:
  // `cache` may be null: everything is compiled. Every folder of `shaders` is an include folder.
  VariantCompiler(ShaderSearchPath shaders, const ShaderCache* cache);

  Result<CompiledVariant> compile(const VariantRequest& request, Lane lane);
  // Every variant of a plan, in the plan's order, each with `half_emulation` as given; with
  // `trace_nonfinite` the tracing variants, each numbered by its place in the plan.
  Result<std::vector<CompiledVariant>> compile_plan(const Plan& plan, Lane lane, bool half_emulation,
                                                    bool trace_nonfinite = false);
  bool in_cache(const VariantRequest& request, Lane lane) const;
  // The folders sources and includes come from; a plan for this compiler is made against them.
  const ShaderSearchPath& shaders() const { return shaders_; }

  // What happened so far: variants compiled, and found in the cache.
  size_t compiled() const { return compiled_; }
  size_t cached() const { return cached_; }
  // The first failure to write the cache, if any: it costs time, not correctness, so the run goes on.
  const std::optional<Error>& cache_write_error() const { return cache_write_error_; }
  // Every file the compiles since the last call read (sources and includes, whether compiled or
  // found in the cache), and forgets them: what `xshade watch` watches for a scene.
  std::set<std::filesystem::path> take_files_read() { return std::exchange(files_read_, {}); }
  // The first damaged cache entry found, if any (ShaderCache::look_up): the variant was compiled
  // again and the entry rewritten, so the run is right; the warning says the cache was not.
  const std::optional<Error>& cache_damage() const { return cache_damage_; }

 private:
  Result<const hlsl::Module*> front_end(const VariantRequest& request);

  ShaderSearchPath shaders_;
  const ShaderCache* cache_;
  // A front end's module, kept with the contents hash of each file it read.
  struct KeptModule {
    std::unique_ptr<hlsl::Module> module;
    std::vector<std::pair<std::filesystem::path, std::string>> read;
  };
  std::map<std::string, KeptModule> modules_;  // by request label
  std::set<std::filesystem::path> files_read_;
  size_t compiled_ = 0;
  size_t cached_ = 0;
  std::optional<Error> cache_write_error_;
  std::optional<Error> cache_damage_;
};

}  // namespace xshade::harness
