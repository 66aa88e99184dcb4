#include "harness/live/file_watcher.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class FileWatcherTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "xshade-file-watcher-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    folder_ = pattern;
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name) << text;
    return folder_ / name;
  }
  fs::path folder_;
};

TEST_F(FileWatcherTest, AFileWrittenInPlaceIsReported) {
  const fs::path shader = write("toon.hlsl", "float4 a;");
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher) << watcher.error().to_string();
  ASSERT_TRUE(watcher->watch({shader}));
  write("toon.hlsl", "float4 b;");
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{shader});
}

// Editors save by writing a new file and renaming it over the old one: the watch is on the
// folder, so the file is still watched afterwards.
TEST_F(FileWatcherTest, AFileReplacedByARenameIsReportedEveryTime) {
  const fs::path shader = write("toon.hlsl", "float4 a;");
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  ASSERT_TRUE(watcher->watch({shader}));
  for (int save = 0; save < 2; ++save) {
    const fs::path saved = write(".toon.hlsl.swp", "float4 b;");
    fs::rename(saved, shader);
    EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{shader}) << "save " << save;
  }
}

TEST_F(FileWatcherTest, OtherFilesInTheFolderAreNot) {
  const fs::path shader = write("toon.hlsl", "float4 a;");
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  ASSERT_TRUE(watcher->watch({shader}));
  write("notes.txt", "not read by any scene");
  EXPECT_TRUE(watcher->wait(100ms, 10ms).empty());
}

TEST_F(FileWatcherTest, AFileNotThereYetIsReportedWhenMade) {
  const fs::path include = folder_ / "lighting.hlsl";
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  ASSERT_TRUE(watcher->watch({include}));
  write("lighting.hlsl", "#define X 1");
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{include});
}

TEST_F(FileWatcherTest, WatchOnlyForgetsTheOthers) {
  const fs::path a = write("a.hlsl", "1"), b = write("b.hlsl", "2");
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  ASSERT_TRUE(watcher->watch({a, b}));
  ASSERT_TRUE(watcher->watch_only({b}));
  write("a.hlsl", "3");
  write("b.hlsl", "4");
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{b});
}

TEST_F(FileWatcherTest, NewFilesOfAKindInAFolderAreReported) {
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  ASSERT_TRUE(watcher->watch_new_files(folder_, ".toml"));
  write("notes.txt", "not a scene");
  const fs::path scene = write("new_scene.toml", "width = 8");
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{scene});
  fs::remove(scene);
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{scene});
}

TEST_F(FileWatcherTest, RelativeNamesAreMadeAbsolute) {
  EXPECT_EQ(normal_file_path("a/../b/./c.hlsl"), fs::current_path() / "b/c.hlsl");
}

TEST_F(FileWatcherTest, AFolderThatIsNotThereIsTheUsersMistake) {
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  const auto watched = watcher->watch({folder_ / "missing" / "toon.hlsl"});
  ASSERT_FALSE(watched);
  EXPECT_EQ(watched.error().kind, ErrorKind::UserInput);
  EXPECT_NE(watched.error().message.find("missing"), std::string::npos) << watched.error().message;
}

TEST_F(FileWatcherTest, OneFolderMissingLeavesTheOthersWatched) {
  const fs::path shader = write("toon.hlsl", "float4 a;");
  auto watcher = FileWatcher::make();
  ASSERT_TRUE(watcher);
  EXPECT_FALSE(watcher->watch({folder_ / "missing" / "a.hlsl", shader}));
  write("toon.hlsl", "float4 b;");
  EXPECT_EQ(watcher->wait(2s, 20ms), std::set<fs::path>{shader});
}

}  // namespace
}  // namespace xshade::harness
