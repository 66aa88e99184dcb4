#include "base/string_index.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace xshade {
namespace {

TEST(StringIndex, NumbersStringsInTheOrderTheyWereAddedAndFindsThemByTheirText) {
  StringIndex index;
  EXPECT_EQ(index.insert("float4"), std::make_pair(0u, true));
  EXPECT_EQ(index.insert(""), std::make_pair(1u, true));  // the empty name is a name like any other
  EXPECT_EQ(index.insert("float"), std::make_pair(2u, true));
  const std::string copy = "float4";  // other memory, the same text
  EXPECT_EQ(index.insert(copy), std::make_pair(0u, false));
  EXPECT_EQ(index.find("float"), 2u);
  EXPECT_EQ(index.find(""), 1u);
  EXPECT_EQ(index.find("float3"), StringIndex::kAbsent);
  EXPECT_EQ(index.size(), 3u);
}

TEST(StringIndex, KeepsEveryNumberAsTheTableGrows) {
  // Names that share their length and their first and last characters, which the hash's short
  // loads overlap on, and far more of them than the table starts with.
  std::vector<std::string> names;
  for (int i = 0; i < 5000; ++i) names.push_back("n" + std::to_string(i) + "_x");
  StringIndex index(4);
  for (size_t i = 0; i < names.size(); ++i) ASSERT_EQ(index.insert(names[i]), std::make_pair(uint32_t(i), true));
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(index.find(names[i]), uint32_t(i)) << names[i];
  EXPECT_EQ(index.find("n5000_x"), StringIndex::kAbsent);
}

}  // namespace
}  // namespace xshade
