#include "base/result.h"

#include <gtest/gtest.h>

namespace xshade {
namespace {

TEST(SourceLocation, PrintsAsMuchAsIsKnown) {
  EXPECT_EQ((SourceLocation{"a.hlsl", 3, 7}).to_string(), "a.hlsl:3:7");
  EXPECT_EQ((SourceLocation{"a.hlsl", 3, 0}).to_string(), "a.hlsl:3");
  EXPECT_EQ((SourceLocation{"a.hlsl", 0, 0}).to_string(), "a.hlsl");
  EXPECT_FALSE(SourceLocation{}.known());
}

TEST(Diagnostic, UsesTheCompilerForm) {
  Diagnostic warning{Severity::Warning, {"x.frag", 12, 4}, "implicit truncation"};
  EXPECT_EQ(warning.to_string(), "x.frag:12:4: warning: implicit truncation");
  Diagnostic bare{Severity::Error, {}, "no input"};
  EXPECT_EQ(bare.to_string(), "error: no input");
}

TEST(Error, ListsItsDiagnosticsUnderTheMessage) {
  Error error{"compile failed", {"x.frag", 0, 0}, {{Severity::Error, {"x.frag", 2, 1}, "bad"}}};
  EXPECT_EQ(error.to_string(), "x.frag: compile failed\n  x.frag:2:1: error: bad");
}

TEST(Result, CarriesAValueOrAnError) {
  Result<int> good = 4;
  Result<int> bad = fail(ErrorKind::UserInput, "nope", {"f", 1, 2});
  ASSERT_TRUE(good.has_value());
  EXPECT_EQ(*good, 4);
  ASSERT_FALSE(bad.has_value());
  EXPECT_EQ(bad.error().where.line, 1u);
  EXPECT_EQ(bad.error().message, "nope");
  EXPECT_EQ(bad.error().kind, ErrorKind::UserInput);
}

// Every failure names its kind where it is born: there is no fail() that chooses one for it.
template <class... Arguments>
concept Fails = requires(Arguments... arguments) {
  fail(arguments...);
};
static_assert(!Fails<std::string>);
static_assert(!Fails<std::string, SourceLocation>);
static_assert(Fails<ErrorKind, std::string>);
static_assert(Fails<ErrorKind, std::string, SourceLocation>);
static_assert(Fails<Error>);

TEST(Error, KeepsTheKindItWasGiven) {
  Result<int> lost = fail(ErrorKind::Backend, "device lost");
  ASSERT_FALSE(lost.has_value());
  EXPECT_EQ(lost.error().kind, ErrorKind::Backend);
}

}  // namespace
}  // namespace xshade
