// Choosing the gl lane's route from the command line, end to end: the real `xshade` binary with
// --gl-platform and with the environment changed.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

TEST(GlPlatform, InfoShowsTheRouteAsked) {
  Outcome egl = run_xshade("", "info --lane gl --gl-platform egl");
  EXPECT_EQ(egl.exit_code, 0) << egl.output;
  EXPECT_NE(egl.output.find("gl: OpenGL 4.5 core (EGL surfaceless)"), std::string::npos) << egl.output;
  EXPECT_NE(egl.output.find("llvmpipe"), std::string::npos) << egl.output;
  Outcome osmesa = run_xshade("", "info --lane gl --gl-platform osmesa");
  EXPECT_EQ(osmesa.exit_code, 0) << osmesa.output;
  EXPECT_NE(osmesa.output.find("gl: OpenGL 4.5 core (OSMesa)"), std::string::npos) << osmesa.output;
}

// A Mesa of 25.1 or later has no OSMesa: auto must then find the EGL route by itself.
TEST(GlPlatform, AutoRunsOnEglWhereOsmesaIsMissing) {
  Outcome outcome = run_xshade("XSHADE_OSMESA_LIBRARY=/nonexistent/libOSMesa.so.8", "info --lane gl");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("gl: OpenGL 4.5 core (EGL surfaceless)"), std::string::npos) << outcome.output;
}

TEST(GlPlatform, AnExplicitRouteDoesNotFallBack) {
  Outcome outcome = run_xshade("XSHADE_EGL_LIBRARY=/nonexistent/libEGL.so.1", "info --lane gl --gl-platform egl");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("gl: unavailable"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("libegl1"), std::string::npos) << outcome.output;
  EXPECT_EQ(outcome.output.find("OSMesa"), std::string::npos) << outcome.output;
}

// The EGL route must be llvmpipe; a setting that leads to another driver fails and says which.
// zink (OpenGL on Vulkan, here on lavapipe) makes a 4.5 context whose renderer names llvmpipe too.
TEST(GlPlatform, EglRefusesARendererOtherThanLlvmpipe) {
  Outcome zink = run_xshade("GALLIUM_DRIVER=zink", "info --lane gl --gl-platform egl");
  EXPECT_EQ(zink.exit_code, 3) << zink.output;
  EXPECT_NE(zink.output.find("gives the renderer 'zink"), std::string::npos) << zink.output;
  EXPECT_NE(zink.output.find("not llvmpipe"), std::string::npos) << zink.output;
  EXPECT_NE(zink.output.find("GALLIUM_DRIVER=zink"), std::string::npos) << zink.output;
  // softpipe offers no 4.5 core context at all.
  Outcome softpipe = run_xshade("GALLIUM_DRIVER=softpipe", "info --lane gl --gl-platform egl");
  EXPECT_EQ(softpipe.exit_code, 3) << softpipe.output;
  EXPECT_NE(softpipe.output.find("llvmpipe is needed"), std::string::npos) << softpipe.output;
  EXPECT_NE(softpipe.output.find("GALLIUM_DRIVER=softpipe"), std::string::npos) << softpipe.output;
}

TEST(GlPlatform, AnUnknownRouteIsAUsageError) {
  Outcome outcome = run_xshade("", "info --gl-platform glx");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("--gl-platform"), std::string::npos) << outcome.output;
}

// Every verb that makes backends hands the route to them: with EGL pointing nowhere, each
// verb's gl backend fails through the EGL route, naming the library it could not open.
TEST(GlPlatform, EveryVerbThatMakesBackendsHandsTheRouteToThem) {
  // Per process: another build's tests may run at the same time.
  const auto scratch =
      std::filesystem::temp_directory_path() / ("xshade_gl_platform_verbs_" + std::to_string(getpid()));
  std::filesystem::remove_all(scratch);
  std::filesystem::create_directories(scratch / "golden");
  const std::string out = "'" + scratch.string() + "'";
  const std::vector<std::string> verbs = {
      "info --lane gl",
      "run toon_shadow_texture --lane gl --no-cache --report " + out + "/report",
      "bless toon_shadow_texture --lane gl --reason 'a test' --golden " + out + "/golden --cache " + out +
          "/cache --report " + out + "/bless",
      "eval '" XSHADE_SOURCE_DIR "/tests/conformance/shaders/rounding.hlsl' --lane gl -o " + out,
      "stability --lane gl --precision float",
      "accuracy --quick --lane gl --report " + out + "/accuracy",
  };
  for (const std::string& verb : verbs) {
    Outcome outcome = run_xshade("XSHADE_EGL_LIBRARY=/nonexistent/libEGL.so.1", verb + " --gl-platform egl");
    EXPECT_EQ(outcome.exit_code, 3) << verb << ": " << outcome.output;
    EXPECT_NE(outcome.output.find("cannot open EGL library '/nonexistent/libEGL.so.1'"), std::string::npos)
        << verb << ": " << outcome.output;
  }
  // Nothing was blessed.
  EXPECT_TRUE(std::filesystem::is_empty(scratch / "golden"));
  std::filesystem::remove_all(scratch);
}

}  // namespace
}  // namespace xshade::tests
