// Hostile input through the real `xshade`: files made to crash or exhaust it (a TOML key nested
// past the parser's stack, image headers claiming gigapixels, a scene that expands into millions
// of draws, symbolic links out of the folders) are each refused with exit 2 and a message naming
// the file, the position and the limit; none reaches a signal or an uncaught exception.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "harness/image/forged_image_headers.h"
#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;
namespace forged = harness::forged;

// "a.a.a...": one dotted key of 100,000 parts, the 200 KB line that overflowed toml++'s stack.
std::string deep_key() {
  std::string key = "a";
  for (int i = 1; i < 100000; ++i) key += ".a";
  return key;
}
constexpr const char* kDeepKeyError =
    "a dotted key or table header of 100000 parts; xshade reads at most 100 (a longer one could overflow the TOML "
    "parser's stack)";

size_t lines_in(const fs::path& file) {
  const std::string text = read_text(file);
  return size_t(std::count(text.begin(), text.end(), '\n'));
}

void append(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::app) << text; }

// `command` through sh, its output and exit code.
Outcome shell(const std::string& command) {
  Outcome outcome;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return outcome;
  char buffer[4096];
  while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) outcome.output.append(buffer, n);
  const int status = pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return outcome;
}

class HostileInput : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_hostile_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    copy_fixed_scene(kSource, root_, kCopiedScene);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path scene() const { return root_ / "scenes" / (std::string(kCopiedScene) + ".toml"); }
  // An 8192 x 4096 environment: within the limits, and some 900 MB to read.
  void use_large_environment() {
    forged::write(root_ / "scenes" / "large.hdr", forged::hdr(8192, 4096));
    append(scene(), "\n[environment]\nkind = \"equirect\"\nfile = \"large.hdr\"\n");
  }

  Outcome run(const std::string& extra = "--lane gl", const std::string& environment = "") {
    return run_xshade(environment,
                      "run" + copied_scene_options(root_) + " --report '" + (root_ / "report").string() + "' " + extra);
  }

  fs::path root_;
};

// ---- TOML nested past the parser's stack: refused before toml++ reads it, at the key.

TEST_F(HostileInput, ASceneFileWithADeepKeyIsRefusedAtTheKey) {
  const size_t line = lines_in(scene()) + 1;
  append(scene(), deep_key() + " = 1\n");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output.substr(0, 2000);
  EXPECT_NE(outcome.output.find(scene().string() + ":" + std::to_string(line) + ":1: " + kDeepKeyError),
            std::string::npos)
      << outcome.output.substr(0, 2000);
}

TEST_F(HostileInput, AGoldenManifestWithADeepKeyIsRefusedAtTheKey) {
  const fs::path manifest = root_ / "golden" / "MANIFEST.toml";
  const size_t line = lines_in(manifest) + 1;
  append(manifest, deep_key() + " = 1\n");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output.substr(0, 2000);
  EXPECT_NE(outcome.output.find(manifest.string() + ":" + std::to_string(line) + ":1: " + kDeepKeyError),
            std::string::npos)
      << outcome.output.substr(0, 2000);
}

TEST_F(HostileInput, AProjectFileWithADeepTableHeaderIsRefusedAtTheHeader) {
  fs::create_directories(root_ / ".git");
  std::ofstream(root_ / "xshade.toml") << "scenes = \"scenes\"\n[" << deep_key() << "]\n";
  Outcome outcome = run_xshade_in(root_, "run --plan");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output.substr(0, 2000);
  EXPECT_NE(outcome.output.find((root_ / "xshade.toml").string() + ":2:2: " + kDeepKeyError), std::string::npos)
      << outcome.output.substr(0, 2000);
}

// ---- Image headers that claim more pixels than the file holds: refused before allocating.

TEST_F(HostileInput, ATextureWhoseHeaderClaimsTooManyPixelsIsTheScenesFault) {
  forged::write(root_ / "scenes" / "huge.png", forged::png(65535, 65535));
  replace_in_file(scene(), "_ShadowTex = \"checker\"", "_ShadowTex = \"huge.png\"");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("cannot read image " + (root_ / "scenes" / "huge.png").string() +
                                ": it is 65535 x 65535 pixels; xshade reads images of at most 16384 pixels a side "
                                "and 33554432 pixels in all"),
            std::string::npos)
      << outcome.output;
}

