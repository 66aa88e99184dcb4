// The gate end to end, through the real `xshade run` on copies of a fixed scene, its golden and
// the shader library in a temporary folder: what a user sees when a shader changes, a golden is
// missing or corrupt, or a scene file is broken.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

// The smallest fixed scene (256 x 256), on the gl lane alone: enough to exercise the gate.

class Gating : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_gating_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    copy_fixed_scene(kSource, root_, kCopiedScene);
  }
  void TearDown() override { fs::remove_all(root_); }

  Outcome run() {
    return run_xshade("", "run --lane gl --no-cache --scenes '" + (root_ / "scenes").string() + "' --golden '" +
                              (root_ / "golden").string() + "' --shaders '" + (root_ / "shaders").string() +
                              "' --report '" + (root_ / "report").string() + "'");
  }

  fs::path root_;
};

TEST_F(Gating, AnUnchangedSceneMatchesItsGolden) {
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_TRUE(fs::exists(root_ / "report/index.html"));
  EXPECT_TRUE(fs::exists(root_ / "report/junit.xml"));
  EXPECT_TRUE(fs::exists(root_ / "report/results.json"));
}

TEST_F(Gating, AVisiblyChangedShaderFailsWithItsDiffInTheReport) {
  const fs::path toon = root_ / "shaders/materials/toon.hlsl";
  std::string text = read_text(toon);
  const std::string output = "return fixed4(diffuse + specular + rim, albedo.a);";
  ASSERT_NE(text.find(output), std::string::npos);
  text.replace(text.find(output), output.size(), "return fixed4((diffuse + specular + rim) * 0.9, albedo.a);");
  std::ofstream(toon, std::ios::binary | std::ios::trunc) << text;

  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("per_pixel"), std::string::npos) << outcome.output;
  // How to accept the new image, on the console and the page.
  const std::string bless = "xshade bless " + std::string(kCopiedScene) + " --reason";
  EXPECT_NE(outcome.output.find(bless), std::string::npos) << outcome.output;
  EXPECT_TRUE(fs::exists(root_ / "report" / kCopiedScene / "gl.diff.png"));
  const std::string page = read_text(root_ / "report" / (std::string(kCopiedScene) + ".html"));
  EXPECT_NE(page.find("gl.diff.png"), std::string::npos);
  EXPECT_NE(page.find(bless), std::string::npos);
}

// A scene that chose a perceptual metric is decided by it: a shader change the per-pixel layer
// fails passes within the metric's threshold, and fails beyond it with the metric's line; the
// metric's figures are in results.json.
TEST_F(Gating, AScenesMetricDecidesItsGoldenComparison) {
  const fs::path toon = root_ / "shaders/materials/toon.hlsl";
  replace_in_file(toon, "return fixed4(diffuse + specular + rim, albedo.a);",
                  "return fixed4((diffuse + specular + rim) * 0.97, albedo.a);");
  const fs::path scene = root_ / "scenes" / (std::string(kCopiedScene) + ".toml");
  const std::string text = read_text(scene);
  std::ofstream(scene, std::ios::binary | std::ios::trunc)
      << text << "\n[compare]\nmetric = \"flip\"\nmetric_threshold = 0.05\nreason = \"3% darker is within it\"\n";
  Outcome loose = run();
  EXPECT_EQ(loose.exit_code, 0) << loose.output;
  const nlohmann::json results = nlohmann::json::parse(read_text(root_ / "report/results.json"));
  const nlohmann::json& golden = results["scenes"][0]["lanes"][0]["against_golden"];
  ASSERT_TRUE(golden["metric"].is_object()) << golden.dump();
  EXPECT_EQ(golden["metric"]["name"], "flip");
  EXPECT_GT(golden["metric"]["value"].get<double>(), 0.0);
  EXPECT_LT(golden["metric"]["value"].get<double>(), 0.05);
  EXPECT_EQ(results["scenes"][0]["compare"]["metric"]["name"], "flip");
  std::map<std::string, std::string> verdicts;  // the golden comparison's layers, as the lane reports them
  for (const nlohmann::json& layer : results["scenes"][0]["lanes"][0]["layers"])
    verdicts[layer["layer"].get<std::string>()] = layer["verdict"].get<std::string>();
  EXPECT_EQ(verdicts["per_pixel"], "fail");  // what decided without the metric
  EXPECT_EQ(verdicts["flip"], "pass");

  replace_in_file(scene, "metric_threshold = 0.05", "metric_threshold = 0.00001");
  Outcome strict = run();
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_NE(strict.output.find("FLIP mean"), std::string::npos) << strict.output;
}

TEST_F(Gating, AMissingGoldenFailsWithTheBlessCommand) {
  fs::remove_all(root_ / "golden");  // no golden yet: no image, no float image, no manifest
  fs::create_directories(root_ / "golden");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("xshade bless toon_shadow_texture --reason \"...\""), std::string::npos)
      << outcome.output;
}

