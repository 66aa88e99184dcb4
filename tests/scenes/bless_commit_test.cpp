// bless's commit through the real binary: killed after each step of its commit it leaves the
// old golden or the new one, which the next run finishes and passes against; two blesses into
// one folder at once keep both entries; a bless that finds the folder locked waits and says so.
// The scene is a fixed one shrunk to a few pixels and blessed on the gl lane alone, so that each
// bless costs little more than starting xshade.
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

// Every file under `folder` with its contents: what "exactly this state" means. The date bless
// records is left out, as two blesses of one image differ in it and nothing else.
using Snapshot = std::map<std::string, std::string>;
Snapshot snapshot(const fs::path& folder) {
  Snapshot files;
  for (const auto& item : fs::recursive_directory_iterator(folder)) {
    if (!item.is_regular_file()) continue;
    std::string text = read_text(item.path());
    if (item.path().filename() == "MANIFEST.toml")
      for (size_t at = text.find("\ndate = "); at != std::string::npos; at = text.find("\ndate = ", at + 1))
        text.erase(at + 1, text.find('\n', at + 1) - at);
    files[fs::relative(item.path(), folder).string()] = text;
  }
  return files;
}

void restore(const fs::path& folder, const std::map<std::string, std::string>& raw) {
  fs::remove_all(folder);
  for (const auto& [name, bytes] : raw) {
    fs::create_directories((folder / name).parent_path());
    std::ofstream(folder / name, std::ios::binary) << bytes;
  }
}

std::map<std::string, std::string> raw_files(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& item : fs::recursive_directory_iterator(folder))
    if (item.is_regular_file()) files[fs::relative(item.path(), folder).string()] = read_text(item.path());
  return files;
}

class BlessCommit : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_bless_commit_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    copy_fixed_scene(kSource, root_, kCopiedScene);
    fs::remove_all(root_ / "golden");
    fs::create_directories(root_ / "golden");
    const std::string text = read_text(root_ / "scenes" / (std::string(kCopiedScene) + ".toml"));
    const std::string size = "size = [256, 256]";
    ASSERT_NE(text.find(size), std::string::npos);
    tiny_ = text;
    tiny_.replace(tiny_.find(size), size.size(), "size = [24, 24]");
    fs::remove(root_ / "scenes" / (std::string(kCopiedScene) + ".toml"));
  }
  void TearDown() override { fs::remove_all(root_); }

  // Writes the scene `name` as the tiny scene with `from` replaced by `to`.
  void scene(const std::string& name, const std::string& from = "", const std::string& to = "") {
    std::string text = tiny_;
    if (!from.empty()) {
      ASSERT_NE(text.find(from), std::string::npos) << from;
      text.replace(text.find(from), from.size(), to);
    }
    std::ofstream(root_ / "scenes" / (name + ".toml"), std::ios::binary | std::ios::trunc) << text;
  }
  std::string folders(const std::string& report) const {
    return " --lane gl" + copied_scene_options(root_) + " --report '" + (root_ / report).string() + "'";
  }
  std::string bless_arguments(const std::string& scene_name, const std::string& reason) const {
    return "bless " + scene_name + " --reason '" + reason + "'" + folders("bless_" + scene_name);
  }
  Outcome bless(const std::string& scene_name, const std::string& reason, const std::string& environment = "") {
    return run_xshade("XSHADE_BLESSED_BY=test " + environment, bless_arguments(scene_name, reason));
  }
  Outcome run(const std::string& scenes) { return run_xshade("", "run " + scenes + folders("report")); }
  // scenes/NAME.toml: one sphere of `material`, 8 x 8 pixels, on every lane.
  void one_sphere_scene(const std::string& name, const std::string& material) const {
    std::ofstream(root_ / "scenes" / (name + ".toml")) << "description = \"one sphere\"\nsize = [8, 8]\n"
                                                          "[camera]\nposition = [0, 0, 4]\ntarget = [0, 0, 0]\n"
                                                          "fov_y = 40\nnear = 0.5\nfar = 20\n"
                                                          "[[object]]\nmesh = \"sphere\"\nmaterial = \""
                                                       << material << "\"\n";
  }

  fs::path root_;
  std::string tiny_;
};

