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

TEST(DiagnosticEngine, RendersTheLineWithACaretKeepingTabs) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t f = sources.add("c.hlsl", "x\n\tint a = @;\r\n");
  diagnostics.error({f, 2, 10}, "unexpected character '@'");
  EXPECT_EQ(diagnostics.render(0), "c.hlsl:2:10: error: unexpected character '@'\n    \tint a = @;\n    \t        ^");
  EXPECT_EQ(diagnostics.render_all(), diagnostics.render(0) + "\n");
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
