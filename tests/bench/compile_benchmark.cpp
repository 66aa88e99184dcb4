// Compile throughput: xshade's front end and GLSL emission, the full path to SPIR-V, and glslang
// compiling the same sources through its own HLSL front end, in one process.
//
//   build/tests/bench/compile_benchmark [--benchmark_repetitions=5]
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"
#include "spirv/hlsl_compiler.h"
#include "spirv/spirv_compiler.h"

namespace {

struct Source {
  std::string name;
  std::string text;
};

// Every .hlsl file of the benchmark's inputs: the conformance shaders and a lit material.
const std::vector<Source>& sources() {
  static const std::vector<Source> list = [] {
    std::vector<Source> found;
    for (const char* dir : {XSHADE_BENCH_DIR, XSHADE_CONFORMANCE_DIR})
      for (const auto& entry : std::filesystem::directory_iterator(dir))
        if (entry.path().extension() == ".hlsl") {
          std::ifstream file(entry.path());
          std::stringstream text;
          text << file.rdbuf();
          found.push_back({entry.path().filename().string(), text.str()});
        }
    return found;
  }();
  return list;
}

void FrontEndAndEmission(benchmark::State& state) {
  for (auto _ : state) {
    for (const Source& source : sources()) {
      auto module = xshade::hlsl::compile_text(source.name, source.text, {});
      auto gl = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Gl});
      auto vk = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Vk});
      benchmark::DoNotOptimize(gl);
      benchmark::DoNotOptimize(vk);
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations() * sources().size()));
}

void FullPathToSpirv(benchmark::State& state) {
  for (auto _ : state) {
    for (const Source& source : sources()) {
      auto module = xshade::hlsl::compile_text(source.name, source.text, {});
      auto vk = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Vk});
      if (!vk) continue;
      if (vk->vertex) benchmark::DoNotOptimize(xshade::spirv::compile_vulkan_glsl(vk->vertex->text, xshade::spirv::Stage::Vertex, source.name));
      if (vk->fragment) benchmark::DoNotOptimize(xshade::spirv::compile_vulkan_glsl(vk->fragment->text, xshade::spirv::Stage::Fragment, source.name));
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations() * sources().size()));
}

void GlslangHlslToSpirv(benchmark::State& state) {
  // The entry points come from the front end once, outside the timed loop.
  struct Job {
    const Source* source;
    std::string vertex, fragment;
    std::vector<std::pair<std::string, std::string>> defines;
  };
  std::vector<Job> jobs;
  for (const Source& source : sources()) {
    auto module = xshade::hlsl::compile_text(source.name, source.text, {});
    Job job{&source, module->reflection.vertex_entry, module->reflection.fragment_entry, {}};
    for (const auto& macro : module->macros) job.defines.emplace_back(macro.name, macro.value);
    jobs.push_back(std::move(job));
  }
  for (auto _ : state) {
    for (const Job& job : jobs) {
      for (const auto& [entry, stage] : {std::pair{job.vertex, xshade::spirv::Stage::Vertex},
                                         std::pair{job.fragment, xshade::spirv::Stage::Fragment}}) {
        if (entry.empty()) continue;
        xshade::spirv::HlslStage request{job.source->text, job.source->name, stage, entry, job.defines, {}, {}};
        benchmark::DoNotOptimize(xshade::spirv::compile_hlsl(request));
      }
    }
  }
  state.SetItemsProcessed(int64_t(state.iterations() * sources().size()));
}

BENCHMARK(FrontEndAndEmission)->Unit(benchmark::kMillisecond);
BENCHMARK(FullPathToSpirv)->Unit(benchmark::kMillisecond);
BENCHMARK(GlslangHlslToSpirv)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
