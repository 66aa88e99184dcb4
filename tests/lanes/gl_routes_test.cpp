// Both routes to the gl lane's context, OSMesa and EGL surfaceless, drive the same Mesa llvmpipe,
// so every fixed scene must come out of them bit for bit the same: the final image and each
// pass's own image. One test per scene file of scenes/ (found when the test runs); each
// compiles the scene for the gl lane once and renders it through a backend of each route, the
// two living side by side in one process as they do in a user's run.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "harness/assets/environment.h"
#include "harness/gl/gl_backend.h"
#include "harness/image/image.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;
using harness::FloatImage;
using harness::GlPlatform;

std::vector<std::string> scene_names() {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(XSHADE_SCENES_DIR, error))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string describe_difference(const FloatImage& osmesa, const FloatImage& egl) {
  if (osmesa.width != egl.width || osmesa.height != egl.height)
    return fmt::format("sizes differ: {}x{} through OSMesa, {}x{} through EGL", osmesa.width, osmesa.height, egl.width,
                       egl.height);
  const harness::ImageDifference difference = harness::max_difference(osmesa, egl);
  const glm::vec4 a = osmesa.at(difference.x, difference.y);
  const glm::vec4 b = egl.at(difference.x, difference.y);
  return fmt::format("largest difference {} in channel {} at ({}, {}): OSMesa ({}, {}, {}, {}), EGL ({}, {}, {}, {})",
                     difference.max, difference.channel, difference.x, difference.y, a.r, a.g, a.b, a.a, b.r, b.g, b.b,
                     b.a);
}

TEST(GlRoutesAgree, TheScenesFolderHasScenes) {
  EXPECT_FALSE(scene_names().empty()) << "no .toml file in " << XSHADE_SCENES_DIR;
}

class GlRoutesAgreeOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(GlRoutesAgreeOnScene, BitForBit) {
  auto scene = harness::load_scene(fs::path(XSHADE_SCENES_DIR) / (GetParam() + ".toml"));
  ASSERT_TRUE(scene) << scene.error().to_string();
  if (std::find(scene->lanes.begin(), scene->lanes.end(), "gl") == scene->lanes.end())
    GTEST_SKIP() << GetParam() << " does not run on the gl lane";
  auto plan = harness::plan_scene(*scene, fs::path(XSHADE_SHADERS_DIR));
  ASSERT_TRUE(plan) << plan.error().to_string();
  harness::VariantCompiler compiler(fs::path(XSHADE_SHADERS_DIR), nullptr);
  auto variants = compiler.compile_plan(*plan, harness::Lane::Gl, false);
  ASSERT_TRUE(variants) << variants.error().to_string();
  auto environment = harness::build_environment(scene->environment);
  ASSERT_TRUE(environment) << environment.error().to_string();

  auto osmesa = harness::create_gl_backend({.platform = GlPlatform::Osmesa});
  ASSERT_TRUE(osmesa) << osmesa.error().to_string();
  auto egl = harness::create_gl_backend({.platform = GlPlatform::Egl});
  ASSERT_TRUE(egl) << egl.error().to_string();
  const harness::RenderOptions keep{.keep_pass_images = true};
  auto through_osmesa = harness::render_scene(**osmesa, *scene, *plan, *variants, *environment, keep);
  ASSERT_TRUE(through_osmesa) << through_osmesa.error().to_string();
  auto through_egl = harness::render_scene(**egl, *scene, *plan, *variants, *environment, keep);
  ASSERT_TRUE(through_egl) << through_egl.error().to_string();
  EXPECT_EQ((*osmesa)->take_driver_messages(), std::vector<std::string>{});
  EXPECT_EQ((*egl)->take_driver_messages(), std::vector<std::string>{});

  const auto& passes = through_osmesa->pass_images;
  ASSERT_EQ(passes.size(), through_egl->pass_images.size());
  ASSERT_FALSE(passes.empty());
  for (size_t i = 0; i < passes.size(); ++i) {
    const auto& [name, image] = passes[i];
    const auto& [egl_name, egl_image] = through_egl->pass_images[i];
    ASSERT_EQ(name, egl_name);
    EXPECT_TRUE(harness::bitwise_equal(image, egl_image))
        << GetParam() << ", pass " << name << ": " << describe_difference(image, egl_image);
  }
  EXPECT_TRUE(harness::bitwise_equal(through_osmesa->image, through_egl->image))
      << GetParam() << ", final image: " << describe_difference(through_osmesa->image, through_egl->image);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GlRoutesAgreeOnScene, ::testing::ValuesIn(scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& scene) {
                           std::string name = scene.param;  // gtest names take letters, digits and _
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace xshade::tests
