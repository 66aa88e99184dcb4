#include "harness/report/report_merge.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"
#include "harness/report/report_text.h"
#include "harness/report/results_json.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

LaneResult lane(const std::string& scene, const std::string& name, Verdict verdict) {
  LaneResult result;
  result.lane = name;
  result.verdict = verdict;
  result.image = scene + "/" + name + ".png";
  return result;
}

SceneResult scene(const std::string& name, std::vector<LaneResult> lanes, std::vector<CrossLaneResult> pairs = {}) {
  SceneResult result;
  result.scene = name;
  for (const LaneResult& each : lanes) result.verdict = worst(result.verdict, each.verdict);
  for (const CrossLaneResult& each : pairs) result.verdict = worst(result.verdict, each.verdict);
  result.lanes = std::move(lanes);
  result.cross_lane = std::move(pairs);
  return result;
}

class ReportMerge : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_merge_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // A report folder as a run leaves it: results.json, and a file (with `content`) for each image.
  fs::path report(const std::string& name, std::vector<SceneResult> scenes, double seconds = 1.0,
                  const std::string& content = "png") {
    RunResults results;
    results.started = "2026-01-0" + std::to_string(++reports_) + "T00:00:00Z";
    results.seconds = seconds;
    results.command = "xshade run " + name;
    results.scenes = std::move(scenes);
    const fs::path folder = root_ / name;
    fs::create_directories(folder);
    for (const SceneResult& each : results.scenes)
      for (const LaneResult& l : each.lanes) {
        fs::create_directories((folder / l.image).parent_path());
        std::ofstream(folder / l.image) << content;
      }
    std::ofstream(folder / "results.json") << results_json(results);
    return folder;
  }

  fs::path root_;
  int reports_ = 0;
};

// Three shards of disjoint scenes: one result of every scene, in name order, with counts that
// are the shards' counts added, and every image copied from its shard.
TEST_F(ReportMerge, ShardsAddUpToOneRunInNameOrder) {
  report("shards/1", {scene("c", {lane("c", "gl", Verdict::Pass), lane("c", "vk", Verdict::Fail)})}, 2.0);
  report("shards/2", {scene("a", {lane("a", "gl", Verdict::Pass)})}, 3.0);
  report("shards/3", {scene("b", {lane("b", "gl", Verdict::Pass)})}, 4.0);
  auto found = find_reports({root_ / "shards"});
  ASSERT_TRUE(found) << found.error().to_string();
  ASSERT_EQ(found->size(), 3u);
  const MergedReport merged = merge_reports(*found);
  ASSERT_EQ(merged.results.scenes.size(), 3u);
  EXPECT_EQ(merged.results.scenes[0].scene, "a");
  EXPECT_EQ(merged.results.scenes[2].scene, "c");
  EXPECT_EQ(merged.results.scenes[2].verdict, Verdict::Fail);
  const VerdictCounts checks = count_checks(merged.results);
  EXPECT_EQ(checks.pass, 3u);
  EXPECT_EQ(checks.fail, 1u);
  EXPECT_EQ(merged.results.seconds, 9.0);
  EXPECT_EQ(merged.results.started, "2026-01-01T00:00:00Z");
  ASSERT_EQ(merged.results.merged_from.size(), 3u);
  EXPECT_EQ(merged.results.merged_from[1].command, "xshade run shards/2");
  ASSERT_EQ(merged.files.size(), 4u);
  EXPECT_TRUE(merged.warnings.empty());
  for (const MergedFile& file : merged.files) EXPECT_TRUE(fs::exists(file.from)) << file.from;
}

// A CTest run checks each lane alone and then all lanes together: each lane is counted once, and
// where the two disagree the worse verdict is kept, with its own files.
TEST_F(ReportMerge, ALaneTwoReportsHoldIsCountedOnceWithItsWorstVerdict) {
  CrossLaneResult pair{"gl", "vk", Verdict::Fail, {}, {}, false};
  report("tests/s", {scene("s", {lane("s", "gl", Verdict::Pass), lane("s", "vk", Verdict::Pass)}, {pair})});
  report("tests/s.gl", {scene("s", {lane("s", "gl", Verdict::Crash)})});
  report("tests/s.vk", {scene("s", {lane("s", "vk", Verdict::Pass)})});
  auto found = find_reports({root_ / "tests"});
  ASSERT_TRUE(found) << found.error().to_string();
  const MergedReport merged = merge_reports(*found);
  ASSERT_EQ(merged.results.scenes.size(), 1u);
  const SceneResult& s = merged.results.scenes[0];
  ASSERT_EQ(s.lanes.size(), 2u);
  EXPECT_EQ(s.lanes[0].verdict, Verdict::Crash);
  EXPECT_EQ(s.lanes[1].verdict, Verdict::Pass);
  ASSERT_EQ(s.cross_lane.size(), 1u);
  EXPECT_EQ(s.verdict, Verdict::Crash);
  const VerdictCounts checks = count_checks(merged.results);
  EXPECT_EQ(checks.total(), 3u);  // two lanes and one pair
  // The crashed gl lane's image comes from the report that holds that result.
  bool from_gl_test = false;
  for (const MergedFile& file : merged.files)
    if (file.to == "s/gl.png") from_gl_test = file.from == root_ / "tests/s.gl" / "s/gl.png";
  EXPECT_TRUE(from_gl_test);
}

