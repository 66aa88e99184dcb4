// Renders in worker processes, through the real `xshade`: a render that hangs is stopped at its
// time limit and reported as that scene's failure while the other scenes pass; a worker that dies
// by a signal is reported with the signal and where it was; and the images and verdicts do not
// depend on how many workers run at once.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"
#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

class Workers : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_workers_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    copy_fixed_scene(kSource, root_, kCopiedScene);
  }
  void TearDown() override { fs::remove_all(root_); }

  // A second scene, `slow`, like the fixed one but with a material whose every pixel runs two
  // nested loops of 50,000 steps (each under llvmpipe's own limit of 65,535 iterations a loop):
  // hours of work, which only a time limit ends.
  void add_slow_scene() {
    std::string shader = read_text(root_ / "shaders/materials/toon.hlsl");
    const std::string end = "  return fixed4(diffuse + specular + rim, albedo.a);";
    const size_t at = shader.find(end);
    ASSERT_NE(at, std::string::npos);
    shader.replace(at, end.size(),
                   "  float slow = 0.0;\n"
                   "  for (int i = 0; i < 50000; ++i)\n"
                   "    for (int j = 0; j < 50000; ++j) slow += sin(slow + float(i) * 0.001 + float(j));\n"
                   "  return fixed4(diffuse + specular + rim + slow * 1e-30, albedo.a);");
    std::ofstream(root_ / "shaders/materials/slow.hlsl") << shader;
    std::string scene = read_text(root_ / "scenes" / (std::string(kCopiedScene) + ".toml"));
    for (size_t pos; (pos = scene.find("materials/toon.hlsl")) != std::string::npos;)
      scene.replace(pos, std::string("materials/toon.hlsl").size(), "materials/slow.hlsl");
    std::ofstream(root_ / "scenes/slow.toml") << scene;
  }

  std::string folders() const { return copied_scene_options(root_); }
  Outcome run(const std::string& extra) {
    return run_xshade("", "run" + folders() + " --report '" + (root_ / "report").string() + "' " + extra);
  }

  fs::path root_;
};

// A limit of its own for the slow scene: the run's default stays, so that the other scene has
// all the time a loaded machine needs.
void set_scene_timeout(const fs::path& scene_file, const std::string& lines) {
  std::string scene = read_text(scene_file);
  const size_t size = scene.find("size = ");
  ASSERT_NE(size, std::string::npos);
  scene.insert(size, lines);
  std::ofstream(scene_file) << scene;
}

TEST_F(Workers, ARenderThatHangsIsATimeoutInItsPassAndTheOtherScenesPass) {
  add_slow_scene();
  // 5 s: the compile (under a second) is over, the first render has begun.
  set_scene_timeout(root_ / "scenes/slow.toml", "timeout = 5\ntimeout_reason = \"a test of a render that hangs\"\n");
  Outcome outcome = run("--lane gl");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("slow on gl: fail - timeout after 5 s in pass scene (render 1 of 2)"),
            std::string::npos)
      << outcome.output;
  EXPECT_NE(outcome.output.find(std::string(kCopiedScene) + " on gl: pass"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("1 of 2 scenes passed"), std::string::npos) << outcome.output;
  // Every report says so.
  EXPECT_NE(read_text(root_ / "report/results.json").find("timeout after 5 s in pass scene"), std::string::npos);
  EXPECT_NE(read_text(root_ / "report/junit.xml").find("timeout after 5 s in pass scene"), std::string::npos);
  EXPECT_NE(read_text(root_ / "report/index.html").find("timeout after 5 s"), std::string::npos);
}

// One job at a time: the first worker renders the slow scene (on gl alone) until it is stopped
// at its limit, and a second one, started in its place, renders the toon on gl and then on vk.
TEST_F(Workers, AWorkerServesRenderAfterRenderAndOneStoppedAtItsLimitIsReplaced) {
  add_slow_scene();
  set_scene_timeout(root_ / "scenes/slow.toml",
                    "lanes = [\"gl\"]\ntimeout = 5\ntimeout_reason = \"a test of a render that hangs\"\n");
  Outcome outcome = run("--lane gl,vk -j 1");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("slow on gl: fail - timeout after 5 s"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find(std::string(kCopiedScene) + " on vk: pass"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("1 of 2 scenes passed"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("; 3 renders in 2 workers;"), std::string::npos) << outcome.output;
}

TEST_F(Workers, TheRunsTimeoutStopsARenderAndAScenesOwnNeedsItsReason) {
  add_slow_scene();
  Outcome outcome = run("slow --lane gl --timeout 5");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("slow on gl: fail - timeout after 5 s in pass scene"), std::string::npos)
      << outcome.output;

  // A limit without its reason is the user's mistake, at its line.
  set_scene_timeout(root_ / "scenes/slow.toml", "timeout = 5\n");
  outcome = run("slow --lane gl");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("slow.toml:1:1: error: timeout_reason"), std::string::npos) << outcome.output;
}