// The old golden has a float image (a highlight above 1), the new one has none and another
// colour: every step changes something a kill could leave half done.
TEST_F(BlessCommit, AKillAfterAnyStepLeavesTheOldGoldenOrTheNewOneAndTheNextRunFinishesIt) {
  const fs::path golden = root_ / "golden";
  const std::string intensity = "intensity = 1.5";
  const auto old_scene = [&] { scene(kCopiedScene); };
  const auto new_scene = [&] { scene(kCopiedScene, intensity, "intensity = 0.5"); };

  old_scene();
  Outcome first = bless(kCopiedScene, "old");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  ASSERT_TRUE(fs::exists(golden / "gl" / (std::string(kCopiedScene) + ".exr"))) << "the old golden needs a float image";
  const auto old_files = raw_files(golden);
  const Snapshot old_state = snapshot(golden);
  new_scene();
  Outcome second = bless(kCopiedScene, "new");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  ASSERT_FALSE(fs::exists(golden / "gl" / (std::string(kCopiedScene) + ".exr"))) << "the new golden has no float image";
  const Snapshot new_state = snapshot(golden);
  ASSERT_NE(old_state, new_state);

  bool saw_old = false, saw_new = false;
  int step = 1;
  for (;; ++step) {
    ASSERT_LT(step, 20) << "bless never finished";
    restore(golden, old_files);
    new_scene();
    Outcome killed = bless(kCopiedScene, "new", "XSHADE_TEST_ABORT_AFTER_BLESS_STEP=" + std::to_string(step));
    if (killed.exit_code == 0) break;                                            // past the last step
    ASSERT_NE(killed.exit_code, 2) << "step " << step << ": " << killed.output;  // killed, not refused
    ASSERT_NE(killed.exit_code, 1) << "step " << step << ": " << killed.output;

    // The manifest alone decides which state it is; the next run makes the files agree with it.
    const std::string manifest = snapshot(golden).at("MANIFEST.toml");
    const bool is_new = manifest == new_state.at("MANIFEST.toml");
    ASSERT_TRUE(is_new || manifest == old_state.at("MANIFEST.toml")) << "step " << step << ": " << manifest;
    (is_new ? saw_new : saw_old) = true;
    if (is_new)
      new_scene();
    else
      old_scene();
    Outcome next = run(kCopiedScene);
    EXPECT_EQ(next.exit_code, 0) << "step " << step << " (" << (is_new ? "new" : "old") << "): " << next.output;
    EXPECT_EQ(snapshot(golden), is_new ? new_state : old_state) << "step " << step;
  }
  EXPECT_GE(step, 7) << "bless has at least six steps to be killed after";
  EXPECT_TRUE(saw_old);
  EXPECT_TRUE(saw_new);
  // The bless that finished left exactly the new state.
  EXPECT_EQ(snapshot(golden), new_state);
}

// Two blesses of different scenes into one folder at once: each reads the manifest, adds its
// entry and writes it back; without the lock one of the two entries is lost. Each holds the
// manifest for 2 s between reading and writing it (far longer than the two renders differ by), so
// that they always overlap there: the second must wait for the first and say so.
// A golden whose image was truncated or deleted (its manifest entry intact) once could not be
// blessed again ("only `xshade bless` may change a golden", exit 2): bless now says what it
// cannot use and writes the golden again, after which a run passes.
TEST_F(BlessCommit, BlessRepairsADamagedOrMissingGolden) {
  scene("s");
  ASSERT_EQ(bless("s", "first").exit_code, 0);
  const fs::path png = root_ / "golden" / "gl" / "s.png";  // one lane blessed: its own golden
  ASSERT_TRUE(fs::exists(png));
  for (const bool truncate : {true, false}) {
    if (truncate)
      std::ofstream(png, std::ios::binary | std::ios::trunc) << read_text(png).substr(0, 40);
    else
      fs::remove(png);
    EXPECT_NE(run("s").exit_code, 0) << "a damaged golden is never a pass";
    Outcome repaired = bless("s", "repaired");
    EXPECT_EQ(repaired.exit_code, 0) << repaired.output;
    EXPECT_NE(repaired.output.find("xshade bless: the golden it replaces cannot be used: "), std::string::npos)
        << repaired.output;
    Outcome after = run("s");
    EXPECT_EQ(after.exit_code, 0) << after.output;
  }
}

