// xshade run: plan each scene, compile what it needs (through the shader cache), render it on
// each of its lanes, write PNG and EXR per scene and lane, and compare the lanes.
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>
#include <system_error>

#include "harness/cli/commands.h"
#include "harness/cli/lane_selection.h"
#include "harness/environment.h"
#include "harness/image_io.h"
#include "harness/planner.h"
#include "harness/scene_renderer.h"
#include "harness/variant_compiler.h"

namespace xshade::cli {
namespace {

namespace fs = std::filesystem;

int worse(int a, int b) { return std::max(a, b); }

// The scene files a run covers: each argument is a scene name in the scenes folder or a path to
// a .toml file; no argument means every scene in the folder, by name.
Result<std::vector<fs::path>> scene_files(const RunOptions& options) {
  std::vector<fs::path> files;
  if (options.scenes.empty()) {
    std::error_code error;
    for (fs::directory_iterator it(options.scenes_dir, error), end; !error && it != end; it.increment(error))
      if (it->path().extension() == ".toml") files.push_back(it->path());
    if (error) return fail("cannot read the scenes folder " + options.scenes_dir.string() + ": " + error.message());
    std::sort(files.begin(), files.end());
    if (files.empty()) return fail("no scenes (*.toml) in " + options.scenes_dir.string());
    return files;
  }
  for (const std::string& scene : options.scenes) {
    const fs::path as_given(scene);
    files.push_back(as_given.extension() == ".toml" ? as_given : options.scenes_dir / (scene + ".toml"));
  }
  return files;
}

fs::path default_cache_dir() {
  if (const char* dir = std::getenv("XSHADE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir && *dir) return fs::path(dir) / "xshade";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "xshade";
  return fs::temp_directory_path() / "xshade-cache";
}

// NaN, infinite and negative channel values: none belongs in a rendered image.
struct NonFinite {
  size_t nan = 0, inf = 0, negative = 0;
  uint32_t first_x = 0, first_y = 0;
  size_t total() const { return nan + inf + negative; }
};

NonFinite count_non_finite(const harness::FloatImage& image) {
  NonFinite count;
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      const glm::vec4 p = image.at(x, y);
      const size_t before = count.total();
      for (int c = 0; c < 4; ++c) {
        if (std::isnan(p[c])) ++count.nan;
        else if (std::isinf(p[c])) ++count.inf;
        else if (p[c] < 0.0f) ++count.negative;
      }
      if (before == 0 && count.total() > 0) count.first_x = x, count.first_y = y;
    }
  return count;
}

// Pixels whose 8-bit sRGB encoding differs by more than `tolerance` steps in some channel.
struct ByteDifference {
  uint32_t max_steps = 0;
  size_t failing = 0;
};

ByteDifference byte_difference(const harness::FloatImage& a, const harness::FloatImage& b, uint32_t tolerance) {
  ByteDifference result;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      const glm::vec4 pa = a.at(x, y), pb = b.at(x, y);
      uint32_t worst = 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max<uint32_t>(worst, uint32_t(std::abs(int(harness::linear_to_srgb8(pa[c])) -
                                                             int(harness::linear_to_srgb8(pb[c])))));
      result.max_steps = std::max(result.max_steps, worst);
      if (worst > tolerance) ++result.failing;
    }
  return result;
}

class SceneRun {
 public:
  SceneRun(const RunOptions& options, const std::vector<harness::Lane>& lanes, harness::VariantCompiler& compiler)
      : options_(options), lanes_(lanes), compiler_(compiler) {}

  // The exit code of one scene.
  int run(const fs::path& file, size_t index, size_t count) {
    auto scene = harness::load_scene(file);
    if (!scene) {
      print_error(file.stem().string(), scene.error());
      return kBadInput;
    }
    auto plan = harness::plan_scene(*scene, options_.shaders_dir);
    if (!plan) {
      print_error(scene->name, plan.error());
      return kBadInput;
    }
    std::vector<harness::Lane> lanes;
    for (harness::Lane lane : lanes_)
      if (std::find(scene->lanes.begin(), scene->lanes.end(), harness::lane_name(lane)) != scene->lanes.end())
        lanes.push_back(lane);

    if (options_.plan_only) {
      std::vector<bool> cached;
      for (const harness::VariantRequest& variant : plan->variants)
        cached.push_back(std::all_of(lanes.begin(), lanes.end(),
                                     [&](harness::Lane lane) { return compiler_.in_cache(variant, lane); }));
      fmt::print("{}", harness::describe_plan(*scene, *plan, cached));
      return kPass;
    }

    auto environment = harness::build_environment(harness::environment_desc(scene->environment));
    if (!environment) {
      print_error(scene->name, environment.error());
      return kBadInput;
    }

    int exit_code = kPass;
    std::map<harness::Lane, harness::FloatImage> images;
    for (harness::Lane lane : lanes) {
      const auto start = std::chrono::steady_clock::now();
      fmt::print("[{}/{}] {} on {} ... ", index + 1, count, scene->name, harness::lane_name(lane));
      std::fflush(stdout);
      auto image = render_on(*scene, *plan, *environment, lane, exit_code);
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      if (!image) continue;
      const NonFinite bad = count_non_finite(*image);
      fmt::print("{:.2f} s", elapsed.count());
      if (bad.total())
        fmt::print(", {} NaN, {} Inf, {} negative values, first at ({}, {})", bad.nan, bad.inf, bad.negative,
                   bad.first_x, bad.first_y);
      fmt::print("\n");
      exit_code = worse(exit_code, write_images(*scene, lane, *image));
      images.emplace(lane, std::move(*image));
    }
    return worse(exit_code, compare_lanes(*scene, images));
  }