TEST_F(HostileInput, AnEnvironmentWhoseHeaderClaimsTooManyPixelsIsTheScenesFault) {
  const std::string original = read_text(scene());
  for (const auto& [name, bytes, size] : {std::tuple{"huge.hdr", forged::hdr(100000, 100000), "100000 x 100000"},
                                          std::tuple{"huge.exr", forged::exr(1000000, 1000000), "1000000 x 1000000"}}) {
    forged::write(root_ / "scenes" / name, bytes);
    std::ofstream(scene(), std::ios::trunc)
        << original << "\n[environment]\nkind = \"equirect\"\nfile = \"" << name << "\"\n";
    Outcome outcome = run();
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find("cannot read image " + (root_ / "scenes" / name).string() + ": it is " + size +
                                  " pixels; xshade reads images of at most 16384 pixels a side"),
              std::string::npos)
        << outcome.output;
  }
}

// white_furnace has no value above 1, so its PNG alone is its golden (made by hand, with the
// manifest entry and hash every golden needs, so that the image's own header is what is refused).
TEST_F(HostileInput, AGoldenWhoseHeaderClaimsTooManyPixelsIsRefused) {
  fs::remove(scene());
  fs::copy_file(kSource / "scenes" / "white_furnace.toml", root_ / "scenes" / "white_furnace.toml");
  const fs::path golden = root_ / "golden" / "white_furnace.png";
  forged::write(golden, forged::png(65535, 65535));
  write_manifest_for(root_ / "golden", "white_furnace");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("cannot read image " + golden.string() +
                                ": it is 65535 x 65535 pixels; xshade reads "
                                "images of at most 16384 pixels a side"),
            std::string::npos)
      << outcome.output;
}

// ---- The work budget: a small scene of 1000 objects, each a 64 x 64 grid, is 4 million draws.

TEST_F(HostileInput, ASceneOfMillionsOfDrawsIsRefusedAsItIsRead) {
  std::string text = read_text(scene());
  text = text.substr(0, text.find("[[object]]"));
  size_t line = size_t(std::count(text.begin(), text.end(), '\n')) + 1;
  size_t fifth = 0;  // the object whose grid takes the draws past 16384: 5 x 4096
  for (int i = 0; i < 1000; ++i) {
    if (i == 4) fifth = line;
    text += "[[object]]\nmesh=\"cube\"\nmaterial=\"materials/toon.hlsl\"\ngrid={rows=64,cols=64,spacing=1}\n";
    line += 4;
  }
  ASSERT_LT(text.size(), 90000u);  // some 88 KB
  std::ofstream(scene(), std::ios::trunc) << text;
  for (const std::string& extra : {std::string("--lane gl"), std::string("--plan")}) {
    Outcome outcome = run(extra);
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output.substr(0, 2000);
    EXPECT_NE(outcome.output.find(scene().string() + ":" + std::to_string(fifth) +
                                  ":1: object[4]: here the scene passes 16384 draws, the most a scene may make; it "
                                  "makes 4096000 in all (1000 objects, a draw for each without a grid and for each "
                                  "cell of a grid, and 0 post effects)"),
              std::string::npos)
        << outcome.output.substr(0, 2000);
  }
}

TEST_F(HostileInput, ALargeFrameTimesManyDrawsIsRefused) {
  replace_in_file(scene(), "size = [256, 256]", "size = [4096, 4096]");
  append(scene(), "[object.grid]\nrows = 64\ncols = 64\nspacing = 0.1\n");
  Outcome outcome = run("--plan");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(
      outcome.output.find("object[0]: here the scene passes 4294967296 pixel-draws (draws times the 4096 x 4096 = "
                          "16777216 pixels each may cover), the most a scene may make; it makes 68719476736 in "
                          "all (4096 draws: 1 objects"),
      std::string::npos)
      << outcome.output;
}

// ---- Symbolic links out of the folders.

TEST_F(HostileInput, ASceneFileLinkedFromOutsideTheScenesFolderIsRefused) {
  fs::create_directories(root_ / "private");
  fs::rename(scene(), root_ / "private" / "secret.toml");
  fs::create_symlink(root_ / "private" / "secret.toml", root_ / "scenes" / "linked.toml");
  for (const std::string& extra : {std::string("--lane gl"), std::string("linked --lane gl")}) {
    Outcome outcome = run(extra);
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find("the scene file " + (root_ / "scenes" / "linked.toml").string() +
                                  " is a symbolic link that points outside the scenes folder " +
                                  (root_ / "scenes").string() + " (to " + (root_ / "private" / "secret.toml").string() +
                                  "); a scene file must be inside its folder"),
              std::string::npos)
        << outcome.output;
    EXPECT_EQ(outcome.output.find("on gl:"), std::string::npos) << outcome.output;  // nothing rendered
  }
}

