#include "glsl/lower/half_emulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {
namespace half_emulation_test {

// Each function returns one expression whose rounding is asked; frag calls them all.
constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
half other(half a) { return a; }
half sum(half a, half b) { return a + b; }
half negated(half a) { return -a; }
half name(half a) { return a; }
half comma(half a, half b) { return (a, b); }
half increment(half a) { return a++; }
half root(half a) { return sqrt(a); }
half call(half a) { return other(a); }
half same_type(half a) { return half(a); }
half cast(float f) { return (half)f; }
half converted(float f) { return f; }
half2x2 twice_matrix(half2x2 m) { return m + m; }
float wide(float a, float b) { return a + b; }
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(float4 p : SV_Position) : SV_Target {
  half2x2 m = twice_matrix(half2x2(1, 0, 0, 1));
  return float4(sum(1, 2) + negated(1) + name(1) + comma(1, 2) + increment(1) + root(1) + call(1) + same_type(1)
      + cast(p.x) + converted(p.y) + m[0][0], wide(p.x, p.y), 0, 1);
}
)";

// The expression the function `name` returns.
const hlsl::Expr& returned(const hlsl::Module& module, const std::string& name) {
  for (const auto& decl : module.unit.decls) {
    if (!decl || decl->name != name || decl->kind != hlsl::DeclKind::Function) continue;
    const auto& body = static_cast<const hlsl::BlockStmt&>(*static_cast<const hlsl::FunctionDecl&>(*decl).body);
    return *static_cast<const hlsl::ReturnStmt&>(*body.statements.at(0)).value;
  }
  throw std::runtime_error("no function " + name);
}

TEST(HalfEmulation, RoundsEachHalfValueWhereItIsMade) {
  auto module = hlsl::compile_text("half.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const HalfEmulation half(true);
  for (const char* made : {"sum", "negated", "root", "call", "cast", "converted"})
    EXPECT_TRUE(half.rounds_result(returned(*module, made))) << made;
  // Passed on, rounded already: a name, a comma's right side, an increment writing in place, a
  // constructor of its own type; half matrices and float values are not rounded.
  for (const char* passed : {"name", "comma", "increment", "same_type", "twice_matrix", "wide"})
    EXPECT_FALSE(half.rounds_result(returned(*module, passed))) << passed;
  const HalfEmulation off(false);
  EXPECT_FALSE(off.rounds_result(returned(*module, "sum")));
}

// ++ and -- on a half write a new half value: rounded as it is stored, not passed on.
TEST(HalfEmulation, AnIncrementOfAHalfIsRoundedAsItIsStored) {
  auto module = hlsl::compile_text("half.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const auto& increment = static_cast<const hlsl::UnaryExpr&>(returned(*module, "increment"));
  EXPECT_TRUE(HalfEmulation(true).rounds_increment(increment));
  EXPECT_FALSE(HalfEmulation(false).rounds_increment(increment));
  const auto& negated = static_cast<const hlsl::UnaryExpr&>(returned(*module, "negated"));
  EXPECT_FALSE(HalfEmulation(true).rounds_increment(negated));
  EXPECT_TRUE(HalfEmulation(true).rounds_compound_target(hlsl::Type::scalar(hlsl::ScalarType::Half)));
  EXPECT_FALSE(HalfEmulation(true).rounds_compound_target(hlsl::Type::scalar(hlsl::ScalarType::Float)));
}

TEST(HalfEmulation, RoundsHalfScalarsAndVectorsWhenEmulating) {
  const HalfEmulation half(true);
  EXPECT_TRUE(half.rounds(hlsl::Type::scalar(hlsl::ScalarType::Half)));
  EXPECT_TRUE(half.rounds(hlsl::Type::vector(hlsl::ScalarType::Half, 3)));
  EXPECT_FALSE(half.rounds(hlsl::Type::scalar(hlsl::ScalarType::Float)));
  EXPECT_FALSE(HalfEmulation(false).rounds(hlsl::Type::scalar(hlsl::ScalarType::Half)));
  // float -> half rounds; half -> half was rounded when it was made.
  const hlsl::Type half3 = hlsl::Type::vector(hlsl::ScalarType::Half, 3);
  EXPECT_TRUE(half.rounds_conversion(hlsl::Type::vector(hlsl::ScalarType::Float, 3), half3));
  EXPECT_FALSE(half.rounds_conversion(half3, half3));
}

TEST(HalfEmulation, NearestHalfTiesToEvenAndOverflowsAsFp16Does) {
  EXPECT_EQ(nearest_half(2049.0), 2048.0);  // halfway between 2048 and 2050: the even one
  EXPECT_EQ(nearest_half(2051.0), 2052.0);
  EXPECT_EQ(nearest_half(0.1), 0.0999755859375);
  EXPECT_EQ(nearest_half(65519.0), 65504.0);  // the largest half
  EXPECT_TRUE(std::isinf(nearest_half(65520.0)));
  EXPECT_EQ(nearest_half(3e-8), std::ldexp(1.0, -24));  // the smallest subnormal
  EXPECT_TRUE(std::signbit(nearest_half(-1e-9)));       // the sign of zero kept
}

TEST(HalfEmulation, RoundedLiteralsStayConstants) {
  EXPECT_EQ(HalfEmulation::rounded_literal("0.1"), 0.0999755859375f);
  EXPECT_EQ(HalfEmulation::rounded_literal("2049"), 2048.0f);
  EXPECT_FALSE(HalfEmulation::rounded_literal("1e6"));  // no finite half: xs_half gives infinity
  EXPECT_FALSE(HalfEmulation::rounded_literal("x"));
  EXPECT_FALSE(HalfEmulation::rounded_literal("1.0 + x"));
}

}  // namespace half_emulation_test
}  // namespace xshade::glsl::lower
