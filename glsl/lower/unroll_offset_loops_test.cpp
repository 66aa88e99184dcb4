#include "glsl/lower/unroll_offset_loops.h"

#include <gtest/gtest.h>

#include <string>

#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {
namespace {

// The loops unrolled in frag() with `body` as its statements, as their variables' values.
std::vector<std::vector<int64_t>> unrolled_in(const std::string& body) {
  auto module = hlsl::compile_text("loops.hlsl",
                                   "#pragma fragment frag\nTexture2D t;\nSamplerState s;\n"
                                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n  float4 sum = 0;\n" +
                                       body + "\n  return sum;\n}\n",
                                   {});
  if (!module->ok()) {
    ADD_FAILURE() << module->diagnostics.render_all();
    return {};
  }
  std::vector<std::vector<int64_t>> found;
  for (const auto& [loop, values] : unroll_offset_loops({module->entry_points.fragment})) found.push_back(values);
  return found;
}

TEST(UnrollOffsetLoops, ALoopWhoseVariableIsATexelOffsetIsUnrolledToItsValues) {
  EXPECT_EQ(unrolled_in("for (int i = -1; i <= 1; ++i) sum += t.Sample(s, uv, int2(i, 0));"),
            (std::vector<std::vector<int64_t>>{{-1, 0, 1}}));
  // Counting down, by a step of two, bounds from constants.
  EXPECT_EQ(unrolled_in(
                "static const int N = 4;\nfor (int i = N; i > 0; i -= 2) sum += t.SampleLevel(s, uv, 0, int2(0, i));"),
            (std::vector<std::vector<int64_t>>{{4, 2}}));
}

TEST(UnrollOffsetLoops, OtherLoopsStayLoops) {
  // Not an offset: GLSL takes the variable as it is.
  EXPECT_TRUE(unrolled_in("for (int i = 0; i < 4; ++i) sum += t.Sample(s, uv + i);").empty());
  // The body writes the variable, or leaves the loop: its values are not known.
  EXPECT_TRUE(unrolled_in("for (int i = 0; i < 4; ++i) { sum += t.Sample(s, uv, int2(i, 0)); i += 1; }").empty());
  EXPECT_TRUE(
      unrolled_in("for (int i = 0; i < 4; ++i) { sum += t.Sample(s, uv, int2(i, 0)); if (sum.x > 1) break; }").empty());
  // A bound known only when drawing.
  EXPECT_TRUE(
      unrolled_in("int n = int(uv.x * 8);\nfor (int i = 0; i < n; ++i) sum += t.Sample(s, uv, int2(i, 0));").empty());
  // Longer than kMaxUnrolledIterations.
  EXPECT_TRUE(unrolled_in("for (int i = 0; i < 1000; ++i) sum += t.Sample(s, uv, int2(i % 8, 0));").empty());
}

}  // namespace
}  // namespace xshade::glsl::lower
