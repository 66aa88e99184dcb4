#include "base/paths.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace xshade {
namespace {

namespace fs = std::filesystem;

TEST(PathIsInside, HoldsAPathToItsFolderWithDotDotAndLinksResolved) {
  const fs::path root = fs::temp_directory_path() / "xshade_path_is_inside";
  fs::remove_all(root);
  fs::create_directories(root / "folder/sub");
  fs::create_directories(root / "outside");
  fs::create_symlink(root / "outside", root / "folder/link_out");
  fs::create_symlink(root / "folder/sub", root / "folder/link_in");

  EXPECT_TRUE(path_is_inside(root / "folder/a.hlsl", root / "folder"));
  EXPECT_TRUE(path_is_inside(root / "folder/sub/../b.hlsl", root / "folder"));
  EXPECT_TRUE(path_is_inside(root / "folder/link_in/c.hlsl", root / "folder"));
  EXPECT_TRUE(path_is_inside(root / "folder/not/yet/there.hlsl", root / "folder"));
  EXPECT_FALSE(path_is_inside(root / "folder/../outside/d.hlsl", root / "folder"));
  EXPECT_FALSE(path_is_inside(root / "folder/link_out/e.hlsl", root / "folder"));
  EXPECT_FALSE(path_is_inside(root / "folder", root / "folder"));  // the folder itself names no file in it
  EXPECT_FALSE(path_is_inside(root / "folder_sibling/f.hlsl", root / "folder"));
  EXPECT_FALSE(path_is_inside("/etc/passwd", root / "folder"));
  fs::remove_all(root);
}

// For a path that exists, existing_resolved_path is resolved_path; for one that does not, it
// gives nothing where resolved_path keeps the missing part as written.
TEST(ExistingResolvedPath, IsResolvedPathForAPathThatExists) {
  const fs::path root = fs::temp_directory_path() / "xshade_existing_resolved_path";
  fs::remove_all(root);
  fs::create_directories(root / "folder/sub");
  fs::create_symlink(root / "folder/sub", root / "folder/link");
  for (const fs::path& path : {root / "folder", root / "folder/sub/..", root / "folder/link", root / "folder//sub"})
    EXPECT_EQ(existing_resolved_path(path), resolved_path(path)) << path;
  EXPECT_EQ(existing_resolved_path(root / "folder/link"), resolved_path(root / "folder/sub"));
  EXPECT_FALSE(existing_resolved_path(root / "folder/missing.hlsl"));
  EXPECT_TRUE(resolved_path(root / "folder/missing.hlsl"));
  fs::remove_all(root);
}

// The lexical half decides as lexically_relative does, on its short path (plain names under the
// folder) and off it (dots, empty names, a folder written with a trailing separator).
TEST(PathIsInside, ResolvedPathsAreComparedAsLexicallyRelativeWould) {
  EXPECT_TRUE(resolved_path_is_inside("/a/b/c.hlsl", "/a/b"));
  EXPECT_TRUE(resolved_path_is_inside("/a/b/sub/c.hlsl", "/a/b"));
  EXPECT_TRUE(resolved_path_is_inside("/a/b/.hidden", "/a/b"));
  EXPECT_TRUE(resolved_path_is_inside("/a/b/c.hlsl", "/a/b/"));
  EXPECT_TRUE(resolved_path_is_inside("/a/b//c.hlsl", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/b", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/b/", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/b/.", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/b/..", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/b/../c.hlsl", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/bc/d.hlsl", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("/a/c.hlsl", "/a/b"));
  EXPECT_FALSE(resolved_path_is_inside("a/b/c.hlsl", "/a/b"));
  for (const char* file : {"/a/b/c.hlsl", "/a/b/sub/c.hlsl", "/a/b/.hidden", "/a/b//c.hlsl", "/a/b/", "/a/b/.",
                           "/a/b/../c.hlsl", "/a/bc/d.hlsl", "/x"}) {
    for (const char* folder : {"/a/b", "/a/b/", "/", "/a"}) {
      const fs::path relative = fs::path(file).lexically_relative(folder);
      const bool expected = !relative.empty() && relative != "." && *relative.begin() != "..";
      EXPECT_EQ(resolved_path_is_inside(file, folder), expected) << file << " in " << folder;
    }
  }
}

}  // namespace
}  // namespace xshade
