// With one lane's driver missing, that lane says which Debian package to install, and the other
// lane still runs. Runs the real `xshade` binary with its environment changed.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

// Neither route to an OpenGL context: OSMesa missing alone makes the gl lane fall back to EGL.
constexpr const char* kNoOpenGl =
    "XSHADE_OSMESA_LIBRARY=/nonexistent/libOSMesa.so.8 XSHADE_EGL_LIBRARY=/nonexistent/libEGL.so.1";
// Both spellings: the loader reads VK_DRIVER_FILES, older loaders VK_ICD_FILENAMES.
constexpr const char* kNoLavapipe =
    "VK_DRIVER_FILES=/nonexistent/lvp_icd.json VK_ICD_FILENAMES=/nonexistent/lvp_icd.json";

TEST(MissingDriver, InfoNamesThePackageForGlAndStillShowsVk) {
  Outcome outcome = run_xshade(kNoOpenGl, "info");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("gl: unavailable"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("libosmesa6"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("vk: Vulkan 1.3 (lavapipe)"), std::string::npos) << outcome.output;
}

TEST(MissingDriver, InfoNamesThePackageForVkAndStillShowsGl) {
  Outcome outcome = run_xshade(kNoLavapipe, "info");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("vk: unavailable"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("mesa-vulkan-drivers"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("gl: OpenGL 4.5 core (OSMesa)"), std::string::npos) << outcome.output;
}

TEST(MissingDriver, RunStillRendersTheOtherLane) {
  const auto report = std::filesystem::temp_directory_path() / "xshade_missing_driver_report";
  std::filesystem::remove_all(report);
  // The smallest fixed scene, compiled afresh so that the cache plays no part.
  Outcome outcome = run_xshade(kNoOpenGl, "run toon_shadow_texture --no-cache --report '" + report.string() + "'");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("libosmesa6"), std::string::npos) << outcome.output;
  EXPECT_TRUE(std::filesystem::exists(report / "toon_shadow_texture" / "vk.png")) << outcome.output;
  EXPECT_TRUE(std::filesystem::exists(report / "toon_shadow_texture" / "vk-hlsl.png")) << outcome.output;
  EXPECT_FALSE(std::filesystem::exists(report / "toon_shadow_texture" / "gl.png"));
}

}  // namespace
}  // namespace xshade::tests
