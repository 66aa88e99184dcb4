// The sensitivity proof of golden gating: for every fixed scene, a small but real change to what
// the scene shows must FAIL against the scene's committed golden with the scene's own [compare]
// tolerances, while a plain re-render PASSES. A gate that lets these through would let a real
// regression of the same size through too.
//
// The perturbations:
//   camera_shift   camera position and target moved sideways (along the camera's right vector)
//                  by the world-space width of one pixel at the target's distance; every scene.
//   rim_threshold  the toon material's _RimThreshold moved from its default 0.5 to 0.55, as a
//                  property of every toon object; scenes with a toon object.
//   fresnel_r0     the dielectric Fresnel R0 of diffuse_and_specular_from_metallic moved from
//                  0.04 to 0.05, in a copy of the shader library; scenes with a standard_pbr object.
//   bokeh_ring     the outermost ring of the active bokeh kernel removed (and its sample count
//                  fixed), in a copy of the shader library; scenes with depth of field.
//
// One lane is enough: what is proved is that the golden comparison notices the change, and the
// comparison is the same code whichever lane rendered the image. The gl lane is the cheapest to
// start, and every fixed scene's golden serves it. Nothing goes through the shader cache: a
// perturbed library copy compiles to a different program than the real library, and without a
// cache no lookup can ever hand one of them out for the other.
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "harness/assets/environment.h"
#include "harness/gate/golden_store.h"
#include "harness/image/image_compare.h"
#include "harness/render/lanes.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = XSHADE_SOURCE_DIR;
const fs::path kShaderLibrary = kSourceDir / "shaders";
const fs::path kScenesDir = kSourceDir / "scenes";
const fs::path kGoldenDir = kSourceDir / "golden";

constexpr Lane kLane = Lane::Gl;
const std::string kLaneName(lane_name(kLane));

const std::string kToonMaterial = "materials/toon.hlsl";
const std::string kStandardMaterial = "materials/standard_pbr.hlsl";
const std::string kDepthOfField = "post/depth_of_field.hlsl";

// The toon material's default rim threshold and how far the perturbation moves it.
constexpr float kRimThresholdDefault = 0.5f;
constexpr float kRimThresholdStep = 0.05f;

// The R0 line of diffuse_and_specular_from_metallic, and the perturbed one.
const std::string kR0Line = "spec_color = lerp(float3(0.04, 0.04, 0.04), albedo, metallic);";
const std::string kPerturbedR0Line = "spec_color = lerp(float3(0.05, 0.05, 0.05), albedo, metallic);";

enum class Perturbation { CameraShift, RimThreshold, FresnelR0, BokehRing };

std::string perturbation_name(Perturbation perturbation) {
  switch (perturbation) {
    case Perturbation::CameraShift: return "camera_shift";
    case Perturbation::RimThreshold: return "rim_threshold";
    case Perturbation::FresnelR0: return "fresnel_r0";
    case Perturbation::BokehRing: return "bokeh_ring";
  }
  return "unknown";
}

struct SensitivityCase {
  std::string scene;
  Perturbation perturbation;
};

void PrintTo(const SensitivityCase& c, std::ostream* out) {
  *out << c.scene << " / " << perturbation_name(c.perturbation);
}

// Every fixed scene. FixedScenesAreExactlyTheSceneFolder keeps this list honest: a new scene
// without a sensitivity proof fails there.
const std::vector<std::string> kFixedScenes = {
    "dof_off",
    "dof_on_16",
    "dof_on_22",
    "dof_on_43",
    "dof_on_71",
    "material_grid",
    "material_grid_guarded",
    "toon_shadow_texture",
    "toon_vs_standard",
    "white_furnace",
};

