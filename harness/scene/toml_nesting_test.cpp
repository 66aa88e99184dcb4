#include "harness/scene/toml_nesting.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

using ::testing::StartsWith;

// `count` parts joined by dots: a.a.a...
std::string dotted(size_t count, const std::string& part = "a") {
  std::string key = part;
  for (size_t i = 1; i < count; ++i) key += "." + part;
  return key;
}

std::string error_of(const std::string& text) {
  auto checked = check_toml_nesting(text, "f.toml");
  return checked ? std::string("ok") : checked.error().where.to_string() + ": " + checked.error().message;
}

TEST(TomlNesting, AKeyOfTheLimitsPartsPassesAndOneMoreIsRefusedAtItsFirstPart) {
  EXPECT_EQ(error_of(dotted(kMaxTomlNesting) + " = 1\n"), "ok");
  EXPECT_EQ(error_of("x = 1\n  " + dotted(kMaxTomlNesting + 1) + " = 1\n"),
            "f.toml:2:3: a dotted key or table header of 101 parts; xshade reads at most 100 (a longer one could "
            "overflow the TOML parser's stack)");
  // The file that overflowed toml++'s stack: one key of 100,000 parts.
  EXPECT_EQ(error_of(dotted(100000) + " = 1\n"),
            "f.toml:1:1: a dotted key or table header of 100000 parts; xshade reads at most 100 (a longer one could "
            "overflow the TOML parser's stack)");
}

TEST(TomlNesting, TableHeadersQuotedPartsAndSpacesAroundDotsCount) {
  EXPECT_THAT(error_of("[" + dotted(101) + "]\n"),
              StartsWith("f.toml:1:2: a dotted key or table header of 101 parts;"));
  EXPECT_THAT(error_of("[[" + dotted(101) + "]]\n"),
              StartsWith("f.toml:1:3: a dotted key or table header of 101 parts;"));
  EXPECT_THAT(error_of(dotted(101, "\"q\"") + " = 1\n"),
              StartsWith("f.toml:1:1: a dotted key or table header of 101 parts;"));
  EXPECT_THAT(error_of(dotted(101, "'q'") + " = 1\n"),
              StartsWith("f.toml:1:1: a dotted key or table header of 101 parts;"));
  EXPECT_THAT(error_of(dotted(101, " a ") + " = 1\n"),
              StartsWith("f.toml:1:2: a dotted key or table header of 101 parts;"));
  EXPECT_THAT(error_of("t = { " + dotted(101) + " = 1 }\n"),
              StartsWith("f.toml:1:7: a dotted key or table header of 101 parts;"));
}

TEST(TomlNesting, DotsInStringsAndCommentsDoNotCount) {
  const std::string dots(5000, '.');
  EXPECT_EQ(error_of("a = \"" + dots + "\"\n"), "ok");
  EXPECT_EQ(error_of("a = '" + dots + "'\n"), "ok");
  EXPECT_EQ(error_of("\"" + dots + "\" = 1\n"), "ok");
  EXPECT_EQ(error_of("a = \"\"\"\n" + dots + "\n\"" + dots + "\\\"\"\"" + dots + "\"\"\"\n"), "ok");
  EXPECT_EQ(error_of("a = '''\n" + dots + "\n'" + dots + "'''\n"), "ok");
  EXPECT_EQ(error_of("a = 1 # " + dots + "\n"), "ok");
  EXPECT_EQ(error_of("a = \"x\\\"" + dots + "\"\n"), "ok");  // an escaped quote does not end the string
  // Up to two quotes before the closing three belong to the string; the key after it counts.
  EXPECT_THAT(error_of("a = \"\"\"x\"\"\"\"\"\n" + dotted(101) + " = 1\n"), StartsWith("f.toml:2:1: a dot"));
  // An unclosed one-line string ends with its line, so that the next line is still checked.
  EXPECT_THAT(error_of("a = \"" + dots + "\n" + dotted(101) + " = 1\n"), StartsWith("f.toml:2:1: a dot"));
}

TEST(TomlNesting, ValuesSeparatedByCommasAreNotOneKey) {
  std::string floats = "a = [";
  for (int i = 0; i < 1000; ++i) floats += "1.5, ";
  EXPECT_EQ(error_of(floats + "2.5]\n"), "ok");
  EXPECT_EQ(error_of("d = 1979-05-27T07:32:00.999999-07:00\n"), "ok");
}

TEST(TomlNesting, ArraysAndInlineTablesNestAtMostTheLimit) {
  EXPECT_EQ(error_of("a = " + std::string(kMaxTomlNesting, '[') + std::string(kMaxTomlNesting, ']') + "\n"), "ok");
  EXPECT_EQ(error_of("a = " + std::string(kMaxTomlNesting + 1, '[')),
            "f.toml:1:105: arrays, inline tables and table headers nest more than 100 deep here; xshade reads at most "
            "100 levels (a deeper file could overflow the TOML parser's stack)");
  std::string tables = "a = ";
  for (size_t i = 0; i <= kMaxTomlNesting; ++i) tables += "{ b = ";
  EXPECT_THAT(error_of(tables), StartsWith("f.toml:1:605: arrays, in"));
  // Many arrays one after the other are not nested.
  std::string siblings = "a = [";
  for (int i = 0; i < 1000; ++i) siblings += "[1], ";
  EXPECT_EQ(error_of(siblings + "[2]]\n"), "ok");
  // Brackets in strings do not count.
  EXPECT_EQ(error_of("a = \"" + std::string(1000, '[') + "\"\n"), "ok");
}

TEST(TomlNesting, ColumnsCountCodePointsAsToml) {
  // "é" is two bytes and one column.
  EXPECT_THAT(error_of("\"é\" = 1\n" + std::string("\"é\".") + dotted(100) + " = 1\n"), StartsWith("f.toml:2:1: "));
  EXPECT_THAT(error_of("x = \"é\" \n" + std::string(" ") + dotted(101)), StartsWith("f.toml:2:2: "));
  EXPECT_THAT(error_of("é = [" + std::string(kMaxTomlNesting + 1, '[')), StartsWith("f.toml:1:105"));
}

}  // namespace
}  // namespace xshade::harness