TEST_F(HostileInput, AProjectFileLinkedFromOutsideItsFolderIsRefused) {
  fs::create_directories(root_ / "repo" / ".git");
  fs::create_directories(root_ / "elsewhere");
  std::ofstream(root_ / "elsewhere" / "xshade.toml") << "scenes = \"../scenes\"\n";
  fs::create_symlink(root_ / "elsewhere" / "xshade.toml", root_ / "repo" / "xshade.toml");
  Outcome outcome = run_xshade_in(root_ / "repo", "run --plan");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find((root_ / "repo" / "xshade.toml").string() +
                                ": the project file is a symbolic link that points outside its folder"),
            std::string::npos)
      << outcome.output;
}

// ---- What is not a file is never read, waited on, or passed over.

// An xshade.toml that is a folder, a FIFO or a link to nothing once made `run` check xshade's own
// fixed scenes instead of the project's and print "10 of 10 scenes passed" with exit 0.
TEST_F(HostileInput, AnXshadeTomlThatIsNotAFileIsExitTwoNotAPassOfTheFixedScenes) {
  fs::create_directories(root_ / "repo" / ".git");
  const fs::path project = root_ / "repo" / "xshade.toml";
  const std::vector<std::pair<std::string, std::function<void()>>> kinds = {
      {"a directory", [&] { fs::create_directories(project); }},
      {"a FIFO", [&] { ASSERT_EQ(::mkfifo(project.c_str(), 0600), 0); }},
      {"a symbolic link to nothing", [&] { fs::create_symlink(root_ / "repo" / "gone.toml", project); }}};
  for (const auto& [kind, make] : kinds) {
    make();
    Outcome outcome = run_xshade_in(root_ / "repo", "run --lane gl");
    EXPECT_EQ(outcome.exit_code, 2) << kind << "\n" << outcome.output;
    EXPECT_NE(outcome.output.find("the project file " + project.string() + " is " + kind + ", not a file"),
              std::string::npos)
        << outcome.output;
    EXPECT_EQ(outcome.output.find("passed"), std::string::npos) << outcome.output;
    fs::remove(project);
  }
}

// A FIFO among the scene files once hung `run` before anything rendered, whether or not the run
// named it: now it is refused at once, and a run of the other scenes by name does not read it.
TEST_F(HostileInput, AFifoAmongTheSceneFilesIsRefusedWithoutWaitingOnIt) {
  const fs::path fifo = root_ / "scenes" / "waiting.toml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  Outcome all = run("--plan");
  EXPECT_EQ(all.exit_code, 2) << all.output;
  EXPECT_NE(all.output.find("the scene file " + fifo.string() + " is a FIFO, not a file"), std::string::npos)
      << all.output;
  Outcome named = run(std::string(kCopiedScene) + " --plan");
  EXPECT_EQ(named.exit_code, 0) << named.output;
}

// A FIFO as a texture once waited in the worker until the lane's time limit ("timeout while
// creating the gl backend", exit 1): it is the scene's mistake, exit 2, naming the file.
TEST_F(HostileInput, AFifoAsATextureIsTheScenesFaultAtOnce) {
  const fs::path fifo = root_ / "scenes" / "waiting.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  replace_in_file(scene(), "_ShadowTex = \"checker\"", "_ShadowTex = \"waiting.png\"");
  Outcome outcome = run("--timeout 60");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(
      outcome.output.find("texture '_ShadowTex': cannot read image " + fifo.string() + ": it is a FIFO, not a file"),
      std::string::npos)
      << outcome.output;
}

// An #include of a FIFO is refused at the include (only a regular file is an include file), never
// waited on.
TEST_F(HostileInput, AnIncludeOfAFifoIsRefusedAtTheInclude) {
  ASSERT_EQ(::mkfifo((root_ / "waiting.hlsl").c_str(), 0600), 0);
  const fs::path shader = root_ / "includes_a_fifo.hlsl";
  std::ofstream(shader) << "#include \"waiting.hlsl\"\n#pragma fragment frag\n"
                           "float4 frag() : SV_Target { return 1; }\n";
  Outcome outcome = run_xshade("", "compile '" + shader.string() + "' --target gl");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(shader.string() + ":1:10: error: cannot find include file 'waiting.hlsl'"),
            std::string::npos)
      << outcome.output;
}