// Which perturbations apply to a scene follows from what it draws; the table is written out so
// that every test has a stable name, and PerturbationsCoverWhatEachSceneDraws checks it.
const std::vector<SensitivityCase> kCases = {
    {"dof_off", Perturbation::CameraShift},
    {"dof_off", Perturbation::FresnelR0},
    {"dof_on_16", Perturbation::CameraShift},
    {"dof_on_16", Perturbation::FresnelR0},
    {"dof_on_16", Perturbation::BokehRing},
    {"dof_on_22", Perturbation::CameraShift},
    {"dof_on_22", Perturbation::FresnelR0},
    {"dof_on_22", Perturbation::BokehRing},
    {"dof_on_43", Perturbation::CameraShift},
    {"dof_on_43", Perturbation::FresnelR0},
    {"dof_on_43", Perturbation::BokehRing},
    {"dof_on_71", Perturbation::CameraShift},
    {"dof_on_71", Perturbation::FresnelR0},
    {"dof_on_71", Perturbation::BokehRing},
    {"material_grid", Perturbation::CameraShift},
    {"material_grid", Perturbation::FresnelR0},
    {"material_grid_guarded", Perturbation::CameraShift},
    {"material_grid_guarded", Perturbation::FresnelR0},
    {"toon_shadow_texture", Perturbation::CameraShift},
    {"toon_shadow_texture", Perturbation::RimThreshold},
    {"toon_vs_standard", Perturbation::CameraShift},
    {"toon_vs_standard", Perturbation::RimThreshold},
    {"toon_vs_standard", Perturbation::FresnelR0},
    {"white_furnace", Perturbation::CameraShift},
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

Scene load_fixed_scene(const std::string& name) {
  auto scene = load_scene(kScenesDir / (name + ".toml"));
  if (!scene) throw std::runtime_error(scene.error().to_string());
  return *scene;
}

bool draws_material(const Scene& scene, const std::string& material) {
  return std::any_of(scene.objects.begin(), scene.objects.end(),
                     [&](const SceneObject& object) { return object.material == material; });
}

// The Fresnel R0 of 0.04 shows on dielectrics only: a pure metal's (metallic 1) R0 is its albedo.
bool draws_dielectric(const Scene& scene) {
  for (const ObjectInstance& instance : expand_instances(scene)) {
    if (instance.material != kStandardMaterial) continue;
    auto metallic = instance.properties.find("_Metallic");
    if (metallic == instance.properties.end() || metallic->second.components[0] < 1.0f) return true;
  }
  return false;
}

const PostEffect* depth_of_field(const Scene& scene) {
  for (const PostEffect& effect : scene.post)
    if (effect.effect == kDepthOfField) return &effect;
  return nullptr;
}

// A private copy of the shader library in a fresh temporary folder, removed with the object, so
// that a perturbation never touches the real library and parallel tests never share a copy.
class ShaderLibraryCopy {
 public:
  ShaderLibraryCopy() {
    std::string pattern = (fs::temp_directory_path() / "xshade_sensitivity_XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder from " + pattern);
    folder_ = pattern;
    fs::copy(kShaderLibrary, root(), fs::copy_options::recursive);
  }
  ~ShaderLibraryCopy() {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }
  ShaderLibraryCopy(const ShaderLibraryCopy&) = delete;
  ShaderLibraryCopy& operator=(const ShaderLibraryCopy&) = delete;

  fs::path root() const { return folder_ / "shaders"; }

 private:
  fs::path folder_;
};

// `text` with its one occurrence of `from` replaced by `to`; nullopt unless it occurs exactly once.
std::optional<std::string> replace_once(const std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) return std::nullopt;
  return text.substr(0, at) + to + text.substr(at + from.size());
}

// What dropping the outer ring did, for the test's messages.
struct RingDrop {
  int samples_before = 0;
  int samples_after = 0;
  float outer_radius = 0.0f;
};

