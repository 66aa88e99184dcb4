#include "glsl/lower/trace_sites.h"

#include <gtest/gtest.h>

#include <string>

#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {
namespace trace_sites_test {

constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
float4 _Color;
static float gain = 2;
float scaled(float a) { return a * gain; }
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(float4 p : SV_Position) : SV_Target {
  float x = 0;
  float4 c = 0;
  float w[2] = {0, 0};
  int n = 0;
  x = p.x * p.y;
  c.rgb += p.xyz;
  x = pow(p.x, p.y);
  x = scaled(p.x);
  pow(p.x, 2);
  scaled(p.y);
  n = 3;
  w[n - 3] = p.z;
  x = _Color.x + gain;
  return c * x + w[0];
}
)";

// The expression statements of frag, in order.
std::vector<const hlsl::Expr*> statements_of_frag(const hlsl::Module& module) {
  std::vector<const hlsl::Expr*> found;
  const auto& body = static_cast<const hlsl::BlockStmt&>(*module.entry_points.fragment->body);
  for (const auto& stmt : body.statements)
    if (stmt && stmt->kind == hlsl::StmtKind::Expr)
      found.push_back(static_cast<const hlsl::ExprStmt&>(*stmt).expr.get());
  return found;
}

TEST(TraceSites, AssignmentsAndIntrinsicResultsAreSitesOfTheirOwn) {
  auto module = hlsl::compile_text("trace.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const std::vector<const hlsl::Expr*> e = statements_of_frag(*module);
  ASSERT_EQ(e.size(), 9u);

  const std::optional<ExpressionSite> product = expression_site(e[0]);
  ASSERT_TRUE(product);
  EXPECT_EQ(product->kind, TraceSite::Kind::Assignment);
  EXPECT_EQ(product->what, "x");
  const std::optional<ExpressionSite> compound = expression_site(e[1]);
  ASSERT_TRUE(compound);
  EXPECT_EQ(compound->kind, TraceSite::Kind::CompoundAssignment);
  EXPECT_EQ(compound->what, "c.rgb");
  // `x = pow(...)` fails where pow does, and `x = scaled(...)` where scaled returns.
  EXPECT_FALSE(expression_site(e[2]));
  EXPECT_FALSE(expression_site(e[3]));
  const std::optional<ExpressionSite> intrinsic = expression_site(e[4]);
  ASSERT_TRUE(intrinsic);
  EXPECT_EQ(intrinsic->kind, TraceSite::Kind::Call);
  EXPECT_EQ(intrinsic->what, "pow");
  // The author's function is tested at its returns: not a site, but tested.
  EXPECT_FALSE(expression_site(e[5]));
  EXPECT_TRUE(is_tested(e[5]));
  EXPECT_FALSE(expression_site(e[6]));  // an int cannot hold a NaN
  const std::optional<ExpressionSite> element = expression_site(e[7]);
  ASSERT_TRUE(element);
  EXPECT_EQ(element->what, "w[...]");
}

TEST(TraceSites, UniformReadsAreMadeOpaqueStaticsAndLocalsAreNot) {
  auto module = hlsl::compile_text("trace.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const auto& sum = static_cast<const hlsl::BinaryExpr&>(
      *static_cast<const hlsl::AssignExpr&>(*statements_of_frag(*module)[8]).value);
  EXPECT_TRUE(reads_uniform(sum.lhs.get()));   // _Color.x: a member of a uniform
  EXPECT_FALSE(reads_uniform(sum.rhs.get()));  // gain is static
  EXPECT_FALSE(reads_uniform(static_cast<const hlsl::AssignExpr&>(*statements_of_frag(*module)[0]).target.get()));
}

}  // namespace trace_sites_test
}  // namespace xshade::glsl::lower
