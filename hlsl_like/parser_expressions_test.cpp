// The parser's expressions and statements, one test per production: precedence, casts, literals,
// statements, semantics, resource types, attributes, switch.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/lexer.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/parser_internal.h"
#include "hlsl_like/parser_test_support.h"

namespace xshade::hlsl::parser_test {
namespace {

TEST(Parser, OperatorPrecedenceAndAssociativity) {
  EXPECT_EQ(expr_tree("a = b = c"), "(= a (= b c))");
  EXPECT_EQ(expr_tree("a += b -= c"), "(+= a (-= b c))");
  EXPECT_EQ(expr_tree("a + b * c"), "(+ a (* b c))");
  EXPECT_EQ(expr_tree("a - b - c"), "(- (- a b) c)");
  EXPECT_EQ(expr_tree("a / b * c % d"), "(% (* (/ a b) c) d)");
  EXPECT_EQ(expr_tree("-a.x"), "(- (. a x))");
  EXPECT_EQ(expr_tree("(float)a * b"), "(* (cast float a) b)");
  EXPECT_EQ(expr_tree("(a) * b"), "(* a b)");
  EXPECT_EQ(expr_tree("(a + b) * c"), "(* (+ a b) c)");
  EXPECT_EQ(expr_tree("x ? y : z ? w : v"), "(? x y (? z w v))");
  EXPECT_EQ(expr_tree("x ? y : z"), "(? x y z)");
  EXPECT_EQ(expr_tree("a < b == c > d"), "(== (< a b) (> c d))");
  EXPECT_EQ(expr_tree("i << 1 + j"), "(<< i (+ 1 j))");
  EXPECT_EQ(expr_tree("i & j | i ^ j"), "(| (& i j) (^ i j))");
  EXPECT_EQ(expr_tree("a || b && c"), "(|| a (&& b c))");
  EXPECT_EQ(expr_tree("!a && ~i"), "(&& (! a) (~ i))");
  EXPECT_EQ(expr_tree("i++, --j"), "(, (post++ i) (pre-- j))");
  EXPECT_EQ(expr_tree("-(float3)n.x"), "(- (cast float3 (. n x)))");
  EXPECT_EQ(expr_tree("((float3)n).x"), "(. (cast float3 n) x)");
  EXPECT_EQ(expr_tree("tex.Sample(s, uv).rgb"), "(. (method tex Sample s uv) rgb)");
  EXPECT_EQ(expr_tree("n.xzy.x"), "(. (. n xzy) x)");
  EXPECT_EQ(expr_tree("arr[i + 1] * 2"), "(* ([] arr (+ i 1)) 2)");
  EXPECT_EQ(expr_tree("l.color.r"), "(. (. l color) r)");
  EXPECT_EQ(expr_tree("float2x2(1, 2, 3, 4)"), "(ctor float2x2 1 2 3 4)");
  EXPECT_EQ(expr_tree("vector<float, 2>(a, b)"), "(ctor float2 a b)");
  EXPECT_EQ(expr_tree("float3(a, b, c).xy"), "(. (ctor float3 a b c) xy)");
  EXPECT_EQ(expr_tree("i %= j <<= 2"), "(%= i (<<= j 2))");
  EXPECT_EQ(expr_tree("a = x > y ? x : y"), "(= a (? (> x y) x y))");
  EXPECT_EQ(expr_tree("a = +b"), "(= a (+ b))");
  EXPECT_EQ(expr_tree("a = 1.5h + 2.0f + .5 + 1e-3"), "(= a (+ (+ (+ 1.5h 2.0) .5) 1e-3))");
  EXPECT_EQ(expr_tree("i = 0x1F + 7u + 3l"), "(= i (+ (+ 31 7u) 3))");
  EXPECT_EQ(expr_tree("a = true ? b : false ? c : d"), "(= a (? true b (? false c d)))");
}

TEST(Parser, CastsAreToldFromParenthesisedExpressionsByTheTypeTable) {
  EXPECT_EQ(expr_tree("(a) - b"), "(- a b)");
  EXPECT_EQ(expr_tree("(float) - b"), "(cast float (- b))");
  EXPECT_EQ(expr_tree("(int)(a)"), "(cast int a)");
  EXPECT_EQ(expr_tree("(float2x2)(float4)a"), "(cast float2x2 (cast float4 a))");
  EXPECT_EQ(expr_tree("(float3(a, b, c))"), "(ctor float3 a b c)");
  EXPECT_EQ(expr_tree("(Light)0"), "(cast Light 0)");
}

// Whatever text a FloatLiteral token has (the preprocessor pastes tokens too), its value and
// whether it is reported are strtod's: every bit of the double, for short and long digit runs,
// exponents near and past the exact powers of ten, and malformed spellings.
TEST(Parser, FloatLiteralValuesAreStrtods) {
  std::mt19937 rng(2024);
  auto digits = [&](size_t n) {
    std::string out;
    for (size_t i = 0; i < n; ++i) out += char('0' + rng() % 10);
    return out;
  };
  std::vector<std::string> spellings = {"0.0",
                                        "1.",
                                        ".5",
                                        "1e5",
                                        "1e+5",
                                        "1e-5",
                                        "1e",
                                        "1e+",
                                        "1.5.3",
                                        ".",
                                        "e5",
                                        "0x1p3",
                                        "1.0e22",
                                        "1.0e23",
                                        "9007199254740993.0",
                                        "123456789012345.6",
                                        "0.000000000000000000000000001",
                                        "1e-22",
                                        "1e-23",
                                        "00012.500e-3",
                                        "1e400",
                                        "1e-400",
                                        "4.9e-324",
                                        "1.7976931348623157e308",
                                        "0e99999",
                                        "12a",
                                        "1.5f"};
  for (int i = 0; i < 4000; ++i) {
    std::string text = digits(rng() % 20);
    if (rng() % 4 != 0) text += "." + digits(rng() % 20);
    if (rng() % 3 == 0) {
      text += (rng() % 2 ? "e" : "E");
      if (rng() % 2) text += (rng() % 2 ? "-" : "+");
      text += digits(rng() % 4);
    }
    spellings.push_back(text);
  }
  for (const std::string& spelling : spellings) {
    SourceManager sources;
    DiagnosticEngine diagnostics(sources);
    Token literal;
    literal.kind = TokenKind::FloatLiteral;
    literal.text = spelling;
    Token end;
    end.kind = TokenKind::EndOfFile;
    const std::vector<Token> tokens = {literal, end};
    parser_detail::Parser parser(tokens, diagnostics);
    const ExprPtr parsed = parser.parse_float_literal();
    ASSERT_NE(parsed, nullptr);
    std::string_view text = spelling;
    if (text.back() == 'f') text.remove_suffix(1);
    const std::string unsuffixed(text);
    char* stop = nullptr;
    const bool starts_well = !text.empty() && ((text[0] >= '0' && text[0] <= '9') || text[0] == '.');
    double expected = starts_well ? std::strtod(unsuffixed.c_str(), &stop) : 0.0;
    const bool valid = starts_well && stop == unsuffixed.c_str() + unsuffixed.size();
    if (!valid) expected = 0.0;
    const double value = static_cast<const FloatLiteralExpr&>(*parsed).value;
    EXPECT_EQ(std::memcmp(&value, &expected, sizeof value), 0) << spelling << ": " << value << " vs " << expected;
    EXPECT_EQ(diagnostics.error_count() > 0, !valid || std::isinf(expected)) << spelling;
  }
}

TEST(Parser, Literals) {
  auto p = parse_text(
      "static const uint a = 4294967295u; static const int b = 0xFFFFFFFF;\n"
      "static const float c = 1.25f; static const half d = 2.5h; static const int e = 010;\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const auto& a = static_cast<const IntLiteralExpr&>(*p->var("a").initializer);
  EXPECT_EQ(a.value, 4294967295u);
  EXPECT_TRUE(a.is_unsigned);
  EXPECT_EQ(static_cast<const IntLiteralExpr&>(*p->var("b").initializer).value, 0xFFFFFFFFu);
  const auto& c = static_cast<const FloatLiteralExpr&>(*p->var("c").initializer);
  EXPECT_EQ(c.spelling, "1.25");
  EXPECT_DOUBLE_EQ(c.value, 1.25);
  EXPECT_FALSE(c.half_suffix);
  const auto& d = static_cast<const FloatLiteralExpr&>(*p->var("d").initializer);
  EXPECT_EQ(d.spelling, "2.5");
  EXPECT_TRUE(d.half_suffix);
  EXPECT_EQ(static_cast<const IntLiteralExpr&>(*p->var("e").initializer).value, 8u);

  auto big = parse_text("static const int x = 4294967296;\nstatic const int y = 0x100000000;\n");
  EXPECT_EQ(big->errors(),
            (std::vector<std::string>{"1:22: integer literal is too large", "2:22: integer literal is too large"}));
}

TEST(Parser, Statements) {
  auto p = parse_text(
      "float4 f(float x) {\n"
      "  static const float k = 2;\n"
      "  float acc = 0, tmp;\n"
      "  [unroll] for (int i = 0; i < 4; ++i) { acc += i; }\n"
      "  for (;;) break;\n"
      "  for (tmp = 0; tmp < 1; tmp += 0.5) continue;\n"
      "  while (acc > 1) acc *= 0.5;\n"
      "  do { acc -= 1; } while (acc > 0);\n"
      "  [branch] if (x < 0) discard; else if (x > 1) { return 1; } else ;\n"
      "  ;\n"
      "  {}\n"
      "  return float4(acc, k, 0, 1);\n"
      "}\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const auto& body = p->function("f").body->statements;
  ASSERT_EQ(body.size(), 11u);
  const auto& k = static_cast<const DeclStmt&>(*body[0]);
  ASSERT_EQ(k.kind, StmtKind::Decl);
  EXPECT_EQ(k.vars[0]->storage, StorageClass::Static);
  EXPECT_TRUE(k.vars[0]->is_const);
  EXPECT_FALSE(k.vars[0]->is_global);
  EXPECT_EQ(static_cast<const DeclStmt&>(*body[1]).vars.size(), 2u);

  const auto& for1 = static_cast<const ForStmt&>(*body[2]);
  ASSERT_EQ(for1.kind, StmtKind::For);
  ASSERT_EQ(for1.attributes.size(), 1u);
  EXPECT_EQ(for1.attributes[0].name, "unroll");
  ASSERT_EQ(for1.init->kind, StmtKind::Decl);
  EXPECT_EQ(static_cast<const DeclStmt&>(*for1.init).vars[0]->name, "i");
  EXPECT_EQ(sexpr(*for1.condition), "(< i 4)");
  EXPECT_EQ(sexpr(*for1.step), "(pre++ i)");
  EXPECT_EQ(for1.body->kind, StmtKind::Block);

  const auto& for2 = static_cast<const ForStmt&>(*body[3]);
  EXPECT_EQ(for2.init, nullptr);
  EXPECT_EQ(for2.condition, nullptr);
  EXPECT_EQ(for2.step, nullptr);
  EXPECT_EQ(for2.body->kind, StmtKind::Break);

  const auto& for3 = static_cast<const ForStmt&>(*body[4]);
  EXPECT_EQ(for3.init->kind, StmtKind::Expr);
  EXPECT_EQ(for3.body->kind, StmtKind::Continue);

  EXPECT_EQ(body[5]->kind, StmtKind::While);
  const auto& do_while = static_cast<const DoWhileStmt&>(*body[6]);
  ASSERT_EQ(do_while.kind, StmtKind::DoWhile);
  EXPECT_EQ(sexpr(*do_while.condition), "(> acc 0)");

  const auto& if1 = static_cast<const IfStmt&>(*body[7]);
  ASSERT_EQ(if1.kind, StmtKind::If);
  ASSERT_EQ(if1.attributes.size(), 1u);
  EXPECT_EQ(if1.attributes[0].name, "branch");
  EXPECT_EQ(if1.then_branch->kind, StmtKind::Discard);
  ASSERT_EQ(if1.else_branch->kind, StmtKind::If);
  const auto& if2 = static_cast<const IfStmt&>(*if1.else_branch);
  EXPECT_EQ(if2.then_branch->kind, StmtKind::Block);
  EXPECT_EQ(if2.else_branch->kind, StmtKind::Empty);

  EXPECT_EQ(body[8]->kind, StmtKind::Empty);
  EXPECT_EQ(body[9]->kind, StmtKind::Block);
  const auto& ret = static_cast<const ReturnStmt&>(*body[10]);
  EXPECT_EQ(sexpr(*ret.value), "(ctor float4 acc k 0 1)");
}

TEST(Parser, InterpolationWordsAreNamesWhereNoTypeFollows) {
  auto p = parse_text("float f(float linear) { float sample = linear; sample = 2; return sample; }\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->function("f").params[0]->name, "linear");
}

TEST(Parser, SemanticsKeepTheirSpelling) {
  auto p = parse_text("float4 f(float4 p : sv_position, float2 t : TexCoord3) : sv_target { return p; }\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const FunctionDecl& f = p->function("f");
  EXPECT_EQ(f.semantic, "sv_target");
  EXPECT_EQ(f.params[0]->semantic, "sv_position");
  EXPECT_EQ(f.params[1]->semantic, "TexCoord3");
  EXPECT_EQ(f.params[1]->semantic_loc.line, 1u);
  EXPECT_EQ(f.params[1]->semantic_loc.column, 45u);
}

TEST(Parser, ResourceTypesOfEveryKind) {
  auto p = parse_text(
      "Texture3D<half4> lut; TextureCubeArray cubes; Texture2DMS<float, 8> depth; Texture1DArray<uint2> ids;\n"
      "SamplerComparisonState cmp; samplerCUBE env; sampler3D vol;\n"
      "struct Light { float3 color; };\nStructuredBuffer<Light> lights; RWByteAddressBuffer raw; RWTexture3D<uint> "
      "grid;\n"
      "struct Scene { float4x4 view; };\nConstantBuffer<Scene> scene : register(b2);\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->var("lut").type.name(), "Texture3D<half4>");
  EXPECT_EQ(p->var("cubes").type, Type::texture(TextureShape::CubeArray, Type::vector(ScalarType::Float, 4)));
  EXPECT_EQ(p->var("depth").type.name(), "Texture2DMS<float>");
  EXPECT_EQ(p->var("ids").type.texel_type().name(), "uint2");
  EXPECT_TRUE(p->var("cmp").type.is_comparison());
  EXPECT_EQ(p->var("env").type, Type::sampler(TextureShape::Cube));
  EXPECT_EQ(p->var("vol").type.name(), "sampler3D");
  EXPECT_EQ(p->var("lights").type.name(), "StructuredBuffer<Light>");
  EXPECT_EQ(p->var("raw").type.name(), "RWByteAddressBuffer");
  EXPECT_EQ(p->var("grid").type.name(), "RWTexture3D<uint>");
  EXPECT_EQ(p->var("scene").type.name(), "ConstantBuffer<Scene>");
  EXPECT_EQ(p->var("scene").binding.index, 2u);
}

TEST(Parser, ConstantBufferAloneIsAName) {
  // The D3D11 tutorials name a cbuffer so; only ConstantBuffer<S> is the type.
  auto p = parse_text("cbuffer ConstantBuffer : register(b0) { float4x4 World; };\nfloat4 ConstantBuffer2;\n");
  EXPECT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->decl<CBufferDecl>(0).name, "ConstantBuffer");
}

TEST(Parser, ResourceTypeArgumentsAreChecked) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"struct L { float a; };\nTexture2D<L> t;",
       "2:11: the texel type of 'Texture2D' must be a scalar or vector, not 'L'"},
      {"Texture2D<float4x4> t;", "1:11: the texel type of 'Texture2D' must be a scalar or vector, not 'float4x4'"},
      {"StructuredBuffer b;", "1:18: expected '<' after 'StructuredBuffer': a structured buffer needs an element type"},
      {"ConstantBuffer<float4> c;", "1:16: ConstantBuffer holds a struct, not 'float4'"},
  };
  for (const auto& [source, error] : cases)
    EXPECT_EQ(parse_text(source)->errors(), std::vector<std::string>{error}) << source;
}

TEST(Parser, AttributesWithStringsAreIgnoredWithANote) {
  auto p = parse_text(
      "[RootSignature(\"RootFlags(0), \" \"CBV(b0)\")]\nfloat4 f() : SV_Target { return 0; }\n"
      "[domain(\"tri\")] [partitioning(\"integer\")] void g() {}\n");
  EXPECT_EQ(p->errors(), std::vector<std::string>{});
  std::vector<std::string> notes;
  for (const Diagnostic& d : p->diagnostics.diagnostics())
    if (d.severity == Severity::Note)
      notes.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
  EXPECT_EQ(notes,
            (std::vector<std::string>{"1:2: attribute 'RootSignature' is ignored", "3:2: attribute 'domain' is ignored",
                                      "3:18: attribute 'partitioning' is ignored"}));
  EXPECT_EQ(p->function("f").attributes.at(0).name, "RootSignature");
}

TEST(Parser, SwitchCasesHoldTheStatementsUpToTheNextLabel) {
  auto p = parse_text("int f(int m) { switch (m) { case 0: case 1: m += 1; break; default: { m = 3; } } return m; }\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const Stmt& statement = *p->function("f").body->statements.at(0);
  ASSERT_EQ(statement.kind, StmtKind::Switch);
  const auto& sw = static_cast<const SwitchStmt&>(statement);
  ASSERT_EQ(sw.cases.size(), 3u);
  EXPECT_EQ(sexpr(*sw.cases[0].value), "0");
  EXPECT_TRUE(sw.cases[0].statements.empty());  // falls through to case 1
  EXPECT_EQ(sw.cases[1].statements.size(), 2u);
  EXPECT_EQ(sw.cases[2].value, nullptr);
  EXPECT_EQ(sw.cases[2].statements.size(), 1u);
}

TEST(Parser, NestedTemplateClosesWithShiftToken) {
  auto p = parse_text("Texture2D<vector<float, 4>> t;\nfloat x = 1 >> 2;\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->var("t").type, Type::texture2d());
  EXPECT_EQ(sexpr(*p->var("x").initializer), "(>> 1 2)");
}

}  // namespace
}  // namespace xshade::hlsl::parser_test
