#include "harness/render/shader_search_path.h"

#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

class ShaderSearchPathTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A folder per test: CTest runs the cases of this fixture in parallel.
    root_ = fs::temp_directory_path() / ("xshade_shader_search_path_test_" +
                                         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(root_);
    for (const char* folder : {"user/materials", "library/materials", "library/post", "secret"})
      fs::create_directories(root_ / folder);
    write("user/materials/velvet.hlsl");
    write("user/materials/toon.hlsl");
    write("library/materials/toon.hlsl");
    write("library/materials/standard_pbr.hlsl");
    write("library/post/depth_of_field.hlsl");
    write("library/materials/notes.txt");
    write("secret/key.hlsl");
  }
  void TearDown() override { fs::remove_all(root_); }

  void write(const std::string& relative) { std::ofstream(root_ / relative) << "// " << relative << "\n"; }
  ShaderSearchPath path() const { return ShaderSearchPath({root_ / "user", root_ / "library"}); }

  fs::path root_;
};

TEST_F(ShaderSearchPathTest, TheFirstFolderThatHasTheFileSuppliesIt) {
  auto toon = path().find("materials/toon.hlsl");
  ASSERT_TRUE(toon) << toon.error().to_string();
  EXPECT_EQ(*toon, root_ / "user/materials/toon.hlsl");
  auto pbr = path().find("materials/standard_pbr.hlsl");
  ASSERT_TRUE(pbr) << pbr.error().to_string();
  EXPECT_EQ(*pbr, root_ / "library/materials/standard_pbr.hlsl");
}

// Where a file made later would be found instead: each place looked, up to the one that has it.
TEST_F(ShaderSearchPathTest, ItSaysWhereItLooked) {
  std::vector<fs::path> looked_in;
  ASSERT_TRUE(path().find("materials/standard_pbr.hlsl", &looked_in));
  EXPECT_EQ(looked_in, (std::vector<fs::path>{root_ / "user/materials/standard_pbr.hlsl",
                                              root_ / "library/materials/standard_pbr.hlsl"}));
  looked_in.clear();
  ASSERT_TRUE(path().find("materials/toon.hlsl", &looked_in));
  EXPECT_EQ(looked_in, std::vector<fs::path>{root_ / "user/materials/toon.hlsl"});
  looked_in.clear();
  ASSERT_FALSE(path().find("../secret/key.hlsl", &looked_in));
  EXPECT_TRUE(looked_in.empty());
}

TEST_F(ShaderSearchPathTest, AFileInNoFolderNamesEveryFolder) {
  auto missing = path().find("materials/silk.hlsl");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message, "'materials/silk.hlsl' is in none of the shader folders (" +
                                         (root_ / "user").string() + ", " + (root_ / "library").string() + ")");
}

TEST_F(ShaderSearchPathTest, APathOutOfTheFoldersIsRefusedBeforeItIsRead) {
  for (const std::string escaping : {"../secret/key.hlsl", "materials/../../secret/key.hlsl", "/etc/passwd"}) {
    auto found = path().find(escaping);
    ASSERT_FALSE(found) << escaping;
    EXPECT_NE(found.error().message.find("is not a path inside the shader folders"), std::string::npos)
        << found.error().message;
  }
  fs::create_symlink(root_ / "secret/key.hlsl", root_ / "user/materials/linked.hlsl");
  auto linked = path().find("materials/linked.hlsl");
  ASSERT_FALSE(linked);
  EXPECT_NE(linked.error().message.find("is a link that leads out of that folder"), std::string::npos)
      << linked.error().message;
}

TEST_F(ShaderSearchPathTest, FilesListsEachHlslFileOnceAcrossFolders) {
  EXPECT_EQ(path().files("materials"),
            (std::vector<std::string>{"materials/standard_pbr.hlsl", "materials/toon.hlsl", "materials/velvet.hlsl"}));
  EXPECT_EQ(path().files("post"), std::vector<std::string>{"post/depth_of_field.hlsl"});
  EXPECT_TRUE(path().files("compute").empty());
}

}  // namespace
}  // namespace xshade::harness