 private:
  void print_error(const std::string& scene, const Error& error) {
    fmt::print(stderr, "xshade run: {}: {}\n", scene, error.to_string());
  }

  std::optional<harness::FloatImage> render_on(const harness::Scene& scene, const harness::Plan& plan,
                                               const harness::Environment& environment, harness::Lane lane,
                                               int& exit_code) {
    std::vector<harness::CompiledVariant> variants;
    for (const harness::VariantRequest& request : plan.variants) {
      auto compiled = compiler_.compile(request, lane);
      if (!compiled) {
        fmt::print("compile failed\n");
        print_error(scene.name, compiled.error());
        exit_code = worse(exit_code, kBadInput);
        return std::nullopt;
      }
      variants.push_back(std::move(*compiled));
    }
    auto backend = harness::create_backend(lane, {.validation = options_.selection.validation});
    if (!backend) {
      fmt::print("unavailable\n");
      print_error(scene.name, backend.error());
      exit_code = worse(exit_code, kBackendError);
      return std::nullopt;
    }
    auto rendered = harness::render_scene(**backend, scene, plan, variants, environment,
                                          {.keep_pass_images = options_.pass_images});
    std::vector<std::string> messages = (*backend)->take_driver_messages();
    if (!rendered) {
      fmt::print("render failed\n");
      print_error(scene.name, rendered.error());
      exit_code = worse(exit_code, kBackendError);
      return std::nullopt;
    }
    for (const std::string& message : messages) {
      fmt::print("\n  driver message: {}", message);
      exit_code = worse(exit_code, kTestFailed);
    }
    for (const auto& [pass, image] : rendered->pass_images) {
      const fs::path file = options_.report_dir / scene.name / "passes" / (pass + "." + std::string(harness::lane_name(lane)) + ".exr");
      std::error_code ignored;
      fs::create_directories(file.parent_path(), ignored);
      if (auto written = harness::write_exr(image, file); !written) print_error(scene.name, written.error());
    }
    return std::move(rendered->image);
  }

  int write_images(const harness::Scene& scene, harness::Lane lane, const harness::FloatImage& image) {
    const fs::path dir = options_.report_dir / scene.name;
    std::error_code error;
    fs::create_directories(dir, error);
    const std::string name(harness::lane_name(lane));
    int exit_code = kPass;
    for (auto written : {harness::write_png(image, dir / (name + ".png")), harness::write_exr(image, dir / (name + ".exr"))}) {
      if (!written) {
        print_error(scene.name, written.error());
        exit_code = kBackendError;
      }
    }
    return exit_code;
  }

  // Every lane against the first that rendered, within the scene's tolerance.
  int compare_lanes(const harness::Scene& scene, const std::map<harness::Lane, harness::FloatImage>& images) {
    if (images.size() < 2) return kPass;
    int exit_code = kPass;
    const auto& [first_lane, first] = *images.begin();
    const size_t pixels = size_t(first.width) * first.height;
    for (const auto& [lane, image] : images) {
      if (lane == first_lane) continue;
      const std::string pair = fmt::format("{} vs {}", harness::lane_name(first_lane), harness::lane_name(lane));
      if (harness::bitwise_equal(first, image)) {
        fmt::print("  {}: bit-identical\n", pair);
        continue;
      }
      const harness::ImageDifference diff = harness::max_difference(first, image);
      const ByteDifference bytes = byte_difference(first, image, scene.compare.channel_tolerance);
      const bool pass = double(bytes.failing) <= scene.compare.max_failing_fraction * double(pixels);
      fmt::print("  {}: max {:.3g} at ({}, {}); {} sRGB steps at most, {} pixels beyond {} -> {}\n", pair, diff.max,
                 diff.x, diff.y, bytes.max_steps, bytes.failing, scene.compare.channel_tolerance,
                 pass ? "agree" : "DISAGREE");
      if (!pass) exit_code = kTestFailed;
    }
    return exit_code;
  }

  const RunOptions& options_;
  const std::vector<harness::Lane>& lanes_;
  harness::VariantCompiler& compiler_;
};

}  // namespace

int run_run(const RunOptions& options) {
  auto lanes = resolve_lanes(options.selection);
  if (!lanes) {
    fmt::print(stderr, "xshade run: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  auto files = scene_files(options);
  if (!files) {
    fmt::print(stderr, "xshade run: {}\n", files.error().to_string());
    return kBadInput;
  }
  std::optional<harness::ShaderCache> cache;
  if (!options.no_cache)
    cache.emplace(options.cache_dir.empty() ? default_cache_dir() : options.cache_dir, harness::compiler_identity());
  harness::VariantCompiler compiler(options.shaders_dir, cache ? &*cache : nullptr);

  int exit_code = kPass;
  SceneRun scene_run(options, *lanes, compiler);
  for (size_t i = 0; i < files->size(); ++i) exit_code = worse(exit_code, scene_run.run((*files)[i], i, files->size()));

  if (!options.plan_only) {
    fmt::print("shaders: {} compiled, {} from the cache{}\n", compiler.compiled(), compiler.cached(),
               cache ? " (" + cache->directory().string() + ")" : std::string(" (cache off)"));
    if (compiler.cache_write_error()) fmt::print("warning: {}\n", compiler.cache_write_error()->to_string());
    fmt::print("images in {}\n", options.report_dir.string());
  }
  return exit_code;
}

}  // namespace xshade::cli
