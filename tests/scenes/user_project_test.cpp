// xshade used from a user's own repository, through the real binary: a project file names the
// scenes, goldens and shaders; a material of the user's own includes xshade's library; paths
// that leave the folders they were given are refused before anything reads them.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

// A user material on the library's scene inputs: lit by the scene's light, nothing more.
constexpr const char* kMaterial = R"(#pragma vertex vert
#pragma fragment frag
#include "include/scene_inputs.hlsl"
float4 _Color = float4(0.8, 0.5, 0.2, 1.0);
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target {
  return _Color * saturate(dot(normalize(input.world_normal), _LightDirection.xyz));
}
)";

constexpr const char* kUserScene = R"(description = "one sphere in a user's own material"
size = [48, 48]
lanes = ["gl", "vk"]
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
material = "materials/user_lit.hlsl"
)";

class UserProject : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_user_project_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    for (const char* folder : {".git", "shaders/materials", "xshade/scenes", "src/deep"})
      fs::create_directories(root_ / folder);
    write("shaders/materials/user_lit.hlsl", kMaterial);
    write("xshade/scenes/user_sphere.toml", kUserScene);
    write("xshade.toml", "scenes = \"xshade/scenes\"\ngolden = \"xshade/golden\"\nshaders = [\"shaders\"]\n");
  }
  void TearDown() override { fs::remove_all(root_); }

  void write(const std::string& relative, const std::string& text) const {
    std::ofstream(root_ / relative, std::ios::binary | std::ios::trunc) << text;
  }
  // `xshade VERB ARGUMENTS` run in `folder` of the project, with a cache and a report of the test's own.
  Outcome xshade_in(const std::string& folder, const std::string& verb, const std::string& arguments = "") const {
    return run_xshade_in(root_ / folder, verb + " --cache '" + (root_ / "cache").string() + "' --report '" +
                                             (root_ / "report").string() + "' " + arguments);
  }
  Outcome bless() const { return xshade_in("", "bless", "user_sphere --reason 'the user material, inspected'"); }

  fs::path root_;
};

TEST_F(UserProject, TheProjectFileGivesTheFoldersFromAnywhereInTheRepository) {
  Outcome blessed = bless();
  ASSERT_EQ(blessed.exit_code, 0) << blessed.output;
  EXPECT_TRUE(fs::exists(root_ / "xshade/golden/user_sphere.png"));
  EXPECT_TRUE(fs::exists(root_ / "xshade/golden/MANIFEST.toml"));

  Outcome run = xshade_in("src/deep", "run");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("user_sphere on gl: pass"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("user_sphere on vk: pass"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("1 of 1 scenes passed"), std::string::npos) << run.output;
}

TEST_F(UserProject, TheUsersMaterialTakesThePlaceOfTheLibrarysOfTheSamePath) {
  // The library's toon has 4 keyword combinations; the user's file of the same path has 2.
  write("shaders/materials/toon.hlsl", std::string("#pragma multi_compile _ _USER_TOON\n") + kMaterial);
  std::string scene = kUserScene;
  scene.replace(scene.find("materials/user_lit.hlsl"), 23, "materials/toon.hlsl");
  write("xshade/scenes/user_sphere.toml", scene);
  Outcome plan = xshade_in("", "run", "--plan");
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("materials/toon.hlsl: 1 of its 2 keyword combinations"), std::string::npos) << plan.output;
}

TEST_F(UserProject, CommandLineFoldersOverrideTheProjectFile) {
  fs::create_directories(root_ / "other/scenes");
  write("other/scenes/second.toml", kUserScene);
  Outcome plan = xshade_in("", "run", "--plan --scenes '" + (root_ / "other/scenes").string() + "'");
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_NE(plan.output.find("plan for scene 'second'"), std::string::npos) << plan.output;
  EXPECT_EQ(plan.output.find("plan for scene 'user_sphere'"), std::string::npos) << plan.output;
}

TEST_F(UserProject, AProjectFolderThatLeavesTheProjectIsRefusedWithItsLocation) {
  write("xshade.toml", "scenes = \"xshade/scenes\"\ngolden = \"../../etc\"\n");
  Outcome run = xshade_in("src", "run");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find((root_ / "xshade.toml").string() + ":2:10: golden: expected a folder inside the project "
                                                               "file's folder"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("which leads out of it"), std::string::npos) << run.output;
}

TEST_F(UserProject, ASceneNameThatLeavesTheScenesFolderIsRefused) {
  fs::create_directories(root_ / "xshade/golden");  // else the missing golden folder is the first error
  Outcome run = xshade_in("", "run", "../../etc/passwd");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("'../../etc/passwd' is not a scene name"), std::string::npos) << run.output;
}

TEST_F(UserProject, AnIncludeThatLeavesTheShaderFoldersIsRefusedUnread) {
  write("shaders/materials/user_lit.hlsl", std::string("#include \"../../../../../../etc/passwd\"\n") + kMaterial);
  Outcome run = xshade_in("", "run", "--plan");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("user_lit.hlsl:1:10: error: include file '../../../../../../etc/passwd' is outside the "
                            "folders this shader was given"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("root:"), std::string::npos) << run.output;  // nothing of the file is shown
}

TEST_F(UserProject, AUsersScenesNeedTheUsersGoldens) {
  write("xshade.toml", "scenes = \"xshade/scenes\"\nshaders = [\"shaders\"]\n");
  Outcome run = xshade_in("", "run");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("are not xshade's own, so their goldens cannot be either: give --golden DIR or golden = "),
            std::string::npos)
      << run.output;
  Outcome blessed = bless();
  EXPECT_EQ(blessed.exit_code, 2) << blessed.output;
  EXPECT_FALSE(fs::exists(root_ / "xshade/golden"));
}

TEST_F(UserProject, ALaneTheSceneDoesNotListIsSkippedNotPassed) {
  ASSERT_EQ(bless().exit_code, 0);
  Outcome run = xshade_in("", "run", "--lane vk-hlsl");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("skipped: the scene runs on gl, vk, none of the lanes asked for"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("0 of 1 scenes passed"), std::string::npos) << run.output;
}

// A pragma xshade does not know is the front end's warning: run prints it at its place in the
// user's file and the report shows it, beside the render it did not stop.
TEST_F(UserProject, AnUnknownPragmaIsPrintedByRunAndShownInTheReport) {
  write("shaders/materials/user_lit.hlsl", std::string("#pragma frobnicate\n") + kMaterial);
  fs::create_directories(root_ / "xshade/golden");
  Outcome run = xshade_in("", "run", "--lane gl");
  EXPECT_EQ(run.exit_code, 1) << "no golden yet: " << run.output;
  const std::string warning = "materials/user_lit.hlsl:1:9: warning: unknown pragma 'frobnicate'";
  EXPECT_NE(run.output.find("user_sphere: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find(warning), std::string::npos) << run.output;
  EXPECT_NE(read_text(root_ / "report" / "user_sphere.html").find("unknown pragma &#39;frobnicate&#39;"),
            std::string::npos);
}

}  // namespace
}  // namespace xshade::tests