// A full disk under the cache and the report: once every gl lane died by SIGBUS (Mesa writes its
// cache index through a memory map) and zero-byte images were left. Now the drivers' cache is off
// with a warning, each file that cannot be written is named with the system's reason, nothing
// half-written is left, and the run is the environment's failure (exit 3). The disks are tmpfs
// mounts in a mount namespace of the test's own (skipped where none can be made): the cache's
// full, the report's with some 100 KiB free (room for its lock, not for its images).
TEST_F(HostileInput, AFullDiskIsExitThreeNamingEachFileAndLeavesNoEmptyFile) {
  const fs::path cache_disk = root_ / "cache_disk", report_disk = root_ / "report_disk";
  fs::create_directories(cache_disk);
  fs::create_directories(report_disk);
  std::string script;
  for (const auto& [disk, blocks] : {std::pair{cache_disk, 32}, std::pair{report_disk, 30}})
    script += "mount -t tmpfs -o size=2m tmpfs '" + disk.string() + "' || exit 77; dd if=/dev/zero of='" +
              disk.string() + "/fill' bs=64k count=" + std::to_string(blocks) + " 2>/dev/null; ";
  script += xshade_command("", "run --lane gl,vk --scenes '" + (root_ / "scenes").string() + "' --golden '" +
                                   (root_ / "golden").string() + "' --shaders '" + (root_ / "shaders").string() +
                                   "' --cache '" + cache_disk.string() + "/cache' --report '" + report_disk.string() +
                                   "/report'") +
            "; echo \"exit $?\"; find '" + cache_disk.string() + "' '" + report_disk.string() +
            "' -type f -size 0 -printf 'empty %p\\n'; find '" + cache_disk.string() + "' '" + report_disk.string() +
            "' -name '*.tmp*' -printf 'temporary %p\\n'";
  std::ofstream(root_ / "full.sh") << script << "\n";
  Outcome outcome = shell("unshare --user --map-root-user --mount sh '" + (root_ / "full.sh").string() + "'");
  if (outcome.exit_code == 77 || outcome.output.find("unshare:") != std::string::npos)
    GTEST_SKIP() << "no mount namespace here: " << outcome.output;
  EXPECT_NE(outcome.output.find("exit 3"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("warning: the drivers' shader cache is off for this run: the disk of " +
                                cache_disk.string() + "/cache has 0 KiB free, less than the 64 MiB it needs"),
            std::string::npos)
      << outcome.output;
  // A lane's own image, not only the golden copied beside it.
  EXPECT_TRUE(std::regex_search(outcome.output, std::regex("cannot write \\S+/report/" + std::string(kCopiedScene) +
                                                           "/(gl|vk)\\.(png|exr): No space left on device")))
      << outcome.output;
  EXPECT_NE(outcome.output.find("xshade run: the report is not whole"), std::string::npos) << outcome.output;
  EXPECT_EQ(outcome.output.find("SIGBUS"), std::string::npos) << outcome.output;
  EXPECT_EQ(outcome.output.find("empty "), std::string::npos) << outcome.output;
  EXPECT_EQ(outcome.output.find("temporary "), std::string::npos) << outcome.output;
}

// A sparse file of 4 GiB named as a shader (HLSL or ShaderLab) is refused by its size, unread.
TEST_F(HostileInput, AShaderSourceOfGigabytesIsRefusedUnread) {
  for (const char* name : {"huge.hlsl", "huge.shader"}) {
    const fs::path shader = root_ / name;
    std::ofstream(shader) << "// nothing yet\n";
    fs::resize_file(shader, uint64_t(4) << 30);
    Outcome outcome = run_xshade("ulimit -v 2000000;", "compile '" + shader.string() + "' --target gl");
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find("is 4294967296 bytes; a shader source may have at most 16 MiB"), std::string::npos)
        << name << ": " << outcome.output;
  }
}

