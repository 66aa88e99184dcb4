#include "spirv/glslang_log.h"

#include <gtest/gtest.h>

namespace xshade::spirv {
namespace {

TEST(GlslangLog, ErrorLinesBecomeLocatedDiagnostics) {
  auto diagnostics = parse_glslang_log(
      "ERROR: shaders/a.frag:12: 'x' : undeclared identifier \n"
      "WARNING: shaders/a.frag:3: '#extension' : extension not supported\n"
      "ERROR: 2 compilation errors.  No code generated.\n");
  ASSERT_EQ(diagnostics.size(), 3u);
  EXPECT_EQ(diagnostics[0].severity, Severity::Error);
  EXPECT_EQ(diagnostics[0].where.file, "shaders/a.frag");
  EXPECT_EQ(diagnostics[0].where.line, 12u);
  EXPECT_EQ(diagnostics[0].message, "'x' : undeclared identifier ");
  EXPECT_EQ(diagnostics[1].severity, Severity::Warning);
  EXPECT_EQ(diagnostics[1].where.line, 3u);
  // The summary has no location and keeps its text.
  EXPECT_FALSE(diagnostics[2].where.known());
  EXPECT_EQ(diagnostics[2].message, "2 compilation errors.  No code generated.");
}

TEST(GlslangLog, NamesMayContainColons) {
  auto diagnostics = parse_glslang_log("ERROR: C:/x/y.frag:7: 'a' : b\n");
  ASSERT_EQ(diagnostics.size(), 1u);
  EXPECT_EQ(diagnostics[0].where.file, "C:/x/y.frag");
  EXPECT_EQ(diagnostics[0].where.line, 7u);
}

TEST(GlslangLog, IgnoresLinesThatAreNotMessages) { EXPECT_TRUE(parse_glslang_log("\n\nshaders/a.frag\n").empty()); }

}  // namespace
}  // namespace xshade::spirv