TEST_F(Workers, AWorkerThatDiesIsACrashNamingTheSignalAndWhereItWas) {
  add_slow_scene();
  // The run in the background; once the slow scene's worker (the run's one child: one render)
  // has been drawing for a while, it is sent SIGSEGV, as a driver's fault would end it.
  const std::string out = (root_ / "out.txt").string();
  const std::string command = "'" + std::string(xshade_binary()) + "' run slow" + folders() + " --report '" +
                              (root_ / "report").string() + "' --lane gl --timeout 600 > '" + out +
                              "' 2>&1 & run=$!; pid=; for i in $(seq 600); do pid=$(pgrep -P $run); " +
                              "[ -n \"$pid\" ] && break; sleep 0.1; done; " +
                              "sleep 2; kill -SEGV $pid; wait $run; echo \"exit $?\" >> '" + out + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string output = read_text(out);
  EXPECT_NE(output.find("exit 3"), std::string::npos) << output;
  EXPECT_NE(output.find("slow on gl: crash - worker died: SIGSEGV (segmentation fault) in pass scene (render 1 of 2)"),
            std::string::npos)
      << output;
}

// ^C or `kill` in the middle of a render: the run ends its worker, removes the workers' folder and
// exits 128 + the signal, as a shell reports it; it writes no report of the scenes it did not
// finish. Each run has a temporary folder of its own (TMPDIR), so that what is left is its own.
TEST_F(Workers, ARunStoppedByASignalEndsItsWorkersAndLeavesNoFolder) {
  add_slow_scene();
  for (const auto& [signal, code] : {std::pair{"INT", 130}, std::pair{"TERM", 143}}) {
    const fs::path temp = root_ / ("tmp_" + std::string(signal));
    fs::create_directories(temp);
    const std::string out = (root_ / "out.txt").string();
    // Through bash with set -m: a background job of a shell without job control starts with SIGINT
    // ignored, which xshade leaves so.
    const std::string command =
        "set -m; TMPDIR='" + temp.string() + "' '" + std::string(xshade_binary()) + "' run slow" + folders() +
        " --report '" + (root_ / "report").string() + "' --lane gl --timeout 600 > '" + out + "' 2>&1 & run=$!; " +
        "worker=; for i in $(seq 600); do worker=$(pgrep -P $run); [ -n \"$worker\" ] && break; sleep 0.1; done; " +
        "sleep 1; kill -" + signal + " $run; wait $run; echo \"exit $?\" >> '" + out + "'; " +
        "sleep 0.5; kill -0 $worker 2>/dev/null && echo 'worker still running' >> '" + out + "'; true";
    std::ofstream(root_ / "stop.sh") << command << "\n";
    ASSERT_EQ(std::system(("bash '" + (root_ / "stop.sh").string() + "' < /dev/null").c_str()), 0) << signal;
    const std::string output = read_text(out);
    EXPECT_NE(output.find("exit " + std::to_string(code)), std::string::npos) << output;
    // At once, in the middle of the render: not once the render has ended.
    EXPECT_NE(output.find("xshade run: stopped by SIG" + std::string(signal)), std::string::npos) << output;
    EXPECT_NE(output.find(" after 0 of 1 scenes"), std::string::npos) << output;
    EXPECT_EQ(output.find("worker still running"), std::string::npos) << output;
    EXPECT_TRUE(fs::is_empty(temp)) << signal << ": " << fs::directory_iterator(temp)->path();
    EXPECT_FALSE(fs::exists(root_ / "report/results.json")) << signal;
  }
}

// A run killed with SIGKILL cannot clean up: the next run removes the workers' folder it left
// (its lock is free), and never one whose run still holds it.
TEST_F(Workers, ARunRemovesTheWorkersFoldersOfDeadRunsAndNoOther) {
  const fs::path temp = root_ / "tmp";
  const fs::path dead = temp / "xshade-workers-dEaD01";
  const fs::path live = temp / "xshade-workers-LiVe01";
  fs::create_directories(dead / "0-gl");
  fs::create_directories(live / "0-gl");
  std::ofstream(dead / "0-gl/image.f32") << "a dead run's render";
  std::ofstream(live / "0-gl/image.f32") << "a live run's render";
  const int held = open(live.c_str(), O_RDONLY | O_DIRECTORY);
  ASSERT_GE(held, 0);
  ASSERT_EQ(flock(held, LOCK_EX), 0);
  Outcome outcome = run_xshade("TMPDIR='" + temp.string() + "'",
                               "run" + folders() + " --report '" + (root_ / "report").string() + "' --lane gl");
  close(held);
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_FALSE(fs::exists(dead)) << outcome.output;
  EXPECT_TRUE(fs::exists(live / "0-gl/image.f32"));
  // And the run's own folder is gone with it.
  std::vector<std::string> left;
  for (const fs::directory_entry& entry : fs::directory_iterator(temp)) left.push_back(entry.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"xshade-workers-LiVe01"});
}

