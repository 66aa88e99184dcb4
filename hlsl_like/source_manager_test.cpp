#include "hlsl_like/source_manager.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

namespace xshade::hlsl {
namespace {

namespace fs = std::filesystem;

TEST(SourceManager, AddedFilesAreNumberedFromOne) {
  SourceManager sources;
  EXPECT_EQ(sources.file_count(), 1u);  // index 0 is "no file"
  const uint32_t a = sources.add("a.hlsl", "x");
  const uint32_t b = sources.add("b.hlsl", "y");
  EXPECT_EQ(a, 1u);
  EXPECT_EQ(b, 2u);
  EXPECT_EQ(sources.name(b), "b.hlsl");
  EXPECT_EQ(sources.text(a), "x");
  EXPECT_TRUE(sources.path(a).empty());
}

TEST(SourceManager, LineTextHandlesLineEndingsAndRanges) {
  SourceManager sources;
  const uint32_t f = sources.add("l.hlsl", "one\r\ntwo\n\nlast");
  EXPECT_EQ(sources.line_text(f, 1), "one");
  EXPECT_EQ(sources.line_text(f, 2), "two");
  EXPECT_EQ(sources.line_text(f, 3), "");
  EXPECT_EQ(sources.line_text(f, 4), "last");
  EXPECT_EQ(sources.line_text(f, 5), "");
  EXPECT_EQ(sources.line_text(f, 0), "");
  EXPECT_EQ(sources.line_text(0, 1), "");
  EXPECT_EQ(sources.line_text(99, 1), "");
}

TEST(SourceManager, ResolveGivesThePrintableLocation) {
  SourceManager sources;
  const uint32_t f = sources.add("r.hlsl", "");
  EXPECT_EQ(sources.resolve(Loc{f, 3, 7}).to_string(), "r.hlsl:3:7");
  EXPECT_FALSE(sources.resolve(Loc{}).known());
  EXPECT_FALSE(sources.resolve(Loc{42, 1, 1}).known());
}

TEST(SourceManager, LoadReadsAFileOnceByCanonicalPath) {
  std::random_device random;
  const fs::path dir = fs::temp_directory_path() / ("xshade_sm_test_" + std::to_string(random()));
  fs::create_directories(dir / "sub");
  std::ofstream(dir / "f.hlsl", std::ios::binary) << "text\r\n";
  SourceManager sources;
  Result<uint32_t> first = sources.load(dir / "f.hlsl");
  Result<uint32_t> again = sources.load(dir / "sub" / ".." / "f.hlsl");
  ASSERT_TRUE(first.has_value());
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(*first, *again);
  EXPECT_EQ(sources.text(*first), "text\r\n");
  EXPECT_EQ(sources.path(*first), fs::weakly_canonical(dir / "f.hlsl"));
  Result<uint32_t> missing = sources.load(dir / "missing.hlsl");
  ASSERT_FALSE(missing.has_value());
  EXPECT_EQ(missing.error().message, "cannot open '" + (dir / "missing.hlsl").string() + "'");
  Result<uint32_t> folder = sources.load(dir / "sub");
  ASSERT_FALSE(folder.has_value());
  EXPECT_EQ(folder.error().message, "'" + (dir / "sub").string() + "' is a directory");
  std::error_code error;
  fs::remove_all(dir, error);
}

}  // namespace
}  // namespace xshade::hlsl
