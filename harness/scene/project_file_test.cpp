#include "harness/scene/project_file.h"

#include <sys/stat.h>

#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

class ProjectFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A folder per test: CTest runs the cases of this fixture in parallel.
    root_ = fs::temp_directory_path() / ("xshade_project_file_test_" +
                                         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    for (const char* folder :
         {"repo/.git", "repo/xshade/scenes", "repo/shaders", "repo/more_shaders", "repo/src/deep", "outside"})
      fs::create_directories(root_ / folder);
    std::ofstream(root_ / "repo/README.md") << "a file\n";
  }
  void TearDown() override { fs::remove_all(root_); }

  Result<ProjectFile> parse(const std::string& text) const {
    return parse_project_file(text, root_ / "repo/xshade.toml");
  }
  // Each problem as "line:col: message".
  std::vector<std::string> problems(const std::string& text) const {
    auto project = parse(text);
    EXPECT_FALSE(project);
    std::vector<std::string> lines;
    if (!project)
      for (const Diagnostic& d : project.error().diagnostics)
        lines.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
    return lines;
  }

  fs::path root_;
};

TEST_F(ProjectFileTest, PathsResolveAgainstTheProjectFilesFolder) {
  auto project =
      parse("scenes = \"xshade/scenes\"\ngolden = \"xshade/golden\"\nshaders = [\"shaders\", \"more_shaders/\"]\n");
  ASSERT_TRUE(project) << project.error().to_string();
  EXPECT_EQ(project->root, root_ / "repo");
  EXPECT_EQ(project->scenes, root_ / "repo/xshade/scenes");
  EXPECT_EQ(project->golden, root_ / "repo/xshade/golden");  // not there yet: blessing creates it
  EXPECT_EQ(project->shaders, (std::vector<fs::path>{root_ / "repo/shaders", root_ / "repo/more_shaders/"}));
}

// A project file is TOML too, read by the same toml++: the same limit holds it, at the key.
TEST_F(ProjectFileTest, AKeyNestedTooDeepIsRefusedBeforeTheTomlParserRecurses) {
  std::string key = "a";
  for (int i = 1; i < 100000; ++i) key += ".a";
  EXPECT_EQ(problems("scenes = \"xshade/scenes\"\n[" + key + "]\n"),
            (std::vector<std::string>{"2:2: a dotted key or table header of 100000 parts; xshade reads at most 100 (a "
                                      "longer one could overflow the TOML parser's stack)"}));
}

TEST_F(ProjectFileTest, EveryKeyIsOptionalAndOneShaderFolderMayBeAString) {
  auto empty = parse("# nothing set\n");
  ASSERT_TRUE(empty) << empty.error().to_string();
  EXPECT_FALSE(empty->scenes);
  EXPECT_FALSE(empty->golden);
  EXPECT_TRUE(empty->shaders.empty());
  auto one = parse("shaders = \"shaders\"\n");
  ASSERT_TRUE(one) << one.error().to_string();
  EXPECT_EQ(one->shaders, std::vector<fs::path>{root_ / "repo/shaders"});
}

TEST_F(ProjectFileTest, AFolderThatLeavesTheProjectIsRefused) {
  fs::create_symlink(root_ / "outside", root_ / "repo/linked");
  EXPECT_EQ(problems("scenes = \"../outside\"\ngolden = \"/etc\"\nshaders = [\"shaders\", \"linked\"]\n"),
            (std::vector<std::string>{
                "1:10: scenes: expected a folder inside the project file's folder " + (root_ / "repo").string() +
                    ", got \"../outside\", which leads out of it",
                "2:10: golden: expected a folder relative to the project file, got the absolute path \"/etc\"",
                "3:23: shaders[1]: expected a folder inside the project file's folder " + (root_ / "repo").string() +
                    ", got \"linked\", which leads out of it",
            }));
}