// Lanes that disagree fail the run even where each lane passes against a golden of its own:
// a material whose fmod of a negative number takes glslang's sign on vk-hlsl (a listed
// divergence, docs/divergences.md), each lane blessed on its own, then a run of all three.
TEST_F(BlessCommit, LanesThatDisagreeFailTheRunThoughEachPassesItsOwnGolden) {
  fs::create_directories(root_ / "shaders" / "materials");
  std::ofstream(root_ / "shaders" / "materials" / "fmod_sign.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#include "include/scene_inputs.hlsl"
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target { return float4(abs(fmod(-1.5 + 0.0 * input.uv.x, 2.0)) / 2.0, 0, 0, 1); }
)";
  one_sphere_scene("fmod", "materials/fmod_sign.hlsl");
  const std::string options = copied_scene_options(root_) + " --report '" + (root_ / "report").string() + "'";
  for (const char* lane : {"gl", "vk", "vk-hlsl"}) {
    Outcome blessed = run_xshade("XSHADE_BLESSED_BY=test", std::string("bless fmod --lane ") + lane +
                                                               " --reason 'this lane on its own'" + options);
    ASSERT_EQ(blessed.exit_code, 0) << blessed.output;
  }
  Outcome outcome = run_xshade("", "run fmod" + options);
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("fmod on vk-hlsl: pass"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("fmod: gl vs vk-hlsl: fail"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("0 of 1 scenes passed"), std::string::npos) << outcome.output;
}

// A float golden (values above 1, which the PNG clamps) edited after bless is refused, naming
// the bless to run, never believed: the run is an error, not a pass against the edited values.
TEST_F(BlessCommit, AnEditedFloatGoldenIsRefused) {
  fs::create_directories(root_ / "shaders" / "materials");
  std::ofstream(root_ / "shaders" / "materials" / "bright.hlsl") << R"(#pragma vertex vert
#pragma fragment frag
#include "include/scene_inputs.hlsl"
SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }
float4 frag(SurfaceVaryings input) : SV_Target { return float4(2.0, 0.5, 0.25, 1.0); }
)";
  one_sphere_scene("bright", "materials/bright.hlsl");
  ASSERT_EQ(bless("bright", "above one").exit_code, 0);
  fs::path exr;
  for (const auto& item : fs::recursive_directory_iterator(root_ / "golden"))
    if (item.path().filename() == "bright.exr") exr = item.path();
  ASSERT_FALSE(exr.empty()) << "bless wrote no float image";
  std::string bytes = read_text(exr);
  bytes.back() = char(bytes.back() ^ 1);
  std::ofstream(exr, std::ios::binary | std::ios::trunc) << bytes;
  Outcome outcome = run("bright");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(exr.string() + " is not the image blessed on"), std::string::npos) << outcome.output;
}

TEST_F(BlessCommit, TwoBlessesAtOnceKeepBothEntries) {
  scene("toon_a");
  scene("toon_b", "_Color = [0.3, 0.6, 0.9, 1]", "_Color = [0.9, 0.3, 0.3, 1]");
  const fs::path golden = root_ / "golden";
  const std::string environment = "XSHADE_BLESSED_BY=test XSHADE_TEST_BLESS_HOLDS_MANIFEST_MS=2000";
  // Both started before either is waited for.
  FILE* first = popen(xshade_command(environment, bless_arguments("toon_a", "a")).c_str(), "r");
  FILE* second = popen(xshade_command(environment, bless_arguments("toon_b", "b")).c_str(), "r");
  ASSERT_TRUE(first && second);
  std::string output;
  char buffer[4096];
  for (FILE* pipe : {first, second})
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  const int status_a = pclose(first), status_b = pclose(second);
  ASSERT_EQ(status_a, 0) << output;
  ASSERT_EQ(status_b, 0) << output;
  EXPECT_NE(output.find("waiting for another xshade"), std::string::npos) << output;
  const std::string manifest = read_text(golden / "MANIFEST.toml");
  EXPECT_NE(manifest.find("scene = \"toon_a\""), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("scene = \"toon_b\""), std::string::npos) << manifest;
  // Both goldens pass with their hashes checked.
  Outcome checked = run("toon_a toon_b");
  EXPECT_EQ(checked.exit_code, 0) << checked.output;
}

// The folder's lock held by someone else: bless says it waits, and finishes once it is free.
TEST_F(BlessCommit, ABlessThatFindsTheFolderLockedWaitsAndSaysSo) {
  scene(kCopiedScene);
  // Close-on-exec: a copy inherited by bless would hold the lock for it after the test lets go.
  const int lock = ::open((root_ / "golden" / ".golden.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  ASSERT_GE(lock, 0);
  ASSERT_EQ(::flock(lock, LOCK_EX), 0);
  const std::string command = xshade_command("XSHADE_BLESSED_BY=test", bless_arguments(kCopiedScene, "first"));
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_TRUE(pipe);
  std::string output;
  char buffer[4096];
  // Read until bless says it waits (or gives up after a minute, or ends without waiting).
  pollfd ready{fileno(pipe), POLLIN, 0};
  while (output.find("waiting for another xshade") == std::string::npos && ::poll(&ready, 1, 60000) > 0) {
    const ssize_t n = ::read(fileno(pipe), buffer, sizeof buffer);
    if (n <= 0) break;
    output.append(buffer, size_t(n));
  }
  EXPECT_NE(output.find("xshade bless: waiting for another xshade to finish writing " + (root_ / "golden").string() +
                        " (it holds " + (root_ / "golden" / ".golden.lock").string() + ")"),
            std::string::npos)
      << output;
  EXPECT_FALSE(fs::exists(root_ / "golden" / "MANIFEST.toml"));  // nothing written while it waits
  ::close(lock);
  ssize_t n = 0;
  while ((n = ::read(fileno(pipe), buffer, sizeof buffer)) > 0) output.append(buffer, size_t(n));
  EXPECT_EQ(pclose(pipe), 0) << output;
  EXPECT_NE(read_text(root_ / "golden" / "MANIFEST.toml").find("reason = \"first\""), std::string::npos) << output;
}

}  // namespace
}  // namespace xshade::tests