// Of several files, the one that hangs is a timeout on its lane; the file before it keeps its
// image and the ones after it get a new worker, which reports each of them.
TEST_F(Workers, AnEvalLaneThatHangsIsATimeoutOfThatFileAndTheOthersStillRun) {
  const fs::path shader = root_ / "hang.hlsl";
  std::ofstream(shader)
      << "#pragma fragment frag\n"
         "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
         "  float s = 0.0;\n"
         "  for (int i = 0; i < 50000; ++i)\n"
         "    for (int j = 0; j < 50000; ++j) s += sin(s + pos.x * 0.001 + float(i) * 0.001 + float(j));\n"
         "  return float4(s * 1e-30, 0, 0, 1);\n"
         "}\n";
  for (const char* name : {"before", "after", "last"})
    std::ofstream(root_ / (std::string(name) + ".hlsl"))
        << "#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0) : SV_Target { return float4(uv, 0, 1); }\n";
  const fs::path out = root_ / "eval";
  Outcome outcome = run_xshade("", "eval '" + (root_ / "before.hlsl").string() + "' '" + shader.string() + "' '" +
                                       (root_ / "after.hlsl").string() + "' '" + (root_ / "last.hlsl").string() +
                                       "' --size 256x256 --lane gl --timeout 2 -o '" + out.string() + "'");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  const std::string hang = "== " + shader.string() + "\ngl: timeout after 2 s";
  EXPECT_NE(outcome.output.find(hang), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("== " + shader.string() + ": exit 1"), std::string::npos) << outcome.output;
  for (const char* name : {"before", "after", "last"}) {
    const std::string file = (root_ / (std::string(name) + ".hlsl")).string();
    EXPECT_NE(outcome.output.find("== " + file + "\ngl: " + (out / (std::string(name) + ".gl.exr")).string() +
                                  "\n== " + file + ": exit 0"),
              std::string::npos)
        << outcome.output;
    EXPECT_TRUE(fs::exists(out / (std::string(name) + ".gl.exr"))) << name;
  }
}

// An EXR's pixels (its header holds the time it was written, which differs from run to run).
std::vector<float> float_pixels(const fs::path& file) {
  Result<harness::FloatImage> image = harness::read_image(file, /*srgb=*/false);
  return image ? image->rgba : std::vector<float>{};
}

// Every fixed scene on every lane, with one worker and with two, with caches cold and warm (the
// compiled shaders, the drivers' own shader cache, the environments): the float images bit for bit
// and every verdict the same. A run with --no-cache is not a third case: it computes what the cold
// run computes (every shader compiled, every environment built in the worker) and stores nothing.
TEST(WorkerCount, ImagesAndVerdictsOfEveryFixedSceneDoNotDependOnItNorOnTheCaches) {
  const fs::path root = fs::temp_directory_path() / "xshade_workers_count";
  fs::remove_all(root);
  const std::string cache = " --cache '" + (root / "cache").string() + "'";
  const std::pair<std::string, std::string> runs[] = {{"one_worker_cold_cache", "-j 1" + cache},
                                                      {"two_workers_warm_cache", "-j 2" + cache}};
  std::map<std::string, std::string> verdicts;
  for (const auto& [name, options] : runs) {
    const fs::path report = root / name;
    Outcome outcome = run_xshade("", "run --report '" + report.string() + "' " + options);
    EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
    const std::string json = read_text(report / "results.json");
    // The verdicts, in order: every "verdict" field of results.json.
    for (size_t at = 0; (at = json.find("\"verdict\": ", at)) != std::string::npos; ++at)
      verdicts[name] += json.substr(at, json.find(',', at) - at) + "\n";
  }
  const std::string& first = runs[0].first;
  EXPECT_FALSE(verdicts[first].empty());
  for (const auto& [name, options] : runs) EXPECT_EQ(verdicts[name], verdicts[first]) << name;
  size_t images = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root / first)) {
    if (entry.path().extension() != ".exr") continue;
    const std::vector<float> pixels = float_pixels(entry.path());
    EXPECT_FALSE(pixels.empty()) << entry.path();
    for (const auto& [name, options] : runs) {
      const fs::path other = root / name / fs::relative(entry.path(), root / first);
      EXPECT_TRUE(pixels == float_pixels(other)) << entry.path() << " differs from " << other;
    }
    ++images;
  }
  EXPECT_GE(images, 30u) << "every fixed scene on every lane writes its float image";
  fs::remove_all(root);
}

}  // namespace
}  // namespace xshade::tests