// results.json is data from a folder anyone can write: a path out of it is dropped, a missing
// file is said, and two different files that claim one path are kept apart.
TEST_F(ReportMerge, PathsAreHeldToTheirReportAndNeverOverwriteEachOther) {
  SceneResult escaping = scene("e", {lane("e", "gl", Verdict::Pass)});
  report("one", {scene("x", {lane("x", "gl", Verdict::Pass)})}, 1.0, "first");
  report("two", {scene("y", {lane("x", "gl", Verdict::Pass)})}, 1.0, "second");  // scene y names x/gl.png too
  const fs::path three = report("three", {escaping});
  // Written by hand after the fact: an image path that leads out, and one that is not there.
  RunResults hostile;
  hostile.command = "forged";
  SceneResult forged = scene("z", {lane("z", "gl", Verdict::Pass), lane("z", "vk", Verdict::Pass)});
  forged.lanes[0].image = "../one/x/gl.png";
  hostile.scenes = {forged};
  std::ofstream(three / "results.json") << results_json(hostile);

  auto found = find_reports({root_ / "one", root_ / "two", three});
  ASSERT_TRUE(found) << found.error().to_string();
  const MergedReport merged = merge_reports(*found);
  ASSERT_EQ(merged.warnings.size(), 2u);
  EXPECT_NE(merged.warnings[0].find("names ../one/x/gl.png, which leads out of"), std::string::npos)
      << merged.warnings[0];
  EXPECT_NE(merged.warnings[1].find("names z/vk.png, which is not there"), std::string::npos) << merged.warnings[1];
  ASSERT_EQ(merged.files.size(), 2u);
  EXPECT_EQ(merged.files[0].to, "x/gl.png");
  EXPECT_EQ(merged.files[1].to, "run-2/x/gl.png");
  EXPECT_EQ(merged.results.scenes[1].lanes[0].image, "run-2/x/gl.png");
  EXPECT_TRUE(merged.results.scenes[2].lanes[0].image.empty());
}

// CTest's lane tests, one run a lane: merged with --cross-lane, the lanes are held against each
// other as one run of them all would, from their float images, with the scene's tolerance.
TEST_F(ReportMerge, LanesFromSeparateRunsAreHeldAgainstEachOther) {
  FloatImage grey(4, 4), moved(4, 4);
  for (size_t i = 0; i < grey.rgba.size(); ++i) grey.rgba[i] = moved.rgba[i] = 0.5f;
  moved.rgba[5 * 4] = 0.9f;  // one pixel far off
  fs::create_directories(root_ / "merged/s");
  ASSERT_TRUE(write_exr(grey, root_ / "merged/s/gl.exr"));
  ASSERT_TRUE(write_exr(grey, root_ / "merged/s/vk.exr"));
  ASSERT_TRUE(write_exr(moved, root_ / "merged/s/vk-hlsl.exr"));
  RunResults results;
  results.scenes = {::xshade::harness::scene(
      "s", {lane("s", "vk-hlsl", Verdict::Pass), lane("s", "gl", Verdict::Pass), lane("s", "vk", Verdict::Pass)})};
  for (LaneResult& each : results.scenes[0].lanes) each.image_exr = "s/" + each.lane + ".exr";

  const std::vector<std::string> warnings = compare_lanes_across_reports(results, root_ / "merged");
  EXPECT_TRUE(warnings.empty());
  const SceneResult& out = results.scenes[0];
  ASSERT_EQ(out.cross_lane.size(), 2u);
  EXPECT_EQ(out.cross_lane[0].first_lane, "gl");  // gl against each other, in lane order, as a run
  EXPECT_EQ(out.cross_lane[0].second_lane, "vk");
  EXPECT_TRUE(out.cross_lane[0].identical);
  EXPECT_TRUE(out.cross_lane[0].diff.empty());
  EXPECT_EQ(out.cross_lane[1].second_lane, "vk-hlsl");
  EXPECT_EQ(out.cross_lane[1].verdict, Verdict::Fail);
  EXPECT_TRUE(fs::exists(root_ / "merged" / out.cross_lane[1].diff));
  EXPECT_EQ(out.verdict, Verdict::Fail);

  // A scene that a run of all its lanes compared already is left as it was.
  const std::vector<CrossLaneResult> before = results.scenes[0].cross_lane;
  compare_lanes_across_reports(results, root_ / "merged");
  EXPECT_EQ(results.scenes[0].cross_lane.size(), before.size());
}