// `xshade diff a.png /dev/zero` once read /dev/zero at full CPU for ever, and a FIFO image
// waited for a writer; each is refused at once, naming what it is.
TEST_F(HostileInput, DiffRefusesADeviceOrAFifoAsAnImage) {
  const fs::path golden = root_ / "golden" / (std::string(kCopiedScene) + ".png");
  ASSERT_TRUE(fs::exists(golden));
  const fs::path fifo = root_ / "waiting.png";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const auto& [other, kind] : {std::pair{fs::path("/dev/zero"), "a device"}, std::pair{fifo, "a FIFO"}}) {
    Outcome outcome = run_xshade("", "diff '" + golden.string() + "' '" + other.string() + "'");
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find("cannot read image " + other.string() + ": it is " + kind + ", not a file"),
              std::string::npos)
        << outcome.output;
  }
}

// `run --shard 1/2` and `run --shard 2/2` at once into one --report once both exited 0 and left
// shard 1's scenes only. A run holds its report folder; a second is refused at once, told which
// run holds it (here the test holds the lock as another run would), and runs once it is free.
TEST_F(HostileInput, ASecondRunIntoAReportFolderInUseIsRefusedNamingTheFirst) {
  fs::create_directories(root_ / "report");
  const fs::path lock = root_ / "report" / ".xshade-report.lock";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const std::string holder = "process 4242: xshade run --shard 1/2\n";
  ASSERT_EQ(::write(fd, holder.data(), holder.size()), ssize_t(holder.size()));
  Outcome refused = run("--lane gl");
  ::close(fd);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("the report folder " + (root_ / "report").string() +
                                " is being written by another xshade (process 4242: xshade run --shard 1/2)"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(root_ / "report" / "results.json")) << "the refused run wrote nothing";
  Outcome free = run("--lane gl");
  EXPECT_EQ(free.exit_code, 0) << free.output;
  // A plan writes no report: it neither takes the lock nor makes the folder.
  Outcome plan = run_xshade(
      "", "run --plan" + copied_scene_options(root_) + " --report '" + (root_ / "plan_report").string() + "'");
  EXPECT_EQ(plan.exit_code, 0) << plan.output;
  EXPECT_FALSE(fs::exists(root_ / "plan_report"));

  // A merge into a folder a run is writing is refused alike, before it copies anything.
  const fs::path merged = root_ / "merged";
  fs::create_directories(merged);
  const int merge_fd = ::open((merged / ".xshade-report.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(merge_fd, 0);
  ASSERT_EQ(::flock(merge_fd, LOCK_EX), 0);
  Outcome merge = run_xshade("", "report merge '" + (root_ / "report").string() + "' --out '" + merged.string() + "'");
  ::close(merge_fd);
  EXPECT_EQ(merge.exit_code, 2) << merge.output;
  EXPECT_NE(merge.output.find("the report folder " + merged.string() + " is being written by another xshade"),
            std::string::npos)
      << merge.output;
  EXPECT_FALSE(fs::exists(merged / "results.json"));
  EXPECT_FALSE(fs::exists(merged / kCopiedScene));
}

// ---- Work and memory have bounds.

// 40 `#pragma multi_compile _ KW_n` lines once made `compile --all-variants` list 2^40
// combinations until it held 8.5 GB; the count is refused before anything is listed.
TEST_F(HostileInput, AllVariantsOfTwoToTheFortyIsRefusedAtOnce) {
  std::string shader = "#pragma fragment frag\n";
  for (int i = 0; i < 40; ++i) shader += "#pragma multi_compile _ KW_" + std::to_string(i) + "\n";
  shader += "float4 frag() : SV_Target { return 1; }\n";
  std::ofstream(root_ / "many.hlsl") << shader;
  const auto started = std::chrono::steady_clock::now();
  Outcome outcome =
      run_xshade("", "compile '" + (root_ / "many.hlsl").string() + "' --target gl --all-variants --no-project");
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(20));  // not minutes of listing
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output.substr(0, 2000);
  EXPECT_NE(
      outcome.output.find("--all-variants compiles at most 16384 keyword combinations, and the 40 keyword sets of "
                          "this shader make more"),
      std::string::npos)
      << outcome.output.substr(0, 2000);
  EXPECT_EQ(outcome.output.find(": compiles"), std::string::npos);
}

// Two images of different sizes are two images that differ: exit 1, never the pass code.
TEST_F(HostileInput, DiffOfImagesOfDifferentSizesFails) {
  Outcome outcome = run_xshade("", "diff '" + (kSource / "golden" / "dof_off.png").string() + "' '" +
                                       (kSource / "golden" / "white_furnace.png").string() + "'");
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find("test is 320x96 but the reference is 320x240"), std::string::npos) << outcome.output;
}

// ---- The compile cache is the user's alone.

