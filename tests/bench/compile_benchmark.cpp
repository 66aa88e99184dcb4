// Compile throughput over the shader library: xshade's front end and GLSL emission, the full
// path to SPIR-V, and glslang compiling the same sources through its own HLSL front end, in one
// process.
//
//   build/tests/bench/compile_benchmark [--benchmark_repetitions=5]
//
// Every benchmark compiles the same sources with the same macros (prelude and default keywords)
// and makes one Vulkan target per stage, so their times compare directly. GlslangGlslToSpirv is
// the share of FullPathToSpirv that is glslang's and SPIRV-Tools' own work on the emitted GLSL:
// no front end can take the full path below it.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/heap.h"
#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"
#include "spirv/hlsl_compiler.h"
#include "spirv/spirv_compiler.h"

namespace {

// One variant of one shader of the library: what `xshade run` compiles for a scene.
struct Source {
  std::string name;  // the file's path, so that its includes resolve as they do in a run
  std::string text;
  xshade::hlsl::CompileOptions options;
};

const std::filesystem::path kLibrary = XSHADE_SHADER_LIBRARY;

// The shader library's variants: each material with its seed forms and with the alternatives
// and guards on, and each pass of the depth of field.
const std::vector<Source>& sources() {
  static const std::vector<Source> list = [] {
    auto read = [](const std::string& library_path, std::vector<std::string> keywords, std::string entry = {}) {
      const std::filesystem::path path = kLibrary / library_path;
      std::ifstream file(path);
      std::stringstream text;
      text << file.rdbuf();
      xshade::hlsl::CompileOptions options;
      options.include_dirs = {kLibrary};
      options.keywords = std::move(keywords);
      options.fragment_only_entry = std::move(entry);
      return Source{path.string(), text.str(), std::move(options)};
    };
    std::vector<Source> found{
        read("materials/standard_pbr.hlsl", {}),
        read("materials/standard_pbr.hlsl", {"_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED", "_F_EXACT", "_GUARDED"}),
        read("materials/toon.hlsl", {}),
        read("materials/toon.hlsl", {"_SHADOW_TEX", "_GUARDED"}),
    };
    for (const char* entry : {"frag_coc", "frag_prefilter", "frag_bokeh", "frag_postfilter", "frag_combine"})
      found.push_back(read("post/depth_of_field.hlsl", {"_KERNEL_LARGE"}, entry));
    return found;
  }();
  return list;
}

// Runs `pass` once untimed, then times it. glslang builds the built-in symbol tables of each
// source language and stage on first use (tens of milliseconds), and the front end reads its
// prelude once: without the warm-up that one-off cost would land in whichever iterations come
// first, and on one side of a comparison only.
// (The warm-up is a function of its own so that a profile can tell its call from the timed ones.)
template <class Pass>
[[gnu::noinline]] void warm_up(const Pass& pass) {
  pass();
}

template <class Pass>
void run_warm(benchmark::State& state, const Pass& pass) {
  warm_up(pass);
  for (auto _ : state) pass();
  state.SetItemsProcessed(int64_t(state.iterations() * sources().size()));
}

// The Vulkan flavour only: the one the full path and glslang's HLSL front end are measured making.
// One round is a function of its own (never inlined) so that compiler_share_callgrind.py finds
// its instructions in a profile.
[[gnu::noinline]] void front_end_and_emission_round() {
  for (const Source& source : sources()) {
    auto module = xshade::hlsl::compile_text(source.name, source.text, source.options);
    auto vk = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Vk});
    benchmark::DoNotOptimize(vk);
  }
}

void FrontEndAndEmission(benchmark::State& state) { run_warm(state, front_end_and_emission_round); }

void FullPathToSpirv(benchmark::State& state) {
  run_warm(state, [] {
    for (const Source& source : sources()) {
      auto module = xshade::hlsl::compile_text(source.name, source.text, source.options);
      auto vk = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Vk});
      if (!vk) continue;
      if (vk->vertex)
        benchmark::DoNotOptimize(
            xshade::spirv::compile_vulkan_glsl(vk->vertex->text, xshade::spirv::Stage::Vertex, source.name));
      if (vk->fragment)
        benchmark::DoNotOptimize(
            xshade::spirv::compile_vulkan_glsl(vk->fragment->text, xshade::spirv::Stage::Fragment, source.name));
    }
  });
}

// FullPathToSpirv without the front end: the emitted GLSL is made once, outside the timed loop.
void GlslangGlslToSpirv(benchmark::State& state) {
  struct EmittedStage {
    std::string text;
    xshade::spirv::Stage stage;
    const std::string* name;
  };
  std::vector<EmittedStage> stages;
  for (const Source& source : sources()) {
    auto module = xshade::hlsl::compile_text(source.name, source.text, source.options);
    auto vk = xshade::glsl::emit(*module, {xshade::glsl::Flavour::Vk});
    if (!vk) continue;
    if (vk->vertex) stages.push_back({vk->vertex->text, xshade::spirv::Stage::Vertex, &source.name});
    if (vk->fragment) stages.push_back({vk->fragment->text, xshade::spirv::Stage::Fragment, &source.name});
  }
  run_warm(state, [&] {
    for (const EmittedStage& emitted : stages)
      benchmark::DoNotOptimize(xshade::spirv::compile_vulkan_glsl(emitted.text, emitted.stage, *emitted.name));
  });
}

// What glslang's HLSL front end is given for one variant: the entry points and the variant's
// macros come from xshade's front end once, outside the timed loop.
struct GlslangJob {
  const Source* source;
  std::string vertex, fragment;
  std::vector<std::pair<std::string, std::string>> defines;
};

[[gnu::noinline]] void glslang_hlsl_round(const std::vector<GlslangJob>& jobs,
                                          const xshade::spirv::IncludeResolver& resolve) {
  for (const GlslangJob& job : jobs) {
    for (const auto& [entry, stage] : {std::pair{job.vertex, xshade::spirv::Stage::Vertex},
                                       std::pair{job.fragment, xshade::spirv::Stage::Fragment}}) {
      if (entry.empty()) continue;
      xshade::spirv::HlslStage request{job.source->text, job.source->name, stage, entry, job.defines, resolve, {}, {}};
      benchmark::DoNotOptimize(xshade::spirv::compile_hlsl(request));
    }
  }
}

void GlslangHlslToSpirv(benchmark::State& state) {
  using Job = GlslangJob;
  std::vector<Job> jobs;
  for (const Source& source : sources()) {
    auto module = xshade::hlsl::compile_text(source.name, source.text, source.options);
    Job job{&source, module->reflection.vertex_entry, module->reflection.fragment_entry, {}};
    for (const auto& macro : module->macros) job.defines.emplace_back(macro.name, macro.value);
    jobs.push_back(std::move(job));
  }
  const xshade::spirv::IncludeResolver resolve = xshade::spirv::include_resolver({kLibrary});
  run_warm(state, [&] { glslang_hlsl_round(jobs, resolve); });
}

BENCHMARK(FrontEndAndEmission)->Unit(benchmark::kMillisecond);
BENCHMARK(FullPathToSpirv)->Unit(benchmark::kMillisecond);
BENCHMARK(GlslangGlslToSpirv)->Unit(benchmark::kMillisecond);
BENCHMARK(GlslangHlslToSpirv)->Unit(benchmark::kMillisecond);

}  // namespace

// The heap as xshade's own main sets it (base/heap.h): the compiler measured in the process it
// runs in.
int main(int argc, char** argv) {
  xshade::keep_freed_heap();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