// A lane that rendered but whose image is missing, damaged or not named once left a warning and
// one check fewer ("2 checks (2 pass)" where there were 3) and the merge passed: each check it
// misses is now an error, in lane order, and so is the scene. A lane that did not render has no
// checks to miss.
TEST_F(ReportMerge, ALaneImageThatCannotBeReadMakesEachCheckItMissesAnError) {
  FloatImage grey(4, 4);
  for (float& value : grey.rgba) value = 0.5f;
  fs::create_directories(root_ / "merged/s");
  ASSERT_TRUE(write_exr(grey, root_ / "merged/s/vk.exr"));
  ASSERT_TRUE(write_exr(grey, root_ / "merged/s/vk-hlsl.exr"));
  std::ofstream(root_ / "merged/s/gl.exr") << "truncated";
  RunResults results;
  results.scenes = {::xshade::harness::scene(
      "s", {lane("s", "gl", Verdict::Pass), lane("s", "vk", Verdict::Pass), lane("s", "vk-hlsl", Verdict::Pass)})};
  for (LaneResult& each : results.scenes[0].lanes) each.image_exr = "s/" + each.lane + ".exr";
  const std::vector<std::string> warnings = compare_lanes_across_reports(results, root_ / "merged");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("s on gl is not held against the other lanes"), std::string::npos) << warnings[0];
  const SceneResult& out = results.scenes[0];
  ASSERT_EQ(out.cross_lane.size(), 3u);
  EXPECT_EQ(out.cross_lane[0].first_lane + " " + out.cross_lane[0].second_lane, "gl vk");
  EXPECT_EQ(out.cross_lane[0].verdict, Verdict::Error);
  EXPECT_EQ(out.cross_lane[1].first_lane + " " + out.cross_lane[1].second_lane, "gl vk-hlsl");
  EXPECT_EQ(out.cross_lane[1].verdict, Verdict::Error);
  EXPECT_EQ(out.cross_lane[2].verdict, Verdict::Pass);
  EXPECT_EQ(out.verdict, Verdict::Error);

  // No image named for a lane that rendered is the same; a lane that crashed misses nothing.
  RunResults unnamed;
  unnamed.scenes = {::xshade::harness::scene(
      "s", {lane("s", "vk", Verdict::Pass), lane("s", "vk-hlsl", Verdict::Pass), lane("s", "gl", Verdict::Crash)})};
  unnamed.scenes[0].lanes[0].image_exr = "s/vk.exr";
  compare_lanes_across_reports(unnamed, root_ / "merged");
  ASSERT_EQ(unnamed.scenes[0].cross_lane.size(), 1u);
  EXPECT_EQ(unnamed.scenes[0].cross_lane[0].verdict, Verdict::Error);
}

TEST_F(ReportMerge, AFolderWithoutReportsOrABrokenResultsFileIsRefusedNamingIt) {
  fs::create_directories(root_ / "empty" / "inner");
  auto found = find_reports({root_ / "empty"});
  ASSERT_FALSE(found);
  EXPECT_NE(found.error().message.find((root_ / "empty").string() + " holds no results.json"), std::string::npos)
      << found.error().message;
  fs::create_directories(root_ / "broken");
  std::ofstream(root_ / "broken" / "results.json") << "{\"format\": \"xshade-results-1\"}";
  found = find_reports({root_ / "broken"});
  ASSERT_FALSE(found);
  EXPECT_NE(found.error().message.find((root_ / "broken" / "results.json").string() + ": not a results.json"),
            std::string::npos)
      << found.error().message;
  EXPECT_FALSE(find_reports({root_ / "missing"}));
}

}  // namespace
}  // namespace xshade::harness
