#include "tests/lanes/probe_scene.h"

#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "harness/assets/environment.h"
#include "harness/assets/equirect.h"
#include "harness/image/image_io.h"
#include "harness/render/environment_cache.h"
#include "harness/render/lanes.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/shader_cache.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"
#include "harness/vulkan/vulkan_backend.h"

namespace xshade::tests {

namespace fs = std::filesystem;

namespace {
// The probes' environments, built once for the whole test run and kept in the build folder
// between test processes (by the hash of what they are made of, EnvironmentCache): every probe
// renders in the same environment on three lanes, and building one (its file read, its SH, its
// prefiltered mips) cost more than rendering the probe.
harness::EnvironmentCache& environments() {
  static harness::EnvironmentCache cache(XSHADE_TEST_CACHE_DIR, harness::compiler_identity());
  return cache;
}
}  // namespace

ProbeScene::ProbeScene(const std::string& name)
    : folder_(fs::temp_directory_path() / ("xshade_probe_" + name + "_" + std::to_string(::getpid()))) {
  fs::remove_all(folder_);
  fs::create_directories(folder_);
}

ProbeScene::~ProbeScene() {
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

void ProbeScene::write(const std::string& file, const std::string& text) const {
  fs::create_directories((folder_ / file).parent_path());
  std::ofstream(folder_ / file, std::ios::binary) << text;
}

void ProbeScene::write_image(const std::string& file, const harness::FloatImage& image) const {
  const fs::path path = folder_ / file;
  auto written = path.extension() == ".exr" ? harness::write_exr(image, path) : harness::write_png(image, path);
  if (!written) ADD_FAILURE() << written.error().to_string();
}

void ProbeScene::write_direction_equirect(const std::string& file) const {
  // One file for every probe, written once: an EXR's header holds the time it was written, and
  // the same bytes are what lets the environment cache find the environment built from them.
  const fs::path shared = fs::path(XSHADE_TEST_CACHE_DIR) / "direction_equirect.exr";
  if (!fs::exists(shared)) {
    fs::create_directories(shared.parent_path());
    const fs::path partial = shared.string() + "." + std::to_string(::getpid()) + ".exr";
    auto written = harness::write_exr(direction_equirect(), partial);
    if (!written) ADD_FAILURE() << written.error().to_string();
    fs::rename(partial, shared);  // whole or not at all, when two test processes write it at once
  }
  fs::copy_file(shared, folder_ / file, fs::copy_options::overwrite_existing);
}

Result<harness::FloatImage> ProbeScene::render(const std::string& scene_text, harness::Lane lane,
                                               harness::Backend& backend) const {
  auto scene = harness::parse_scene(scene_text, folder_ / "probe.toml");
  if (!scene) return fail(scene.error());
  const harness::ShaderSearchPath shaders(std::vector<fs::path>{folder_, XSHADE_SHADERS_DIR});
  auto plan = harness::plan_scene(*scene, shaders);
  if (!plan) return fail(plan.error());
  auto environment = environments().get(scene->environment);
  if (!environment) return fail(environment.error());
  harness::VariantCompiler compiler(shaders, nullptr);
  auto variants = compiler.compile_plan(*plan, lane, false);
  if (!variants) return fail(variants.error());
  auto rendered = harness::render_scene(backend, *scene, *plan, *variants, **environment);
  if (!rendered) return fail(rendered.error());
  return std::move(rendered->image);
}

const char* const kUnityBlitVertexFunctions = R"(
    float4x4 unity_ObjectToWorld;
    float4x4 unity_MatrixVP;
    struct Blit { float4 pos : SV_Position; float2 uv : TEXCOORD0; };
    Blit vert_img(float4 vertex : POSITION, float2 uv : TEXCOORD0) {
      Blit o;
      o.pos = mul(unity_MatrixVP, mul(unity_ObjectToWorld, float4(vertex.xyz, 1.0)));
      o.uv = uv;
      return o;
    }
    Blit vert_triangle(float4 vertex : POSITION) {
      Blit o;
      o.pos = float4(vertex.xy, 0.0, 1.0);
      o.uv = (vertex.xy + 1.0) * 0.5;
    #if UNITY_UV_STARTS_AT_TOP
      o.uv = o.uv * float2(1.0, -1.0) + float2(0.0, 1.0);
    #endif
      return o;
    }
)";

std::string probe_scene_head(const std::string& description, uint32_t width, uint32_t height) {
  return "description = \"" + description + "\"\nsize = [" + std::to_string(width) + ", " + std::to_string(height) +
         "]\n[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\nfov_y = 40\nnear = 0.1\nfar = 10\n";
}

harness::FloatImage direction_equirect() {
  harness::FloatImage image(256, 128);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      image.set(x, y, glm::vec4(0.5f + 0.5f * harness::equirect_texel_direction(x, y, 256, 128), 1.0f));
  return image;
}

namespace {
std::map<harness::Lane, std::unique_ptr<harness::Backend>>& backends() {
  static std::map<harness::Lane, std::unique_ptr<harness::Backend>> made;
  return made;
}
}  // namespace

harness::Backend& suite_backend(harness::Lane lane) {
  auto& made = backends();
  if (!made.count(lane)) {
    auto created = harness::create_backend(lane, {.validation = harness::vulkan_validation_available()});
    if (!created) throw std::runtime_error(std::string(harness::lane_name(lane)) + ": " + created.error().to_string());
    made[lane] = std::move(*created);
  }
  return *made.at(lane);
}

void release_suite_backends() { backends().clear(); }

void expect_no_driver_messages() {
  for (auto& [lane, backend] : backends())
    for (const std::string& message : backend->take_driver_messages())
      ADD_FAILURE() << harness::lane_name(lane) << " driver message: " << message;
}

}  // namespace xshade::tests