// dof_kernels.hlsl with the outermost ring of the kernel `keyword` selects removed and its
// sample count (the array's size and kBokehSampleCount) set to what is left.
Result<std::pair<std::string, RingDrop>> drop_outer_ring(const std::string& kernels, const std::string& keyword) {
  const std::regex block_start("#(el)?if defined\\(" + keyword + "\\)\\n");
  std::smatch start;
  if (!std::regex_search(kernels, start, block_start))
    return fail(ErrorKind::UserInput, "no kernel block for " + keyword);
  const size_t block_begin = size_t(start.position(0) + start.length(0));
  const size_t block_end = kernels.find("};", block_begin);
  if (block_end == std::string::npos)
    return fail(ErrorKind::UserInput, "the " + keyword + " kernel has no closing '};'");
  const std::string block = kernels.substr(block_begin, block_end - block_begin);

  std::smatch count;
  if (!std::regex_search(block, count, std::regex("static const int kBokehSampleCount = (\\d+);\\n")))
    return fail(ErrorKind::UserInput, "the " + keyword + " kernel declares no kBokehSampleCount");
  const int samples = std::stoi(count[1]);
  const std::string array_head = "static const float2 kBokehKernel[" + std::to_string(samples) + "] = {\n";
  const size_t points_begin = block.find(array_head);
  if (points_begin == std::string::npos)
    return fail(ErrorKind::UserInput, "the " + keyword + " kernel's array is not " + array_head);

  struct Point {
    std::string text;
    float radius;
  };
  std::vector<Point> points;
  const std::regex point("float2\\((-?[0-9.]+), (-?[0-9.]+)\\)");
  const std::string body = block.substr(points_begin + array_head.size());
  for (auto it = std::sregex_iterator(body.begin(), body.end(), point); it != std::sregex_iterator(); ++it)
    points.push_back({it->str(0), std::hypot(std::stof((*it)[1]), std::stof((*it)[2]))});
  if (int(points.size()) != samples)
    return fail(ErrorKind::UserInput, "the " + keyword + " kernel lists " + std::to_string(points.size()) +
                                          " points, not " + std::to_string(samples));

  // A ring is the points at one radius; the kernel values carry 7 digits.
  float outer = 0.0f;
  for (const Point& p : points) outer = std::max(outer, p.radius);
  std::string kept;
  int remaining = 0;
  for (const Point& p : points) {
    if (p.radius > outer - 1e-4f) continue;
    kept += (remaining ? ",\n  " : "  ") + p.text;
    ++remaining;
  }
  if (remaining == 0 || remaining == samples)
    return fail(ErrorKind::UserInput, "the " + keyword + " kernel has no separate outer ring");

  std::string new_block = block.substr(0, size_t(count.position(0)));
  new_block += "static const int kBokehSampleCount = " + std::to_string(remaining) + ";\n";
  new_block += block.substr(size_t(count.position(0) + count.length(0)),
                            points_begin - size_t(count.position(0) + count.length(0)));
  new_block += "static const float2 kBokehKernel[" + std::to_string(remaining) + "] = {\n" + kept + "\n";
  std::string result = kernels.substr(0, block_begin) + new_block + kernels.substr(block_end);
  return std::pair{result, RingDrop{samples, remaining, outer}};
}

