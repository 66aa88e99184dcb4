// Where a scene's time goes, per scene and lane: compiling its variants with no cache (cold; the
// first compile of a process also pays glslang's one-time set-up) and from a filled cache (warm),
// the first frame (which creates programs, meshes and textures, and in which the drivers compile
// their pipelines), and the frames after it (median, fastest and slowest). Prints a Markdown table.
//
//   build/tests/bench/scene_benchmark [FRAMES] [--shaders DIR]... [SCENE.toml...]
//
// Default: 5 frames, every fixed scene; --shaders folders are searched before the library (a
// user project's scenes name their own materials).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "base/heap.h"
#include "harness/assets/environment.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"

namespace {

namespace fs = std::filesystem;
using namespace xshade::harness;

const fs::path kSource = XSHADE_SOURCE_DIR;
const fs::path kLibrary = kSource / "shaders";

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Compiles every variant of the plan for the lane; the time in milliseconds, or a negative
// number when one fails.
double compile_all(VariantCompiler& compiler, const Plan& plan, Lane lane, std::vector<CompiledVariant>* out) {
  const auto start = std::chrono::steady_clock::now();
  for (const VariantRequest& request : plan.variants) {
    auto compiled = compiler.compile(request, lane);
    if (!compiled) return -1.0;
    if (out) out->push_back(std::move(*compiled));
  }
  return milliseconds_since(start);
}

}  // namespace

int main(int argc, char** argv) {
  xshade::keep_freed_heap();  // as xshade's own main: the floor measured in the process a run has
  int frames = 5;
  std::vector<fs::path> scenes, folders;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--shaders" && i + 1 < argc)
      folders.push_back(argv[++i]);
    else if (argument.ends_with(".toml"))
      scenes.push_back(argument);
    else
      frames = std::max(1, std::atoi(argument.c_str()));
  }
  folders.push_back(kLibrary);
  const ShaderSearchPath shaders(folders);
  if (scenes.empty()) {
    for (const auto& entry : fs::directory_iterator(kSource / "scenes"))
      if (entry.path().extension() == ".toml") scenes.push_back(entry.path());
    std::sort(scenes.begin(), scenes.end());
  }
  const fs::path cache_dir = fs::temp_directory_path() / "xshade_scene_benchmark_cache";
  fs::remove_all(cache_dir);
  const ShaderCache cache(cache_dir, compiler_identity());

  std::printf(
      "| scene | lane | variants | compile cold (ms) | compile warm (ms) | first frame (ms) | render median (ms) | "
      "fastest - slowest (ms) |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const fs::path& file : scenes) {
    auto scene = load_scene(file);
    if (!scene) return std::fprintf(stderr, "%s\n", scene.error().to_string().c_str()), 2;
    auto plan = plan_scene(*scene, shaders);
    if (!plan) return std::fprintf(stderr, "%s\n", plan.error().to_string().c_str()), 2;
    auto environment = build_environment(scene->environment);
    if (!environment) return std::fprintf(stderr, "%s\n", environment.error().to_string().c_str()), 2;
    for (Lane lane : all_lanes()) {
      VariantCompiler cold(shaders, nullptr);
      std::vector<CompiledVariant> variants;
      const double cold_ms = compile_all(cold, *plan, lane, &variants);
      VariantCompiler filler(shaders, &cache);
      compile_all(filler, *plan, lane, nullptr);
      VariantCompiler warm(shaders, &cache);
      const double warm_ms = compile_all(warm, *plan, lane, nullptr);

      auto backend = create_backend(lane);
      if (!backend || cold_ms < 0) {
        std::printf("| %s | %s | %zu | failed | | | | |\n", scene->name.c_str(), std::string(lane_name(lane)).c_str(),
                    plan->variants.size());
        continue;
      }
      // The first frame uploads meshes and textures and lets the driver compile its pipelines.
      auto rendered = render_scene(**backend, *scene, *plan, variants, *environment, {.frames = uint32_t(frames) + 1});
      if (!rendered) continue;
      std::vector<double> times;
      for (size_t frame = 1; frame < rendered->frame_timings.size(); ++frame)
        times.push_back(milliseconds_of(rendered->frame_timings[frame]));
      std::sort(times.begin(), times.end());
      if (times.empty()) continue;
      std::printf("| %s | %s | %zu | %.1f | %.2f | %.1f | %.1f | %.1f - %.1f |\n", scene->name.c_str(),
                  std::string(lane_name(lane)).c_str(), plan->variants.size(), cold_ms, warm_ms,
                  milliseconds_of(rendered->frame_timings.front()), times[times.size() / 2], times.front(),
                  times.back());
      std::fflush(stdout);
    }
  }
  fs::remove_all(cache_dir);
  return 0;
}
