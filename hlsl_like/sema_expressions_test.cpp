// Semantic analysis of expressions, one test per rule: the intrinsic table, names, conversions,
// operators, assignment, initializer lists and members.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/intrinsics.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/sema.h"
#include "hlsl_like/sema_internal.h"
#include "hlsl_like/sema_test_support.h"

namespace xshade::hlsl::sema_test {
namespace {

// ---------------------------------------------------------------------------------------------
// Intrinsic table

TEST(IntrinsicTable, EveryIntrinsicHasANameAndSignatures) {
  for (uint16_t id = 1;; ++id) {
    const IntrinsicInfo& info = intrinsic_info(IntrinsicId(id));
    if (info.id == IntrinsicId::None) break;
    EXPECT_EQ(info.id, IntrinsicId(id));
    EXPECT_EQ(info.name, intrinsic_name(IntrinsicId(id)));
    if (info.id == IntrinsicId::BufferMethod) continue;  // no name of its own: any buffer method
    EXPECT_FALSE(info.name.empty());
    // Texture methods take their signatures from the texture (sema_methods.cpp).
    EXPECT_EQ(info.signatures.empty(), info.is_method) << info.name;
    // Sema ranks an intrinsic's candidates in arrays of this size.
    EXPECT_LE(info.signatures.size(), sema_detail::kMaxIntrinsicSignatures) << info.name;
    for (const IntrinsicSignature& signature : info.signatures) {
      EXPECT_LE(signature.param_count, 4) << info.name;
      EXPECT_NE(signature.elements, 0) << info.name;
    }
    const std::optional<IntrinsicId> found =
        info.is_method ? find_texture_method(info.name) : find_intrinsic(info.name);
    EXPECT_EQ(found, IntrinsicId(id)) << info.name;
  }
}

TEST(IntrinsicTable, FunctionsAndMethodsAreLookedUpApart) {
  EXPECT_EQ(find_intrinsic("lerp"), IntrinsicId::Lerp);
  EXPECT_EQ(find_intrinsic("tex2D"), IntrinsicId::Tex2D);
  EXPECT_EQ(find_intrinsic("Sample"), std::nullopt);
  EXPECT_EQ(find_intrinsic("Lerp"), std::nullopt);  // case matters
  EXPECT_EQ(find_texture_method("Sample"), IntrinsicId::Sample);
  EXPECT_EQ(find_texture_method("GetDimensions"), IntrinsicId::GetDimensions);
  EXPECT_EQ(find_texture_method("lerp"), std::nullopt);
  EXPECT_EQ(intrinsic_name(IntrinsicId::Mul), "mul");
  EXPECT_EQ(intrinsic_name(IntrinsicId::None), "");
  EXPECT_TRUE(intrinsic_info(IntrinsicId::Ddx).fragment_only);
  EXPECT_FALSE(intrinsic_info(IntrinsicId::SampleLevel).fragment_only);
  EXPECT_EQ(intrinsic_info(IntrinsicId::Mul).signatures.size(), 9u);
}

TEST(IntrinsicTable, SincosHasTwoOutParameters) {
  const IntrinsicInfo& info = intrinsic_info(IntrinsicId::Sincos);
  ASSERT_EQ(info.signatures.size(), 1u);
  const IntrinsicSignature& signature = info.signatures[0];
  ASSERT_EQ(signature.param_count, 3);
  EXPECT_FALSE(signature.params[0].out);
  EXPECT_TRUE(signature.params[1].out);
  EXPECT_TRUE(signature.params[2].out);
  EXPECT_EQ(signature.result.shape, PatternShape::Void);
}

// ---------------------------------------------------------------------------------------------
// Names and scopes

TEST(SemaNames, UnknownNameIsAnErrorAndSilencesTheRest) {
  EXPECT_EQ(messages_of("void t() {\n  float3 x = foo * 2 + 1;\n}\n"), (Strings{"2:14: error: unknown name 'foo'"}));
}

TEST(SemaNames, UnknownNameSuggestsACloseOne) {
  EXPECT_EQ(messages_of("float color;\nfloat t() { return colr; }\n"),
            (Strings{"2:20: error: unknown name 'colr'; did you mean 'color'?"}));
}

TEST(SemaNames, RedefinitionInTheSameScopeHasANote) {
  EXPECT_EQ(messages_of("void t() {\n  float x = 1;\n  int x = 2;\n}\n"),
            (Strings{"3:7: error: redefinition of 'x'", "2:9: note: previous definition of 'x' is here"}));
  EXPECT_EQ(messages_of("float g;\nvoid g() {}\n"),
            (Strings{"2:6: error: redefinition of 'g'", "1:7: note: previous definition of 'g' is here"}));
}

TEST(SemaNames, InnerScopesMayShadow) {
  auto a = analyze_source("float x;\nvoid t(float y) {\n  float x = y;\n  { int x = 1; x = 2; }\n}\n");
  EXPECT_EQ(a->messages(), Strings{});
}

TEST(SemaNames, ForInitVariablesEndWithTheLoop) {
  EXPECT_EQ(messages_of("void t() {\n  for (int i = 0; i < 4; i++) {}\n  i = 1;\n}\n"),
            (Strings{"3:3: error: unknown name 'i'"}));
}

TEST(SemaNames, NamesPointAtTheirDeclarations) {
  auto a =
      analyze_source("cbuffer C { float4 tint; };\nstatic float k = 2;\nfloat4 t(float s) { return tint * s * k; }\n");
  ASSERT_EQ(a->messages(), Strings{});
  const Expr& ret = a->expression("t", 0);
  ASSERT_EQ(ret.kind, ExprKind::Binary);
  const auto& outer = static_cast<const BinaryExpr&>(ret);
  const auto& inner = static_cast<const BinaryExpr&>(*outer.lhs);
  const auto& tint = static_cast<const NameExpr&>(*inner.lhs);
  ASSERT_NE(tint.decl, nullptr);
  EXPECT_EQ(tint.decl->kind, DeclKind::Var);
  EXPECT_EQ(tint.type.name(), "float4");
  const auto& s = static_cast<const ConversionExpr&>(*inner.rhs);  // splat to float4
  EXPECT_EQ(static_cast<const NameExpr&>(*s.operand).decl, a->function("t").params[0].get());
}

TEST(SemaNames, TypesAndFunctionsAreNotValues) {
  EXPECT_EQ(messages_of("struct S { float a; };\nfloat f() { return 1; }\nvoid t() { float x = f; }\n"),
            (Strings{"3:22: error: 'f' is a function, not a value"}));
}

// ---------------------------------------------------------------------------------------------
// Conversions

TEST(SemaConversions, ScalarSplatsWithAConversionNode) {
  auto a = analyze_source("void t() { float3 v = 1.5; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  const Expr& init = a->expression("t", 0);
  EXPECT_EQ(dump(&init), "(to float3 1.5)");
  EXPECT_EQ(init.type.name(), "float3");
  // The literal itself is untouched.
  EXPECT_EQ(static_cast<const ConversionExpr&>(init).operand->type.name(), "float");
}

TEST(SemaConversions, VectorTruncationWarns) {
  auto a = analyze_source("void t(float4 a) {\n  float3 b = a;\n  float c = a;\n}\n");
  EXPECT_EQ(a->messages(), (Strings{"2:14: warning: implicit truncation of vector type from 'float4' to 'float3'",
                                    "3:13: warning: implicit truncation of vector type from 'float4' to 'float'"}));
  EXPECT_EQ(dump(&a->expression("t", 0)), "(to float3 a)");
}

TEST(SemaConversions, MatrixTruncationWarns) {
  EXPECT_EQ(messages_of("void t(float4x4 m) { float3x3 n = m; }\n"),
            (Strings{"1:35: warning: implicit truncation of matrix type from 'float4x4' to 'float3x3'"}));
}

TEST(SemaConversions, OneComponentVectorsAndScalarsConvertFreely) {
  EXPECT_EQ(messages_of("void t(float1 a, float b) { float c = a; float1 d = b; float3 e = a; }\n"), Strings{});
}

TEST(SemaConversions, ScalarTypesChangePerComponent) {
  auto a = analyze_source("void t(int3 i, bool b) { float3 f = i; half h = b; uint u = -1; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(dump(&a->expression("t", 0)), "(to float3 i)");
  EXPECT_EQ(dump(&a->expression("t", 1)), "(to half b)");
  EXPECT_EQ(dump(&a->expression("t", 2)), "(to uint (- 1))");
}

TEST(SemaConversions, WideningAVectorIsAnError) {
  EXPECT_EQ(messages_of("void t(float2 a) {\n  float3 b = a;\n}\n"),
            (Strings{"2:14: error: cannot convert from 'float2' to 'float3'"}));
}

TEST(SemaConversions, StructsAndResourcesDoNotConvert) {
  EXPECT_EQ(
      messages_of("struct A { float x; };\nstruct B { float x; };\nvoid t(A a) { B b = a; float f = a; }\n"),
      (Strings{"3:21: error: cannot convert from 'A' to 'B'", "3:34: error: cannot convert from 'A' to 'float'"}));
  EXPECT_EQ(messages_of("Texture2D tex;\nvoid t() { float4 f = tex; }\n"),
            (Strings{"2:23: error: cannot convert from 'Texture2D' to 'float4'"}));
}

TEST(SemaConversions, ExplicitCastsTruncateSilently) {
  Probe p = probe("float4 v; float4x4 m;", "(float3)v");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(type_of("float4x4 m;", "(float3x3)m"), "float3x3");
  EXPECT_EQ(type_of("float4 v;", "(float)v"), "float");
  EXPECT_EQ(type_of("float4 v;", "(int4)v"), "int4");
  EXPECT_EQ(probe("float2 v;", "(float3)v").messages,
            (Strings{"2:12: error: cannot convert from 'float2' to 'float3'"}));
}

TEST(SemaConversions, CastingZeroToAStructZeroInitializesIt) {
  EXPECT_EQ(messages_of("struct V { float4 pos; float2 uv[2]; };\nV t() { V o = (V)0; return o; }\n"), Strings{});
  EXPECT_EQ(messages_of("struct V { float4 pos; };\nvoid t(float x) { V o = (V)x; }\n"),
            (Strings{"2:25: error: cannot convert from 'float' to 'V'"}));
}

// ---------------------------------------------------------------------------------------------
// Binary and unary operators

TEST(SemaOperators, ArithmeticTakesTheHigherScalarType) {
  const std::string g = "int i; uint u; half h; float f; bool b; half3 h3;";
  EXPECT_EQ(type_of(g, "i + f"), "float");
  EXPECT_EQ(type_of(g, "i + u"), "uint");
  EXPECT_EQ(type_of(g, "h * f"), "float");
  EXPECT_EQ(type_of(g, "b + b"), "int");
  EXPECT_EQ(type_of(g, "i * 2"), "int");
  EXPECT_EQ(type_of(g, "i * 2.0"), "float");
  // A float literal takes a half operand's type, as DXC's literal types do.
  EXPECT_EQ(type_of(g, "h * 2.0"), "half");
  EXPECT_EQ(type_of(g, "h3 * -0.5"), "half3");
  EXPECT_EQ(type_of(g, "h * 2.0h"), "half");
  EXPECT_EQ(type_of(g, "f % 2.0"), "float");
}

TEST(SemaOperators, BothOperandsConvertToTheResultType) {
  Probe p = probe("int i; float3 v;", "v * i");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(p.tree, "(* v (to float3 i))");
  EXPECT_EQ(probe("bool b;", "b + b").tree, "(+ (to int b) (to int b))");
}

TEST(SemaOperators, VectorsOfDifferentLengthsTruncateToTheShorter) {
  Probe p = probe("float4 a; float3 b;", "a + b");
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(p.tree, "(+ (to float3 a) b)");
  EXPECT_EQ(p.messages, (Strings{"2:12: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
}

TEST(SemaOperators, MatrixTimesMatrixIsComponentWise) {
  Probe p = probe("float4x4 a; float4x4 b;", "a * b");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float4x4");
  EXPECT_EQ(p.tree, "(* a b)");
  Probe q = probe("float4x4 a; float3x3 b;", "a + b");
  EXPECT_EQ(q.type, "float3x3");
  EXPECT_EQ(q.messages, (Strings{"2:12: warning: implicit truncation of matrix type from 'float4x4' to 'float3x3'"}));
}

TEST(SemaOperators, VectorTimesMatrixNeedsMul) {
  EXPECT_EQ(probe("float4 v; float4x4 m;", "v * m").messages,
            (Strings{"2:14: error: cannot apply '*' to 'float4' and 'float4x4'; use mul()"}));
  EXPECT_EQ(probe("float4 v; float4x4 m;", "m + v").messages,
            (Strings{"2:14: error: cannot apply '+' to 'float4x4' and 'float4'"}));
}

TEST(SemaOperators, BitwiseOperatorsNeedIntegers) {
  EXPECT_EQ(type_of("int i; uint u;", "i & u"), "uint");
  EXPECT_EQ(type_of("uint2 u;", "u << 2"), "uint2");
  EXPECT_EQ(probe("float f; int i;", "f & i").messages,
            (Strings{"2:14: error: '&' needs integer operands, not 'float'"}));
  EXPECT_EQ(probe("float f;", "~f").messages, (Strings{"2:12: error: '~' needs integer operands, not 'float'"}));
}

TEST(SemaOperators, ComparisonsAndLogicGiveBools) {
  Probe p = probe("float3 a; int b;", "a < b");
  EXPECT_EQ(p.type, "bool3");
  EXPECT_EQ(p.tree, "(< a (to float3 b))");
  EXPECT_EQ(type_of("float3 a; float b;", "a && b"), "bool3");
  EXPECT_EQ(probe("float3 a; float b;", "a && b").tree, "(&& (to bool3 a) (to bool3 b))");
  EXPECT_EQ(type_of("float a; float b;", "!a || b"), "bool");
  EXPECT_EQ(type_of("float3 a;", "!a"), "bool3");
  EXPECT_EQ(type_of("float3 a;", "a, 1"), "int");
}

TEST(SemaOperators, UnaryOperators) {
  EXPECT_EQ(type_of("bool b;", "-b"), "int");
  EXPECT_EQ(type_of("uint2 u;", "~u"), "uint2");
  EXPECT_EQ(type_of("", "float2 v; v++"), "float2");
  EXPECT_EQ(probe("struct S { float a; }; S s;", "-s").messages, (Strings{"2:12: error: cannot apply '-' to 'S'"}));
}

TEST(SemaOperators, ConditionalTakesTheCommonType) {
  Probe p = probe("bool c; int i; float f;", "c ? i : f");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float");
  EXPECT_EQ(p.tree, "(? c (to float i) f)");
  EXPECT_EQ(probe("int c; float f;", "c ? f : f").tree, "(? (to bool c) f f)");
}

TEST(SemaOperators, ConditionalWithAVectorConditionIsComponentWise) {
  Probe p = probe("bool3 c;", "c ? 1.0 : 0.0");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(p.tree, "(? c (to float3 1.0) (to float3 0.0))");
  Probe q = probe("float3 x;", "x > 0 ? x : -x");
  EXPECT_EQ(q.type, "float3");
  EXPECT_EQ(q.tree, "(? (> x (to float3 0)) x (- x))");
  Probe r = probe("float4 x; float y;", "x ? y : 0");
  EXPECT_EQ(r.type, "float4");
  EXPECT_EQ(r.tree, "(? (to bool4 x) (to float4 y) (to float4 0))");
}

TEST(SemaOperators, ConditionsMustBeScalar) {
  EXPECT_EQ(messages_of("void t(float3 v) {\n  if (v > 0) {}\n}\n"),
            (Strings{"2:9: error: condition must be a scalar, not 'bool3'; use any() or all()"}));
  auto a = analyze_source(
      "void t(int n, float x) { while (n) { n--; } if (x) {} do {} while (false); for (;;) { break; } }");
  EXPECT_EQ(a->messages(), Strings{});
  const auto& loop = static_cast<const WhileStmt&>(a->statement("t", 0));
  EXPECT_EQ(dump(loop.condition.get()), "(to bool n)");
}

// ---------------------------------------------------------------------------------------------
// L-values and assignment

TEST(SemaAssign, UniformsAndConstantsAreReadOnly) {
  const std::string source =
      "float4 g;\n"
      "cbuffer C { float4 tint; };\n"
      "static const float k = 1;\n"
      "static float s;\n"
      "void t(float p, uniform float u) {\n"
      "  g = 1;\n"
      "  tint.x = 2;\n"
      "  k = 3;\n"
      "  u = 4;\n"
      "  s = 5; p = 6;\n"
      "}\n";
  EXPECT_EQ(messages_of(source), (Strings{"6:3: error: cannot assign to 'g': uniforms are read-only",
                                          "7:3: error: cannot assign to 'tint': uniforms are read-only",
                                          "8:3: error: cannot assign to 'k': it is const",
                                          "9:3: error: cannot assign to 'u': uniforms are read-only"}));
}

TEST(SemaAssign, RvaluesAndRepeatedSwizzlesAreNotAssignable) {
  EXPECT_EQ(messages_of("float f() { return 1; }\nvoid t(float4 v) {\n  v.xx = 1;\n  f() = 2;\n  (v + 1) = 3;\n}\n"),
            (Strings{"3:5: error: cannot assign to a swizzle with repeated components",
                     "4:3: error: expression is not assignable", "5:6: error: expression is not assignable"}));
  EXPECT_EQ(messages_of("void t() { 1++; }"), (Strings{"1:12: error: expression is not assignable"}));
}

TEST(SemaAssign, FieldsElementsAndSwizzlesOfLocalsAreAssignable) {
  EXPECT_EQ(messages_of("struct S { float4 a[2]; };\n"
                        "void t(inout S s, out float2 o) { s.a[1].zyx = 1; s.a[0][3] = 2; o = 0; o.y++; }\n"),
            Strings{});
}

TEST(SemaAssign, ResourcesAreNotAssignable) {
  EXPECT_EQ(messages_of("Texture2D a;\nvoid t(Texture2D b) { b = a; }\n"),
            (Strings{"2:23: error: 'Texture2D' objects are only assignable to local variables, which then name them"}));
}

TEST(SemaAssign, CompoundAssignmentFollowsTheOperator) {
  auto a =
      analyze_source("void t(float3 v, int i, float f, float3 w) {\n  v *= 2;\n  i *= 0.5;\n  f += w;\n  v += f;\n}\n");
  EXPECT_EQ(a->messages(), (Strings{"4:5: warning: implicit truncation of vector type from 'float3' to 'float'"}));
  EXPECT_EQ(dump(&a->expression("t", 0)), "(*= v (to float3 2))");
  EXPECT_EQ(dump(&a->expression("t", 1)), "(*= i 0.5)");  // computed in float, then back to int
  EXPECT_EQ(dump(&a->expression("t", 3)), "(+= v (to float3 f))");
  EXPECT_EQ(a->expression("t", 1).type.name(), "int");
}

TEST(SemaAssign, AssignmentConvertsTheValue) {
  auto a = analyze_source("void t(float4 v, half h) {\n  float3 x;\n  x = v;\n  h = 1;\n}\n");
  EXPECT_EQ(a->messages(), (Strings{"3:7: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
  EXPECT_EQ(dump(&a->expression("t", 1)), "(= x (to float3 v))");
  EXPECT_EQ(dump(&a->expression("t", 2)), "(= h (to half 1))");
}

TEST(SemaAssign, ReturnValuesConvertToTheReturnType) {
  auto a =
      analyze_source("float3 f(float4 v) {\n  return v;\n}\nvoid g() {\n  return 1;\n}\nfloat h() {\n  return;\n}\n");
  EXPECT_EQ(a->messages(), (Strings{"2:10: warning: implicit truncation of vector type from 'float4' to 'float3'",
                                    "5:10: error: void function 'g' cannot return a value",
                                    "8:3: error: 'h' must return a value of type 'float'"}));
}

TEST(SemaAssign, MissingReturnOnSomePathWarns) {
  EXPECT_EQ(messages_of("float f(float x) {\n  if (x > 0) return 1;\n}\n"),
            (Strings{"1:7: warning: not all paths return a value"}));
  EXPECT_EQ(messages_of("float f(float x) { if (x > 0) return 1; else return 2; }\n"
                        "float g(float x) { while (true) { if (x > 0) return 1; } }\n"
                        "float4 h(float x) : SV_Target { if (x > 0) return 1; discard; }\n"),
            Strings{});
}

// ---------------------------------------------------------------------------------------------
// Initializer lists

TEST(SemaInit, ComponentsAreCountedHlslStyle) {
  auto a = analyze_source(
      "void t(float2 p) {\n"
      "  float4 v = {1, 2, 3, 4};\n"
      "  float2 k[2] = {float2(0, 1), float2(1, 0)};\n"
      "  float2 m[2] = {0, 1, 1, 0};\n"
      "  float4 w = {p, 1, 2};\n"
      "}\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(dump(&a->expression("t", 0)), "({} float4 (to float 1) (to float 2) (to float 3) (to float 4))");
  EXPECT_EQ(dump(&a->expression("t", 1)),
            "({} float2[2] (float2 (to float 0) (to float 1)) (float2 (to float 1) (to float 0)))");
  EXPECT_EQ(dump(&a->expression("t", 2)),
            "({} float2[2] ({} float2 (to float 0) (to float 1)) ({} float2 (to float 1) (to float 0)))");
  EXPECT_EQ(dump(&a->expression("t", 3)), "({} float4 p (to float 1) (to float 2))");
}

TEST(SemaInit, WrongCountIsAnError) {
  EXPECT_EQ(messages_of("void t() {\n  float4 v = {1, 2, 3, 4, 5};\n}\n"),
            (Strings{"2:14: error: initializer has 5 components, 'float4' needs 4"}));
}

TEST(SemaInit, StructsAndNestedLists) {
  auto a = analyze_source(
      "struct L { float3 dir; float4 color; };\n"
      "static const L lights[2] = { { {0, 1, 0}, {1, 1, 1, 1} }, float3(1, 0, 0), float4(0.5, 0.5, 0.5, 1) };\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(dump(a->global("lights").initializer.get()),
            "({} L[2] ({} L ({} float3 (to float 0) (to float 1) (to float 0)) "
            "({} float4 (to float 1) (to float 1) (to float 1) (to float 1))) "
            "({} L (float3 (to float 1) (to float 0) (to float 0)) (float4 0.5 0.5 0.5 (to float 1))))");
}

TEST(SemaInit, UnsizedArraysTakeTheirLengthFromTheList) {
  auto a = analyze_source("static const float2 kDisk[] = { 0, 0, 0.5, 0, 1, 0 };\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(a->global("kDisk").type.name(), "float2[3]");
  EXPECT_EQ(a->global("kDisk").initializer->type.name(), "float2[3]");
}

TEST(SemaInit, UnsizedArraysCountComponentsOfAnyScalars) {
  // Not only literals: four scalar variables fill two float2 elements.
  auto a = analyze_source("void t(float a, float b, float c, float d) { float2 k[] = { a, b, c, d }; }\n");
  EXPECT_EQ(a->messages(), Strings{});
}

TEST(SemaInit, AnElementMayNotStraddleTwoMembers) {
  EXPECT_EQ(messages_of("void t() { float2 k[2] = { float3(0, 0, 0), 1 }; }\n"),
            (Strings{"1:28: error: initializer element of type 'float3' spans several elements of 'float2[2]'"}));
}

TEST(SemaInit, StaticConstNeedsAnInitializer) {
  EXPECT_EQ(
      messages_of("static const float k;\nvoid t() { const int n; }\n"),
      (Strings{"1:20: error: static const 'k' needs an initializer", "2:22: error: const 'n' needs an initializer"}));
}

// ---------------------------------------------------------------------------------------------
// Members and indexing

TEST(SemaMembers, StructFields) {
  auto a =
      analyze_source("struct S { float a; float3 b; };\nfloat3 t(S s) { return s.b; }\nvoid u(S s) { s.c = 1; }\n");
  EXPECT_EQ(a->messages(), (Strings{"3:17: error: 'S' has no member 'c'"}));
  const auto& member = static_cast<const MemberExpr&>(a->expression("t", 0));
  EXPECT_EQ(member.field_index, 1);
  EXPECT_EQ(member.type.name(), "float3");
}

// The components a swizzle picks, as a vector to compare with.
std::vector<uint8_t> swizzle_of(const MemberExpr& member) { return {member.swizzle.begin(), member.swizzle.end()}; }

TEST(SemaMembers, VectorSwizzles) {
  const std::string g = "float4 v; float2 p; float f; int3 i;";
  EXPECT_EQ(type_of(g, "v.xyz"), "float3");
  EXPECT_EQ(type_of(g, "v.bgra"), "float4");
  EXPECT_EQ(type_of(g, "v.w"), "float");
  EXPECT_EQ(type_of(g, "f.xxx"), "float3");
  EXPECT_EQ(type_of(g, "i.zy"), "int2");
  auto a = analyze_source("float4 v;\nfloat2 t() { return v.wx; }\n");
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("t", 0))), (std::vector<uint8_t>{3, 0}));
  EXPECT_EQ(probe(g, "v.xg").messages, (Strings{"2:14: error: swizzle 'xg' mixes xyzw and rgba components"}));
  EXPECT_EQ(probe(g, "p.z").messages, (Strings{"2:14: error: swizzle 'z' is out of range for 'float2'"}));
  EXPECT_EQ(probe(g, "f.y").messages, (Strings{"2:14: error: swizzle 'y' is out of range for 'float'"}));
  EXPECT_EQ(probe(g, "v.xyzwx").messages, (Strings{"2:14: error: swizzle 'xyzwx' has more than 4 components"}));
  EXPECT_EQ(probe(g, "v.foo").messages, (Strings{"2:14: error: 'float4' has no member 'foo'"}));
}

TEST(SemaMembers, MatrixSwizzles) {
  auto a = analyze_source(
      "float4x4 m;\nfloat2 t() { return m._m00_m11; }\nfloat u() { return m._44; }\n"
      "float3 w() { return m._12_21_34; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("t", 0))), (std::vector<uint8_t>{0, 5}));
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("u", 0))), (std::vector<uint8_t>{15}));
  EXPECT_EQ(a->expression("u", 0).type.name(), "float");
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("w", 0))), (std::vector<uint8_t>{1, 4, 11}));
  EXPECT_EQ(probe("float2x2 m;", "m._m22").messages,
            (Strings{"2:14: error: swizzle '_m22' is out of range for 'float2x2'"}));
  EXPECT_EQ(probe("float2x3 m;", "m._13").type, "float");
  EXPECT_EQ(probe("float2x3 m;", "m._31").messages,
            (Strings{"2:14: error: swizzle '_31' is out of range for 'float2x3'"}));
}

TEST(SemaMembers, IndexingAMatrixGivesARow) {
  EXPECT_EQ(type_of("float4x4 m;", "m[1]"), "float4");
  EXPECT_EQ(type_of("float3x4 m;", "m[2]"), "float4");
  EXPECT_EQ(type_of("float3x4 m;", "m[2][3]"), "float");
  EXPECT_EQ(type_of("float4 v;", "v[3]"), "float");
  EXPECT_EQ(type_of("float2 a[5];", "a[4]"), "float2");
  Probe p = probe("float4 a[4]; float f;", "a[f]");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.tree, "([] a (to int f))");
  EXPECT_EQ(probe("float4 v;", "v[4]").messages, (Strings{"2:14: error: index 4 is out of range for 'float4'"}));
  EXPECT_EQ(probe("float f;", "f[0]").messages, (Strings{"2:13: error: cannot index a value of type 'float'"}));
  EXPECT_EQ(probe("float4 v; float2 i;", "v[i]").messages,
            (Strings{"2:14: error: index must be an integer scalar, not 'float2'"}));
}

// ---------------------------------------------------------------------------------------------
// Constructors and user functions

}  // namespace
}  // namespace xshade::hlsl::sema_test
