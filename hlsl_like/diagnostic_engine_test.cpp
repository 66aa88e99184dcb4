#include "hlsl_like/diagnostic_engine.h"

#include <gtest/gtest.h>

#include <string>

namespace xshade::hlsl {
namespace {

TEST(DiagnosticEngine, CountsAndKeepsTheOrder) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t f = sources.add("d.hlsl", "a\nb\n");
  diagnostics.warning({f, 1, 1}, "first");
  diagnostics.error({f, 2, 1}, "second");
  diagnostics.note({}, "third");
  EXPECT_EQ(diagnostics.warning_count(), 1u);
  EXPECT_EQ(diagnostics.error_count(), 1u);
  EXPECT_TRUE(diagnostics.has_errors());
  ASSERT_EQ(diagnostics.diagnostics().size(), 3u);
  EXPECT_EQ(diagnostics.diagnostics()[0].to_string(), "d.hlsl:1:1: warning: first");
  EXPECT_EQ(diagnostics.diagnostics()[2].to_string(), "note: third");
}

TEST(DiagnosticEngine, RendersTheLineWithACaretExpandingTabs) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  // The tab is column 1; 'i' is column 2 and shows at the first tab stop (8); '@' is column 10,
  // 8 bytes after 'i', so it shows 16 places in.
  const uint32_t f = sources.add("c.hlsl", "x\n\tint a = @;\r\n  \tb\n");
  diagnostics.error({f, 2, 10}, "unexpected character '@'");
  EXPECT_EQ(diagnostics.render(0),
            "c.hlsl:2:10: error: unexpected character '@'\n"
            "            int a = @;\n"
            "                    ^");
  EXPECT_EQ(diagnostics.render_all(), diagnostics.render(0) + "\n");
  // A tab after two spaces still ends at the tab stop: 'b' shows 8 places in, not 10.
  diagnostics.error({f, 3, 4}, "here");
  EXPECT_EQ(diagnostics.render(1),
            "c.hlsl:3:4: error: here\n"
            "            b\n"
            "            ^");
}

TEST(DiagnosticEngine, ControlBytesAreEscapedAndTheCaretFollows) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  // NUL, ESC and 0xFF each show as four characters (\x00, \x1B, \xFF): 'z' at column 5 follows
  // "a" and three escapes, 1 + 3 * 4 = 13 places in.
  const uint32_t f = sources.add("e.hlsl", std::string("a\0\x1b\xffz\n", 6));
  diagnostics.error({f, 1, 5}, "z");
  EXPECT_EQ(diagnostics.render(0),
            "e.hlsl:1:5: error: z\n"
            "    a\\x00\\x1B\\xFFz\n"
            "                 ^");
  // Pointing at an escaped byte puts the caret under its backslash.
  diagnostics.error({f, 1, 3}, "escape");
  EXPECT_EQ(diagnostics.render(1),
            "e.hlsl:1:3: error: escape\n"
            "    a\\x00\\x1B\\xFFz\n"
            "         ^");
}

TEST(DiagnosticEngine, ACaretPastTheEndOfTheLineSitsJustAfterIt) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t f = sources.add("s.hlsl", "int x = 1\n");
  diagnostics.error({f, 1, 10}, "expected ';'");
  EXPECT_EQ(diagnostics.render(0),
            "s.hlsl:1:10: error: expected ';'\n"
            "    int x = 1\n"
            "             ^");
}

TEST(DiagnosticEngine, QuotedTextIsClippedAndEscaped) {
  EXPECT_EQ(in_quotes("_Color"), "'_Color'");
  EXPECT_EQ(in_quotes(""), "''");
  EXPECT_EQ(in_quotes(std::string("a\0\n\x7f\x80", 5)), "'a\\x00\\x0A\\x7F\\x80'");
  // Exactly kMaxQuotedLength characters are shown whole; one more is cut with "...".
  const std::string limit(kMaxQuotedLength, 'n');
  EXPECT_EQ(in_quotes(limit), "'" + limit + "'");
  EXPECT_EQ(in_quotes(limit + "m"), "'" + limit + "...'");
  EXPECT_EQ(in_quotes(std::string(size_t(1) << 20, 'n')), "'" + limit + "...'");
}

TEST(DiagnosticEngine, LongLinesAreShownAroundTheColumn) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  std::string line(100000, 'a');
  line[50000] = '@';
  const uint32_t f = sources.add("long.hlsl", line);
  diagnostics.error({f, 1, 50001}, "here");
  const std::string text = diagnostics.render(0);
  EXPECT_LT(text.size(), 400u);
  const size_t excerpt = text.find("\n    ...");
  ASSERT_NE(excerpt, std::string::npos);
  const size_t caret_line = text.find('\n', excerpt + 1);
  const size_t at = text.find('@');
  const size_t caret = text.find('^');
  ASSERT_NE(caret, std::string::npos);
  EXPECT_EQ(caret - caret_line, at - excerpt);  // the caret sits under the '@'
}

TEST(DiagnosticEngine, StopsAfterTheErrorLimit) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  for (int i = 0; i < 200; ++i) diagnostics.error({}, "e" + std::to_string(i));
  EXPECT_EQ(diagnostics.error_count(), DiagnosticEngine::kErrorLimit);
  ASSERT_EQ(diagnostics.diagnostics().size(), DiagnosticEngine::kErrorLimit + 1);
  EXPECT_EQ(diagnostics.diagnostics().back().to_string(), "note: too many errors; stopping here");
  diagnostics.warning({}, "warnings still count");
  EXPECT_EQ(diagnostics.warning_count(), 1u);
}

}  // namespace
}  // namespace xshade::hlsl