// Moves the camera sideways by the world-space width of one pixel at the target's distance.
void shift_camera_one_pixel(Camera& camera, uint32_t height) {
  const glm::vec3 forward = camera.target - camera.position;
  const float distance = glm::length(forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const float pixel_width = 2.0f * distance * std::tan(glm::radians(camera.fov_y_degrees) / 2.0f) / float(height);
  camera.position += right * pixel_width;
  camera.target += right * pixel_width;
}

// One environment per scene for the whole process: building it (the prefiltered texture) is the
// slowest part of a render, and no perturbation here touches it.
const Environment& environment_of(const Scene& scene) {
  static std::map<std::string, Environment> built;
  auto found = built.find(scene.name);
  if (found != built.end()) return found->second;
  auto environment = build_environment(scene.environment);
  if (!environment) throw std::runtime_error(environment.error().to_string());
  return built.emplace(scene.name, std::move(*environment)).first->second;
}

// Renders `scene` on the gl lane with the shader library at `shader_root` (compiled without a
// cache) and compares the image with the scene's golden using the scene's [compare] settings.
Result<Comparison> render_against_golden(const Scene& scene, const fs::path& shader_root) {
  auto plan = plan_scene(scene, shader_root);
  if (!plan) return fail(plan.error());
  for (const VariantRequest& request : plan->variants)
    if (std::mismatch(shader_root.begin(), shader_root.end(), request.source.begin(), request.source.end()).first !=
        shader_root.end())
      return fail(ErrorKind::Internal, request.label() + " was planned from " + request.source.string() + ", outside " +
                                           shader_root.string());

  VariantCompiler compiler(shader_root, nullptr);
  std::vector<CompiledVariant> variants;
  for (const VariantRequest& request : plan->variants) {
    auto compiled = compiler.compile(request, kLane);
    if (!compiled) return fail(compiled.error());
    variants.push_back(std::move(*compiled));
  }
  auto backend = create_backend(kLane);
  if (!backend) return fail(backend.error());
  auto rendered = render_scene(**backend, scene, *plan, variants, environment_of(scene));
  if (!rendered) return fail(rendered.error());

  const GoldenStore goldens(kGoldenDir);
  auto golden = goldens.find(scene.name, kLaneName);
  if (!golden) return fail(golden.error());
  if (!*golden) return fail(ErrorKind::UserInput, goldens.missing_message(scene.name, kLaneName));
  return compare_images(rendered->image, (*golden)->image, scene.compare);
}

// The comparison as a reviewer reads it: failing pixels and worst steps (the per-pixel layer),
// what the position layer forgave, and the summary.
std::string describe(const Comparison& comparison) {
  std::string text = "verdict " + std::string(verdict_name(comparison.verdict)) + ", decided by " +
                     comparison.decided_by + "; failing pixels " + std::to_string(comparison.metrics.failing_pixels);
  for (const LayerResult& layer : comparison.layers)
    if (layer.layer == "per_pixel" || layer.layer == "position" || layer.layer == "summary" || layer.layer == "size")
      text += "\n  " + layer.layer + ": " + layer.detail;
  return text;
}

// ---- The scene list -------------------------------------------------------------------------

TEST(SensitivityCoverage, FixedScenesAreExactlyTheSceneFolder) {
  std::set<std::string> on_disk;
  for (const fs::directory_entry& entry : fs::directory_iterator(kScenesDir))
    if (entry.path().extension() == ".toml") on_disk.insert(entry.path().stem().string());
  EXPECT_EQ(on_disk, std::set<std::string>(kFixedScenes.begin(), kFixedScenes.end()));
}

// Every perturbation that applies to a scene is in the table, and none that does not.
TEST(SensitivityCoverage, PerturbationsCoverWhatEachSceneDraws) {
  for (const std::string& name : kFixedScenes) {
    const Scene scene = load_fixed_scene(name);
    std::set<Perturbation> expected = {Perturbation::CameraShift};
    if (draws_material(scene, kToonMaterial)) expected.insert(Perturbation::RimThreshold);
    if (draws_dielectric(scene)) expected.insert(Perturbation::FresnelR0);
    if (depth_of_field(scene)) expected.insert(Perturbation::BokehRing);
    std::set<Perturbation> listed;
    for (const SensitivityCase& c : kCases)
      if (c.scene == name) listed.insert(c.perturbation);
    EXPECT_EQ(listed, expected) << name;
  }
}

// The perturbations move what they say they move: the defaults they start from are still the
// library's.
TEST(SensitivityCoverage, PerturbationsStartFromTheLibrarysValues) {
  const std::string toon = read_text(kShaderLibrary / kToonMaterial);
  EXPECT_NE(
      toon.find(
          "fixed _RimThreshold <string UIName = \"Rim threshold\"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;"),
      std::string::npos)
      << "the toon material's _RimThreshold default is no longer " << kRimThresholdDefault;
  EXPECT_TRUE(replace_once(read_text(kShaderLibrary / "include" / "brdf.hlsl"), kR0Line, kPerturbedR0Line))
      << "brdf.hlsl no longer holds exactly one '" << kR0Line << "'";
}

TEST(SensitivityCoverage, OneRingIsDroppedFromEachKernel) {
  const std::string kernels = read_text(kShaderLibrary / "include" / "dof_kernels.hlsl");
  // The outer ring of each kernel (radius 1) and what remains: the rings inside it.
  const std::map<std::string, std::pair<int, int>> expected = {{"_KERNEL_SMALL", {16, 6}},
                                                               {"_KERNEL_MEDIUM", {22, 8}},
                                                               {"_KERNEL_LARGE", {43, 22}},
                                                               {"_KERNEL_VERY_LARGE", {71, 43}}};
  for (const auto& [keyword, counts] : expected) {
    auto dropped = drop_outer_ring(kernels, keyword);
    ASSERT_TRUE(dropped) << dropped.error().to_string();
    EXPECT_EQ(dropped->second.samples_before, counts.first) << keyword;
    EXPECT_EQ(dropped->second.samples_after, counts.second) << keyword;
    EXPECT_NEAR(dropped->second.outer_radius, 1.0f, 1e-6f) << keyword;
    // The other kernels are untouched.
    for (const auto& [other, other_counts] : expected) {
      if (other != keyword) {
        EXPECT_NE(dropped->first.find("kBokehKernel[" + std::to_string(other_counts.first) + "]"), std::string::npos);
      }
    }
  }
}

TEST(SensitivityCoverage, TheCameraMovesByOnePixelAtTheTarget) {
  Camera camera;
  camera.position = {0.0f, 0.0f, 10.0f};
  camera.target = {0.0f, 0.0f, 0.0f};
  camera.fov_y_degrees = 90.0f;
  shift_camera_one_pixel(camera, 200);
  // The view spans 2 * 10 * tan(45 degrees) = 20 units over 200 pixels; right is +x.
  EXPECT_NEAR(camera.position.x, 0.1f, 1e-6f);
  EXPECT_NEAR(camera.target.x, 0.1f, 1e-6f);
  EXPECT_EQ(camera.position.y, 0.0f);
  EXPECT_EQ(camera.target.z, 0.0f);
}

// ---- A plain re-render passes ---------------------------------------------------------------

class SensitivityRerender : public ::testing::TestWithParam<std::string> {};

TEST_P(SensitivityRerender, PassesAgainstTheGolden) {
  const Scene scene = load_fixed_scene(GetParam());
  auto comparison = render_against_golden(scene, kShaderLibrary);
  ASSERT_TRUE(comparison) << comparison.error().to_string();
  std::cout << scene.name << " / re-render: " << describe(*comparison) << "\n";
  EXPECT_EQ(comparison->verdict, Verdict::Pass) << scene.name << " re-rendered: " << describe(*comparison);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SensitivityRerender, ::testing::ValuesIn(kFixedScenes),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

// ---- A perturbed render fails ---------------------------------------------------------------

class SensitivityPerturbed : public ::testing::TestWithParam<SensitivityCase> {};

TEST_P(SensitivityPerturbed, FailsAgainstTheGolden) {
  const SensitivityCase& c = GetParam();
  Scene scene = load_fixed_scene(c.scene);
  std::optional<ShaderLibraryCopy> library;
  std::string what;

  switch (c.perturbation) {
    case Perturbation::CameraShift: {
      const Camera before = scene.camera;
      shift_camera_one_pixel(scene.camera, scene.height);
      what = "camera moved by " + std::to_string(glm::length(scene.camera.position - before.position)) +
             " world units to the right";
      break;
    }
    case Perturbation::RimThreshold: {
      int toon_objects = 0;
      for (SceneObject& object : scene.objects) {
        if (object.material != kToonMaterial) continue;
        ASSERT_EQ(object.properties.count("_RimThreshold"), 0u) << object.name << " sets its own _RimThreshold";
        object.properties["_RimThreshold"] = PropertyValue::scalar(kRimThresholdDefault + kRimThresholdStep);
        ++toon_objects;
      }
      ASSERT_GT(toon_objects, 0);
      what = "_RimThreshold 0.5 -> 0.55 on " + std::to_string(toon_objects) + " toon object(s)";
      break;
    }
    case Perturbation::FresnelR0: {
      library.emplace();
      const fs::path brdf = library->root() / "include" / "brdf.hlsl";
      auto edited = replace_once(read_text(brdf), kR0Line, kPerturbedR0Line);
      ASSERT_TRUE(edited) << brdf << " does not hold exactly one '" << kR0Line << "'";
      write_text(brdf, *edited);
      what = "dielectric R0 0.04 -> 0.05 in a library copy";
      break;
    }
    case Perturbation::BokehRing: {
      const PostEffect* effect = depth_of_field(scene);
      ASSERT_NE(effect, nullptr);
      auto kernel = std::find_if(effect->keywords.begin(), effect->keywords.end(),
                                 [](const std::string& k) { return k.rfind("_KERNEL_", 0) == 0; });
      ASSERT_NE(kernel, effect->keywords.end()) << "the depth of field names no kernel";
      library.emplace();
      const fs::path kernels = library->root() / "include" / "dof_kernels.hlsl";
      auto dropped = drop_outer_ring(read_text(kernels), *kernel);
      ASSERT_TRUE(dropped) << dropped.error().to_string();
      write_text(kernels, dropped->first);
      what = *kernel + " " + std::to_string(dropped->second.samples_before) + " -> " +
             std::to_string(dropped->second.samples_after) + " samples in a library copy";
      break;
    }
  }

  auto comparison = render_against_golden(scene, library ? library->root() : kShaderLibrary);
  ASSERT_TRUE(comparison) << comparison.error().to_string();
  // Printed on success too: how far inside the gate each perturbation lands is worth watching.
  std::cout << c.scene << " / " << perturbation_name(c.perturbation) << " (" << what << "): " << describe(*comparison)
            << "\n";
  EXPECT_EQ(comparison->verdict, Verdict::Fail)
      << c.scene << " with " << perturbation_name(c.perturbation) << " (" << what
      << ") PASSES against its golden: the gate would miss this change. " << describe(*comparison);
}

INSTANTIATE_TEST_SUITE_P(Scenes, SensitivityPerturbed, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<SensitivityCase>& param) {
                           return param.param.scene + "_" + perturbation_name(param.param.perturbation);
                         });

}  // namespace
}  // namespace xshade::harness