TEST_F(ProjectFileTest, WrongKeysTypesAndFoldersAreReportedWhereTheyAre) {
  EXPECT_EQ(problems("scene = \"xshade/scenes\"\nshaders = 3\ngolden = \"README.md\"\n"),
            (std::vector<std::string>{
                "1:1: scene: unknown key in a project file; did you mean scenes?",
                "2:11: shaders: expected a folder or an array of folders, got 3",
                "3:10: golden: expected a folder, got \"README.md\", which is a file",
            }));
  EXPECT_EQ(
      problems("scenes = \"scenes\"\n"),
      (std::vector<std::string>{"1:10: scenes: expected an existing folder, got \"scenes\", which does not exist (" +
                                (root_ / "repo/scenes").string() + ")"}));
  const std::vector<std::string> syntax = problems("scenes = [\"a\"\n");
  ASSERT_EQ(syntax.size(), 1u);
  EXPECT_EQ(syntax[0].rfind("1:15: syntax error: ", 0), 0u) << syntax[0];  // where TOML stops: the end of the file
}

TEST_F(ProjectFileTest, TheNearestProjectFileAboveIsFoundUpToTheRepositoryRoot) {
  EXPECT_EQ(find_project_file(root_ / "repo/src/deep"), std::nullopt);
  std::ofstream(root_ / "repo/xshade.toml") << "";
  EXPECT_EQ(find_project_file(root_ / "repo/src/deep"), root_ / "repo/xshade.toml");
  EXPECT_EQ(find_project_file(root_ / "repo"), root_ / "repo/xshade.toml");
  // Above the repository's root is another project's business.
  std::ofstream(root_ / "xshade.toml") << "";
  fs::remove(root_ / "repo/xshade.toml");
  EXPECT_EQ(find_project_file(root_ / "repo/src"), std::nullopt);
  EXPECT_EQ(find_project_file(root_ / "outside"), root_ / "xshade.toml");
}

// An xshade.toml that is not a file is never passed over: xshade would check its own fixed scenes
// instead of the project's and call that a pass.
TEST_F(ProjectFileTest, AnXshadeTomlThatIsNotAFileIsAnErrorNotPassedOver) {
  std::ofstream(root_ / "xshade.toml") << "";  // above the repository: never reached if the repo's is refused
  const fs::path here = root_ / "repo" / "xshade.toml";
  const auto refusal = [&]() {
    auto found = find_project_file(root_ / "repo/src");
    return found ? std::string("(found)") : found.error().message;
  };
  fs::create_directories(here);
  EXPECT_EQ(refusal(), "the project file " + here.string() +
                           " is a directory, not a file: make it the project's xshade.toml or remove it (--no-project "
                           "ignores it)");
  fs::remove(here);
  ASSERT_EQ(::mkfifo(here.c_str(), 0600), 0);
  EXPECT_NE(refusal().find(" is a FIFO, not a file"), std::string::npos);
  fs::remove(here);
  fs::create_symlink(root_ / "repo" / "gone.toml", here);
  EXPECT_NE(refusal().find(" is a symbolic link to nothing, not a file"), std::string::npos);
}

TEST_F(ProjectFileTest, LoadNamesTheFileItCannotRead) {
  auto missing = load_project_file(root_ / "repo/absent.toml");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().to_string(), "the project file " + (root_ / "repo/absent.toml").string() +
                                             " cannot be opened: No such file or directory");
}

// A project file that is a symbolic link out of its folder is refused before it is read; one
// that links to a file inside the folder is read.
TEST_F(ProjectFileTest, ALinkOutOfItsFolderIsRefusedAndOneInsideIsRead) {
  std::ofstream(root_ / "outside/elsewhere.toml") << "scenes = \"xshade/scenes\"\n";
  fs::create_symlink(root_ / "outside/elsewhere.toml", root_ / "repo/xshade.toml");
  auto linked = load_project_file(root_ / "repo/xshade.toml");
  ASSERT_FALSE(linked);
  EXPECT_EQ(linked.error().to_string(),
            (root_ / "repo/xshade.toml").string() +
                ": the project file is a symbolic link that points outside its folder (to " +
                (root_ / "outside/elsewhere.toml").string() + "); a project file must be inside the folder it is for");
  EXPECT_EQ(linked.error().kind, ErrorKind::UserInput);

  fs::remove(root_ / "repo/xshade.toml");
  std::ofstream(root_ / "repo/src/real.toml") << "scenes = \"xshade/scenes\"\n";
  fs::create_symlink(root_ / "repo/src/real.toml", root_ / "repo/xshade.toml");
  auto inside = load_project_file(root_ / "repo/xshade.toml");
  ASSERT_TRUE(inside) << inside.error().to_string();
  EXPECT_EQ(inside->scenes, root_ / "repo/xshade/scenes");
}

}  // namespace
}  // namespace xshade::harness
