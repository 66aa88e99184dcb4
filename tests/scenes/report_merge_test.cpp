// One report of several runs, through the real binary: three fixed scenes (one changed so that it
// fails against its golden) run once unsharded and once as three shards whose reports
// `xshade report merge` joins. The merged report must hold what the unsharded run holds: the
// same counts, the same verdict for every scene, lane and pair of lanes, and every image it names.
#include <filesystem>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Every verdict a results.json holds, by scene, by scene and lane, and by scene and pair.
std::map<std::string, std::string> verdicts(const json& results) {
  std::map<std::string, std::string> out;
  for (const json& scene : results.at("scenes")) {
    const std::string name = scene.at("scene");
    out[name] = scene.at("verdict");
    for (const json& lane : scene.at("lanes"))
      out[name + "/" + lane.at("lane").get<std::string>()] = lane.at("verdict");
    for (const json& pair : scene.at("cross_lane"))
      out[name + "/" + pair.at("first_lane").get<std::string>() + "~" + pair.at("second_lane").get<std::string>()] =
          pair.at("verdict");
  }
  return out;
}

TEST(ReportMergeThroughTheBinary, ThreeShardsMergedAreTheUnshardedRun) {
  const fs::path root = fs::temp_directory_path() / "xshade_report_merge_shards";
  fs::remove_all(root);
  fs::create_directories(root / "scenes");
  fs::copy(kSource / "golden", root / "golden", fs::copy_options::recursive);
  for (const char* scene : {"toon_shadow_texture", "white_furnace", "toon_vs_standard"})
    fs::copy_file(kSource / "scenes" / (std::string(scene) + ".toml"),
                  root / "scenes" / (std::string(scene) + ".toml"));
  replace_in_file(root / "scenes/toon_shadow_texture.toml", "_Color = [0.3, 0.6, 0.9, 1]",
                  "_Color = [0.3, 0.62, 0.9, 1]");
  const std::string folders = " --no-project --scenes '" + (root / "scenes").string() + "' --golden '" +
                              (root / "golden").string() + "' --cache '" + (root / "cache").string() + "'";

  Outcome whole = run_xshade("", "run --report '" + (root / "whole").string() + "'" + folders);
  ASSERT_EQ(whole.exit_code, 1) << whole.output;  // the changed scene fails
  for (int shard = 1; shard <= 3; ++shard) {
    Outcome part = run_xshade("", "run --shard " + std::to_string(shard) + "/3 --report '" +
                                      (root / "shards" / std::to_string(shard)).string() + "'" + folders);
    ASSERT_NE(part.exit_code, 2) << part.output;
  }
  Outcome merged =
      run_xshade("", "report merge '" + (root / "shards").string() + "' --out '" + (root / "merged").string() + "'");
  ASSERT_EQ(merged.exit_code, 0) << merged.output;  // written; without --exit-code the verdict is not the exit
  EXPECT_NE(merged.output.find("merged 3 reports: 3 scenes (2 pass, 1 fail, 0 error, 0 crash, 0 skipped)"),
            std::string::npos)
      << merged.output;
  Outcome gated = run_xshade("", "report merge '" + (root / "shards").string() + "' --out '" +
                                     (root / "merged_gate").string() + "' --exit-code");
  EXPECT_EQ(gated.exit_code, 1) << gated.output;

  const json one = json::parse(read_text(root / "whole" / "results.json"));
  const json all = json::parse(read_text(root / "merged" / "results.json"));
  EXPECT_EQ(all.at("scene_counts"), one.at("scene_counts"));
  EXPECT_EQ(all.at("check_counts"), one.at("check_counts"));
  EXPECT_EQ(all.at("verdict"), one.at("verdict"));
  EXPECT_EQ(verdicts(all), verdicts(one));
  EXPECT_EQ(all.at("merged_from").size(), 3u);
  // Every image the merged report names is in it, and every page it links.
  for (const json& scene : all.at("scenes")) {
    for (const json& lane : scene.at("lanes")) {
      for (const char* field : {"image", "image_exr", "golden", "golden_exr", "diff"}) {
        const std::string path = lane.at(field);
        if (!path.empty()) {
          EXPECT_TRUE(fs::is_regular_file(root / "merged" / path)) << path;
        }
      }
    }
    EXPECT_TRUE(fs::is_regular_file(root / "merged" / (scene.at("scene").get<std::string>() + ".html")));
  }
  const std::string index = read_text(root / "merged" / "index.html");
  EXPECT_NE(index.find("merged from</dt><dd>3 runs"), std::string::npos);
  fs::remove_all(root);
}

}  // namespace
}  // namespace xshade::tests