// With HOME unset the cache once fell back to /tmp/xshade-cache, which another user had made
// with mode 777 and filled with variants of their own; xshade used them. The fallback is now the
// user's own folder, made 0700, and a cache folder others can write is not used (a warning, then
// the run compiles everything).
TEST_F(HostileInput, ACacheFolderOthersCanWriteIsNotUsedAndTheFallbackIsTheUsersOwn) {
  fs::create_directories(root_ / "cache");
  fs::permissions(root_ / "cache", fs::perms::all);
  Outcome shared = run("--lane gl");
  EXPECT_EQ(shared.exit_code, 0) << shared.output;
  EXPECT_NE(shared.output.find("xshade run: warning: not using the compile cache: " + (root_ / "cache").string() +
                               " can be written by other users (mode 777); make it private with chmod 700"),
            std::string::npos)
      << shared.output;
  EXPECT_TRUE(fs::is_empty(root_ / "cache")) << "nothing was stored where others can write";

  const fs::path tmp = root_ / "tmp";
  fs::create_directories(tmp);
  const std::string options = " --scenes '" + (root_ / "scenes").string() + "' --golden '" +
                              (root_ / "golden").string() + "' --shaders '" + (root_ / "shaders").string() +
                              "' --report '" + (root_ / "report").string() + "' --lane gl";
  Outcome fallback =
      run_xshade("HOME= XDG_CACHE_HOME= XSHADE_CACHE_DIR= TMPDIR='" + tmp.string() + "'", "run" + options);
  EXPECT_EQ(fallback.exit_code, 0) << fallback.output;
  const fs::path own = tmp / ("xshade-cache-" + std::to_string(::geteuid()));
  struct stat status {};
  ASSERT_EQ(::stat(own.c_str(), &status), 0) << fallback.output;
  EXPECT_EQ(status.st_mode & 0777, 0700u);
  EXPECT_FALSE(fs::is_empty(own));
}

// ---- An exception that escapes a verb is exit 3 with a message, not an abort (exit 134).

TEST_F(HostileInput, AnAllocationThatFailsIsExitThreeWithAMessage) {
  // An 8192 x 4096 environment is within the limits: reading it takes some 900 MB, more than the
  // address space this run is given, so the allocation throws std::bad_alloc in the worker that
  // builds the environment, which says so and exits 3; the run reports that lane's crash with
  // the worker's words and exits 3 too. Neither aborts (exit 134).
  use_large_environment();
  Outcome outcome = run("--lane gl", "ulimit -v 600000;");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("xshade worker: out of memory (an allocation failed; each xshade process may take 0.6 "
                                "GiB of address space (XSHADE_MEMORY_LIMIT=GiB sets it, 0 for no limit)); nothing "
                                "more was done"),
            std::string::npos)
      << outcome.output;
  EXPECT_NE(outcome.output.find("toon_shadow_texture on gl: crash - worker exited with code 3 while building the "
                                "environment"),
            std::string::npos)
      << outcome.output;
  EXPECT_EQ(outcome.output.find("terminate called"), std::string::npos) << outcome.output;
}

// The same runaway with no limit from the shell: xshade's own ceiling (XSHADE_MEMORY_LIMIT, by
// default half the machine's memory) turns it into exit 3 with the limit named, never the
// kernel's OOM killer; a setting that is not a number is the user's mistake.
TEST_F(HostileInput, XshadesOwnMemoryCeilingStopsARunawayWithExitThree) {
  use_large_environment();
  Outcome outcome = run("--lane gl", "ulimit -v unlimited; XSHADE_MEMORY_LIMIT=0.6");
  EXPECT_EQ(outcome.exit_code, 3) << outcome.output;
  EXPECT_NE(outcome.output.find("xshade worker: out of memory (an allocation failed; each xshade process may take 0.6 "
                                "GiB of address space"),
            std::string::npos)
      << outcome.output;
  EXPECT_EQ(outcome.output.find("SIGKILL"), std::string::npos) << outcome.output;

  Outcome mistaken = run("--lane gl", "XSHADE_MEMORY_LIMIT=lots");
  EXPECT_EQ(mistaken.exit_code, 2) << mistaken.output;
  EXPECT_NE(mistaken.output.find("xshade: XSHADE_MEMORY_LIMIT=lots: expected the address space each xshade process "
                                 "may take, in GiB (0: no limit)"),
            std::string::npos)
      << mistaken.output;
}

}  // namespace
}  // namespace xshade::tests
