// Mesa's on-disk shader cache, through the real binary: runs keep it in xshade's cache folder
// (never the user's), and a driver's compile warning fails the run on a warm cache as on a cold
// one, although Mesa then compiles nothing.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

// Reads a variable it never wrote: Mesa's GLSL compiler warns "`unset' used uninitialized".
constexpr const char* kWarningMaterial = R"(#pragma vertex vert
#pragma fragment frag
#include "include/scene_inputs.hlsl"
float4 _Color = float4(0.8, 0.5, 0.2, 1.0);
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target {
  float unset;
  return _Color * saturate(dot(normalize(input.world_normal), _LightDirection.xyz)) + 0.0 * unset;
}
)";

constexpr const char* kWarnedScene = R"(description = "a material whose GLSL the driver warns about"
size = [32, 32]
lanes = ["gl"]
[camera]
position = [0, 0, 4]
target = [0, 0, 0]
fov_y = 40
near = 0.5
far = 20
[[light]]
type = "directional"
direction = [0.3, 0.6, 0.7]
[[object]]
mesh = "sphere"
material = "materials/warns.hlsl"
)";

constexpr const char* kWarning =
    "warns.hlsl': OpenGL shader compiler other (severity high, id 1): 0:8(100): warning: "
    "`unset' used uninitialized";

class DriverCache : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_driver_cache_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    for (const char* folder : {"shaders/materials", "scenes", "golden"}) fs::create_directories(root_ / folder);
    std::ofstream(root_ / "shaders/materials/warns.hlsl") << kWarningMaterial;
    std::ofstream(root_ / "scenes/warn.toml") << kWarnedScene;
  }
  void TearDown() override { fs::remove_all(root_); }

  Outcome run() {
    return run_xshade("", "run --no-project --scenes '" + (root_ / "scenes").string() + "' --golden '" +
                              (root_ / "golden").string() + "' --shaders '" + (root_ / "shaders").string() +
                              "' --cache '" + (root_ / "cache").string() + "' --report '" +
                              (root_ / "report").string() + "'");
  }
  // xshade's folder for the drivers' cache: one per build of xshade, inside its own cache.
  fs::path driver_cache() const {
    for (const auto& entry : fs::directory_iterator(root_ / "cache"))
      if (entry.is_directory() && entry.path().filename().string().starts_with("driver-")) return entry.path();
    return {};
  }

  fs::path root_;
};

TEST_F(DriverCache, AWarningFailsTheRunOnAColdCacheAndOnAWarmOne) {
  Outcome cold = run();
  EXPECT_EQ(cold.exit_code, 1) << cold.output;
  EXPECT_NE(cold.output.find("warn on gl: fail - driver: program '"), std::string::npos) << cold.output;
  EXPECT_NE(cold.output.find(kWarning), std::string::npos) << cold.output;
  const fs::path drivers = driver_cache();
  ASSERT_FALSE(drivers.empty()) << "no driver-* folder in " << (root_ / "cache");
  ASSERT_TRUE(fs::is_directory(drivers / "mesa_shader_cache")) << "Mesa kept nothing in xshade's folder";

  Outcome warm = run();
  EXPECT_EQ(warm.exit_code, 1) << warm.output;
  EXPECT_NE(warm.output.find(kWarning), std::string::npos) << warm.output;

  // What carried it: without the messages kept beside Mesa's cache, the warm run would not see it,
  // for Mesa compiled nothing.
  fs::remove_all(drivers / "compile_messages");
  Outcome forgotten = run();
  EXPECT_EQ(forgotten.output.find("used uninitialized"), std::string::npos) << forgotten.output;
}

// An entry of Mesa's cache damaged between runs was read, failed Mesa's own check, compiled again
// and never replaced: right images, every later run slower than a cold one, and nothing said.
// Now the run says so once, sets the folder aside, and the drivers build it again.
TEST_F(DriverCache, AnEntryDamagedBetweenRunsSetsTheFolderAsideOnceWithAWarning) {
  run();
  const fs::path drivers = driver_cache();
  ASSERT_FALSE(drivers.empty()) << "no driver-* folder in " << (root_ / "cache");
  fs::path entry;
  for (const auto& file : fs::recursive_directory_iterator(drivers / "mesa_shader_cache"))
    if (file.is_regular_file() && file.path().filename() != "index") entry = file.path();
  ASSERT_FALSE(entry.empty()) << "Mesa kept no entry";
  std::string bytes = read_text(entry);
  bytes.back() = char(bytes.back() ^ 0x5a);
  std::ofstream(entry, std::ios::binary) << bytes;

  Outcome damaged = run();
  EXPECT_NE(damaged.output.find("warning: the drivers' shader cache in " + drivers.string() +
                                " had 1 entry changed "
                                "since xshade saw them written (" +
                                fs::relative(entry, drivers).string() + "): it is set aside and built again"),
            std::string::npos)
      << damaged.output;
  EXPECT_TRUE(fs::is_directory(drivers / "mesa_shader_cache")) << "built again";
  EXPECT_NE(read_text(entry), bytes) << "the damaged entry is gone";
  Outcome after = run();
  EXPECT_EQ(after.output.find("drivers' shader cache"), std::string::npos) << after.output;
}

}  // namespace
}  // namespace xshade::tests