TEST_F(Gating, ACorruptGoldenIsBadInputNamingTheFile) {
  std::ofstream(root_ / "golden" / (std::string(kCopiedScene) + ".png"), std::ios::trunc) << "not a png";
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find((root_ / "golden" / (std::string(kCopiedScene) + ".png")).string()), std::string::npos)
      << outcome.output;
}

TEST_F(Gating, AMalformedSceneIsBadInputWhileTheOtherScenesRun) {
  std::ofstream(root_ / "scenes/broken.toml") << "description = \"broken\"\nsize = [64, 64\n";
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("broken.toml:2:"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("toon_shadow_texture on gl: pass"), std::string::npos) << outcome.output;
  EXPECT_TRUE(fs::exists(root_ / "report" / kCopiedScene / "gl.png"));
}

// A second run with the cache the first one filled compiles nothing.
TEST_F(Gating, ASecondRunWithAWarmCacheCompilesNothing) {
  const std::string arguments = "run --plan --lane gl --cache '" + (root_ / "cache").string() + "' --scenes '" +
                                (root_ / "scenes").string() + "' --shaders '" + (root_ / "shaders").string() + "'";
  const std::string render = "run --lane gl --cache '" + (root_ / "cache").string() + "' --scenes '" +
                             (root_ / "scenes").string() + "' --golden '" + (root_ / "golden").string() +
                             "' --shaders '" + (root_ / "shaders").string() + "' --report '" +
                             (root_ / "report").string() + "'";
  Outcome cold = run_xshade("", render);
  ASSERT_EQ(cold.exit_code, 0) << cold.output;
  EXPECT_EQ(cold.output.find("shaders: 0 compiled"), std::string::npos) << cold.output;
  Outcome warm = run_xshade("", render);
  ASSERT_EQ(warm.exit_code, 0) << warm.output;
  EXPECT_NE(warm.output.find("shaders: 0 compiled"), std::string::npos) << warm.output;
  Outcome plan = run_xshade("", arguments);
  EXPECT_NE(plan.output.find("(in the cache)"), std::string::npos) << plan.output;
  EXPECT_EQ(plan.output.find("(to compile)"), std::string::npos) << plan.output;
}

// Half emulation runs on the GLSL lanes; vk-hlsl is skipped, and the fp32 golden is not compared.
TEST_F(Gating, HalfEmulationRunsTheGlslLanesAndSkipsVkHlsl) {
  Outcome outcome =
      run_xshade("", "run --precision half --lane gl --lane vk-hlsl --no-cache --scenes '" +
                         (root_ / "scenes").string() + "' --golden '" + (root_ / "golden").string() + "' --shaders '" +
                         (root_ / "shaders").string() + "' --report '" + (root_ / "report").string() + "'");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("toon_shadow_texture on gl: pass"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("toon_shadow_texture on vk-hlsl: skipped"), std::string::npos) << outcome.output;
}

TEST_F(Gating, BlessRefusesWithoutAReasonAndWritesNothing) {
  fs::remove_all(root_ / "golden");  // no golden yet: no image, no float image, no manifest
  fs::create_directories(root_ / "golden");
  Outcome outcome =
      run_xshade("", std::string("bless ") + kCopiedScene + " --reason ' ' --scenes '" + (root_ / "scenes").string() +
                         "' --golden '" + (root_ / "golden").string() + "'");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("say why with --reason"), std::string::npos) << outcome.output;
  // Refused before anything renders: the command line is checked first, not only the store.
  EXPECT_EQ(outcome.output.find(std::string(kCopiedScene) + " on "), std::string::npos) << outcome.output;
  EXPECT_TRUE(fs::is_empty(root_ / "golden"));
}

// Shards split the fixed scenes between CI jobs: together they cover each scene exactly once.
TEST(Sharding, ShardsCoverEverySceneOnce) {
  std::vector<std::string> scenes;
  for (const auto& entry : fs::directory_iterator(kSource / "scenes"))
    if (entry.path().extension() == ".toml") scenes.push_back(entry.path().stem().string());
  std::map<std::string, int> seen;
  for (int shard = 1; shard <= 3; ++shard) {
    Outcome outcome = run_xshade("", "run --plan --no-cache --shard " + std::to_string(shard) + "/3");
    ASSERT_EQ(outcome.exit_code, 0) << outcome.output;
    for (const std::string& scene : scenes)
      if (outcome.output.find("plan for scene '" + scene + "'") != std::string::npos) ++seen[scene];
  }
  for (const std::string& scene : scenes) EXPECT_EQ(seen[scene], 1) << scene;
  EXPECT_EQ(run_xshade("", "run --plan --shard 4/3").exit_code, 2);
}

}  // namespace
}  // namespace xshade::tests
