// The parser, one test per production and per recovery rule (skip_until through parser_internal.h).
// Why this file is long: it is one short case per rule of the grammar, read as the list of them.
#include "hlsl_like/parser.h"

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
#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl {
namespace {

// Source text through the real lexer into the parser; everything the tree points into lives here.
struct Parsed {
  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  std::deque<std::string> text_store;
  std::vector<Token> tokens;
  TranslationUnit unit;

  // "line:col: message" for each error, in order.
  std::vector<std::string> errors() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics.diagnostics())
      if (d.severity == Severity::Error)
        out.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
    return out;
  }

  template <class T>
  const T& decl(size_t index) const {
    EXPECT_LT(index, unit.decls.size());
    return static_cast<const T&>(*unit.decls.at(index));
  }
  const FunctionDecl& function(std::string_view name) const {
    for (const auto& d : unit.decls)
      if (d->kind == DeclKind::Function && d->name == name && static_cast<const FunctionDecl&>(*d).body)
        return static_cast<const FunctionDecl&>(*d);
    throw std::runtime_error("no function " + std::string(name));
  }
  const VarDecl& var(std::string_view name) const {
    for (const auto& d : unit.decls)
      if (d->kind == DeclKind::Var && d->name == name) return static_cast<const VarDecl&>(*d);
    throw std::runtime_error("no variable " + std::string(name));
  }
};

// The tokens only, for a test that starts a Parser at one production.
std::unique_ptr<Parsed> lex_text(const std::string& text) {
  auto parsed = std::make_unique<Parsed>();
  const uint32_t file = parsed->sources.add("test.hlsl", text);
  Lexer lexer(parsed->sources.text(file), file, parsed->diagnostics, &parsed->text_store);
  for (;;) {
    parsed->tokens.push_back(lexer.next());
    if (parsed->tokens.back().kind == TokenKind::EndOfFile) break;
  }
  return parsed;
}

std::unique_ptr<Parsed> parse_text(const std::string& text) {
  auto parsed = lex_text(text);
  parsed->unit = parse(parsed->tokens, parsed->diagnostics);
  return parsed;
}

// The tree of an expression as an S-expression, to pin shapes in one line.
std::string sexpr(const Expr& e);

template <class List>
std::string sexpr_list(const List& list) {
  std::string out;
  for (const ExprPtr& item : list) out += " " + sexpr(*item);
  return out;
}

std::string sexpr(const Expr& e) {
  switch (e.kind) {
    case ExprKind::IntLiteral: {
      const auto& x = static_cast<const IntLiteralExpr&>(e);
      return std::to_string(x.value) + (x.is_unsigned ? "u" : "");
    }
    case ExprKind::FloatLiteral: {
      const auto& x = static_cast<const FloatLiteralExpr&>(e);
      return x.spelling + (x.half_suffix ? "h" : "");
    }
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr&>(e).value ? "true" : "false";
    case ExprKind::Name: return static_cast<const NameExpr&>(e).name;
    case ExprKind::Unary: {
      const auto& x = static_cast<const UnaryExpr&>(e);
      static const char* const kOps[] = {"+", "-", "!", "~", "pre++", "pre--", "post++", "post--"};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.operand) + ")";
    }
    case ExprKind::Binary: {
      const auto& x = static_cast<const BinaryExpr&>(e);
      static const char* const kOps[] = {"+", "-", "*", "/", "%", "<<", ">>", "&", "|", "^", "&&", "||",
                                         "<", ">", "<=", ">=", "==", "!=", ","};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.lhs) + " " + sexpr(*x.rhs) + ")";
    }
    case ExprKind::Assign: {
      const auto& x = static_cast<const AssignExpr&>(e);
      static const char* const kOps[] = {"=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.target) + " " + sexpr(*x.value) + ")";
    }
    case ExprKind::Conditional: {
      const auto& x = static_cast<const ConditionalExpr&>(e);
      return "(? " + sexpr(*x.condition) + " " + sexpr(*x.then_value) + " " + sexpr(*x.else_value) + ")";
    }
    case ExprKind::Call: {
      const auto& x = static_cast<const CallExpr&>(e);
      if (x.call_kind == CallKind::Constructor) return "(ctor " + x.constructed.name() + sexpr_list(x.args) + ")";
      if (x.object) return "(method " + sexpr(*x.object) + " " + x.callee + sexpr_list(x.args) + ")";
      return "(call " + x.callee + sexpr_list(x.args) + ")";
    }
    case ExprKind::Member: {
      const auto& x = static_cast<const MemberExpr&>(e);
      return "(. " + sexpr(*x.object) + " " + x.member + ")";
    }
    case ExprKind::Index: {
      const auto& x = static_cast<const IndexExpr&>(e);
      return "([] " + sexpr(*x.object) + " " + sexpr(*x.index) + ")";
    }
    case ExprKind::Cast: {
      const auto& x = static_cast<const CastExpr&>(e);
      return "(cast " + x.target.name() + " " + sexpr(*x.operand) + ")";
    }
    case ExprKind::InitList: return "{" + sexpr_list(static_cast<const InitListExpr&>(e).elements) + " }";
    case ExprKind::Conversion: return "(conversion)";
  }
  return "?";
}

// The expression of `float __e = EXPR;` inside a function whose locals a..z are declared.
std::string expr_tree(const std::string& expression) {
  auto parsed = parse_text("struct Light { float3 color; };\n"
                           "void f(float a, float b, float c, float d, float x, float y, float z, float w, float v,"
                           " float3 n, int i, int j, Texture2D tex, SamplerState s, float2 uv, Light l,"
                           " float arr[4]) {\n  " +
                           expression + ";\n}\n");
  EXPECT_EQ(parsed->errors(), std::vector<std::string>{}) << expression;
  if (parsed->diagnostics.has_errors()) return "<error>";
  const FunctionDecl& f = parsed->function("f");
  const Stmt& statement = *f.body->statements.at(0);
  EXPECT_EQ(statement.kind, StmtKind::Expr);
  return sexpr(*static_cast<const ExprStmt&>(statement).expr);
}

const char* const kUnityShader = R"(
// A Unity-style lit shader, preprocessed.
typedef half4 fixed4;

struct appdata {
  float4 vertex : POSITION;
  float3 normal : NORMAL;
  float2 uv : TEXCOORD0;
};

struct v2f {
  float4 pos : SV_POSITION;
  float2 uv : TEXCOORD0;
  float3 worldNormal : TEXCOORD1;
  nointerpolation int id : TEXCOORD2;
  float w[4];
};

cbuffer UnityPerMaterial : register(b0) {
  float4 _Color;
  row_major float4x4 _ObjectToWorld;
  float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
  float _Bias <float UIMin = -1.5; int Steps = -2;>;
};

Texture2D _MainTex : register(t0);
SamplerState sampler_MainTex : register(s0, space1);
Texture2D<float4> _ShadowTex;
sampler2D _RampTex;
uniform float4 _Tint;
static const float PI = 3.14159;

v2f vert(appdata v) {
  v2f o;
  o.pos = mul(_ObjectToWorld, v.vertex);
  o.uv = v.uv;
  o.worldNormal = normalize(mul((float3x3)_ObjectToWorld, v.normal));
  o.id = 0;
  [unroll] for (int k = 0; k < 4; ++k) o.w[k] = 0;
  return o;
}

fixed4 frag(v2f i) : SV_Target {
  float3 n = normalize(i.worldNormal);
  float nd = dot(n, float3(0, 1, 0)) * 0.5 + 0.5;
  fixed4 albedo = _MainTex.Sample(sampler_MainTex, i.uv) * _Color;
  albedo.rgb *= tex2D(_RampTex, float2(nd, 0.5)).rgb;
  if (albedo.a < 0.01) discard;
  return albedo * _Tint;
}
)";

TEST(Parser, UnityShaderEndToEnd) {
  auto p = parse_text(kUnityShader);
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  ASSERT_EQ(p->unit.decls.size(), 12u);

  const auto& fixed4 = p->decl<TypedefDecl>(0);
  EXPECT_EQ(fixed4.kind, DeclKind::Typedef);
  EXPECT_EQ(fixed4.name, "fixed4");
  EXPECT_EQ(fixed4.type, Type::vector(ScalarType::Half, 4));

  const auto& appdata = p->decl<StructDecl>(1);
  ASSERT_EQ(appdata.kind, DeclKind::Struct);
  ASSERT_EQ(appdata.fields.size(), 3u);
  EXPECT_EQ(appdata.fields[1].name, "normal");
  EXPECT_EQ(appdata.fields[1].type, Type::vector(ScalarType::Float, 3));
  EXPECT_EQ(appdata.fields[1].semantic, "NORMAL");
  EXPECT_EQ(appdata.fields[2].semantic, "TEXCOORD0");

  const auto& v2f = p->decl<StructDecl>(2);
  ASSERT_EQ(v2f.fields.size(), 5u);
  EXPECT_EQ(v2f.fields[0].semantic, "SV_POSITION");
  EXPECT_EQ(v2f.fields[3].interpolation, Interpolation::NoInterpolation);
  EXPECT_EQ(v2f.fields[3].type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(v2f.fields[4].type, Type::array(Type::scalar(ScalarType::Float), 4));
  EXPECT_EQ(v2f.fields[4].semantic, "");

  const auto& cbuffer = p->decl<CBufferDecl>(3);
  ASSERT_EQ(cbuffer.kind, DeclKind::CBuffer);
  EXPECT_EQ(cbuffer.name, "UnityPerMaterial");
  EXPECT_EQ(cbuffer.binding.register_class, 'b');
  EXPECT_EQ(cbuffer.binding.index, 0u);
  ASSERT_EQ(cbuffer.members.size(), 4u);
  EXPECT_TRUE(cbuffer.members[0]->is_global);
  EXPECT_EQ(cbuffer.members[1]->packing, MatrixPacking::RowMajor);
  EXPECT_EQ(cbuffer.members[1]->type.rows(), 4u);
  const VarDecl& metallic = *cbuffer.members[2];
  ASSERT_EQ(metallic.annotations.size(), 3u);
  EXPECT_EQ(metallic.annotations[0].name, "UIName");
  EXPECT_EQ(metallic.annotations[0].text, "Metallic");
  EXPECT_EQ(metallic.annotations[0].value, nullptr);
  EXPECT_EQ(metallic.annotations[1].name, "UIMin");
  EXPECT_EQ(metallic.annotations[1].type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(sexpr(*metallic.annotations[2].value), "1.0");
  ASSERT_NE(metallic.initializer, nullptr);
  EXPECT_EQ(sexpr(*metallic.initializer), "0.5");
  const VarDecl& bias = *cbuffer.members[3];
  ASSERT_EQ(bias.annotations.size(), 2u);
  EXPECT_EQ(sexpr(*bias.annotations[0].value), "(- 1.5)");
  EXPECT_EQ(sexpr(*bias.annotations[1].value), "(- 2)");

  const VarDecl& main_tex = p->var("_MainTex");
  EXPECT_EQ(main_tex.type, Type::texture2d());
  EXPECT_EQ(main_tex.binding.register_class, 't');
  EXPECT_EQ(main_tex.binding.index, 0u);
  EXPECT_TRUE(main_tex.is_global);
  const VarDecl& sampler = p->var("sampler_MainTex");
  EXPECT_EQ(sampler.type.kind(), TypeKind::SamplerState);
  EXPECT_EQ(sampler.binding.register_class, 's');
  EXPECT_EQ(sampler.binding.space, 1u);
  EXPECT_EQ(p->var("_ShadowTex").type, Type::texture2d());
  EXPECT_EQ(p->var("_ShadowTex").binding.register_class, 0);
  EXPECT_EQ(p->var("_RampTex").type, Type::sampler2d());
  EXPECT_EQ(p->var("_Tint").storage, StorageClass::Uniform);
  const VarDecl& pi = p->var("PI");
  EXPECT_EQ(pi.storage, StorageClass::Static);
  EXPECT_TRUE(pi.is_const);
  EXPECT_EQ(sexpr(*pi.initializer), "3.14159");

  const FunctionDecl& vert = p->function("vert");
  EXPECT_EQ(vert.return_type.kind(), TypeKind::Struct);
  EXPECT_EQ(vert.return_type.struct_decl(), &v2f);
  ASSERT_EQ(vert.params.size(), 1u);
  EXPECT_EQ(vert.params[0]->type.struct_decl(), &appdata);
  ASSERT_EQ(vert.body->statements.size(), 7u);
  const Stmt& loop = *vert.body->statements[5];
  ASSERT_EQ(loop.kind, StmtKind::For);
  ASSERT_EQ(loop.attributes.size(), 1u);
  EXPECT_EQ(loop.attributes[0].name, "unroll");
  const auto& normal = static_cast<const ExprStmt&>(*vert.body->statements[3]);
  EXPECT_EQ(sexpr(*normal.expr),
            "(= (. o worldNormal) (call normalize (call mul (cast float3x3 _ObjectToWorld) (. v normal))))");

  const FunctionDecl& frag = p->function("frag");
  EXPECT_EQ(frag.semantic, "SV_Target");
  EXPECT_EQ(frag.return_type, Type::vector(ScalarType::Half, 4));
  ASSERT_EQ(frag.body->statements.size(), 6u);
  const auto& albedo = static_cast<const DeclStmt&>(*frag.body->statements[2]);
  EXPECT_EQ(sexpr(*albedo.vars[0]->initializer),
            "(* (method _MainTex Sample sampler_MainTex (. i uv)) _Color)");
  const auto& tint = static_cast<const ExprStmt&>(*frag.body->statements[3]);
  EXPECT_EQ(sexpr(*tint.expr), "(*= (. albedo rgb) (. (call tex2D _RampTex (ctor float2 nd 0.5)) rgb))");
  const auto& discard_if = static_cast<const IfStmt&>(*frag.body->statements[4]);
  ASSERT_EQ(discard_if.kind, StmtKind::If);
  EXPECT_EQ(discard_if.then_branch->kind, StmtKind::Discard);
  EXPECT_EQ(discard_if.else_branch, nullptr);
}

TEST(Parser, ScalarVectorAndMatrixTypes) {
  auto p = parse_text(
      "bool b; int i; uint u; dword d; half h; float f; min16float m16; min10float m10; min16int mi; min16uint mu;\n"
      "float1 f1; int3 i3; half4 h4; bool2 b2; min16float3 m3;\n"
      "float2x3 m23; float4x4 m44; half1x1 h11; int3x2 i32;\n"
      "vector<float, 3> v3; matrix<half, 2, 3> hm; vector vd; matrix md;\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->var("b").type, Type::scalar(ScalarType::Bool));
  EXPECT_EQ(p->var("i").type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(p->var("u").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("d").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("h").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("f").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("m16").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("m10").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("mi").type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(p->var("mu").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("f1").type, Type::vector(ScalarType::Float, 1));
  EXPECT_NE(p->var("f1").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("i3").type, Type::vector(ScalarType::Int, 3));
  EXPECT_EQ(p->var("h4").type, Type::vector(ScalarType::Half, 4));
  EXPECT_EQ(p->var("b2").type, Type::vector(ScalarType::Bool, 2));
  EXPECT_EQ(p->var("m3").type, Type::vector(ScalarType::Half, 3));
  const Type& m23 = p->var("m23").type;
  EXPECT_TRUE(m23.is_matrix());
  EXPECT_EQ(m23.rows(), 2u);
  EXPECT_EQ(m23.cols(), 3u);
  EXPECT_EQ(p->var("m44").type, Type::matrix(ScalarType::Float, 4, 4));
  EXPECT_EQ(p->var("h11").type, Type::matrix(ScalarType::Half, 1, 1));
  EXPECT_EQ(p->var("i32").type, Type::matrix(ScalarType::Int, 3, 2));
  EXPECT_EQ(p->var("v3").type, Type::vector(ScalarType::Float, 3));
  EXPECT_EQ(p->var("hm").type, Type::matrix(ScalarType::Half, 2, 3));
  EXPECT_EQ(p->var("vd").type, Type::vector(ScalarType::Float, 4));
  EXPECT_EQ(p->var("md").type, Type::matrix(ScalarType::Float, 4, 4));
}

TEST(Parser, DoubleIsReportedAndReadAsFloat) {
  auto p = parse_text("double x;\ndouble3 y = double3(1, 2, 3);\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:1: double is not supported", "2:1: double is not supported",
                                                    "2:13: double is not supported"}));
  EXPECT_EQ(p->var("x").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("y").type, Type::vector(ScalarType::Float, 3));
}

TEST(Parser, StructAndTypedefNamesAreTypes) {
  auto p = parse_text(
      "struct Light { float3 dir; float3 color; };\n"
      "typedef float3 Color;\n"
      "typedef Light Lamp;\n"
      "Light lights[2];\n"
      "Color tint;\n"
      "float3 f(Lamp l) { Light copy = (Light)0; Color c = (Color)(l.color); return c * copy.color; }\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const auto& light = p->decl<StructDecl>(0);
  const Type& lights = p->var("lights").type;
  ASSERT_EQ(lights.kind(), TypeKind::Array);
  EXPECT_EQ(lights.array_length(), 2u);
  EXPECT_EQ(lights.element().struct_decl(), &light);
  EXPECT_EQ(lights.name(), "Light[2]");
  EXPECT_EQ(p->var("tint").type, Type::vector(ScalarType::Float, 3));
  const FunctionDecl& f = p->function("f");
  EXPECT_EQ(f.params[0]->type.struct_decl(), &light);
  const auto& copy = static_cast<const DeclStmt&>(*f.body->statements[0]);
  EXPECT_EQ(sexpr(*copy.vars[0]->initializer), "(cast Light 0)");
  const auto& c = static_cast<const DeclStmt&>(*f.body->statements[1]);
  EXPECT_EQ(sexpr(*c.vars[0]->initializer), "(cast float3 (. l color))");
}

TEST(Parser, GlobalQualifiersArraysAndDeclarators) {
  auto p = parse_text(
      "static const float2 kKernel[3] = { float2(0, 0), float2(0.5, 0), float2(1, 0) };\n"
      "static const float kWeights[] = { 0.25, 0.5, 0.25 };\n"
      "static const float2 kFlat[] = { 0, 0, 1, 1 };\n"
      "float a, b = 1, c[2];\n"
      "column_major float3x4 cm;\n"
      "static const int N = 2 * 2;\n"
      "float sized[N + 1];\n"
      "sampler s;\n"
      "float m2[2][3];\n"
      "static const int nested[2][2] = { { 1, 2 }, { 3, 4 } };\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const VarDecl& kernel = p->var("kKernel");
  EXPECT_EQ(kernel.type, Type::array(Type::vector(ScalarType::Float, 2), 3));
  EXPECT_EQ(sexpr(*kernel.initializer), "{ (ctor float2 0 0) (ctor float2 0.5 0) (ctor float2 1 0) }");
  // Unsized arrays stay unsized (length 0): semantic analysis counts their initializers.
  EXPECT_EQ(p->var("kWeights").type.array_length(), 0u);
  EXPECT_EQ(p->var("kFlat").type.array_length(), 0u);
  EXPECT_EQ(p->var("a").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("a").initializer, nullptr);
  EXPECT_EQ(sexpr(*p->var("b").initializer), "1");
  EXPECT_EQ(p->var("c").type, Type::array(Type::scalar(ScalarType::Float), 2));
  EXPECT_EQ(p->var("cm").packing, MatrixPacking::ColumnMajor);
  EXPECT_EQ(p->var("cm").type.rows(), 3u);
  EXPECT_EQ(p->var("cm").type.cols(), 4u);
  EXPECT_TRUE(p->var("N").is_const);
  EXPECT_EQ(p->var("N").storage, StorageClass::Static);
  EXPECT_EQ(p->var("sized").type.array_length(), 5u);
  EXPECT_EQ(p->var("s").type, Type::sampler2d());
  const Type& m2 = p->var("m2").type;
  EXPECT_EQ(m2.array_length(), 2u);
  EXPECT_EQ(m2.element().array_length(), 3u);
  EXPECT_EQ(sexpr(*p->var("nested").initializer), "{ { 1 2 } { 3 4 } }");
}

TEST(Parser, FunctionsParametersAndPrototypes) {
  auto p = parse_text(
      "float helper(float x);\n"
      "void vert(in float4 pos : POSITION, out float4 o : SV_Position, inout float k,\n"
      "          uniform float4x4 mvp, centroid float2 uv : TEXCOORD0, float scale = 2.0) {\n"
      "  o = mul(mvp, pos) * scale;\n"
      "}\n"
      "[numthreads(8, 8, 1)] void cs(void) {}\n"
      "float helper(float x) { return x; }\n"
      "float noname(float, int);\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  ASSERT_EQ(p->unit.decls.size(), 5u);
  const auto& prototype = p->decl<FunctionDecl>(0);
  EXPECT_EQ(prototype.body, nullptr);
  ASSERT_EQ(prototype.params.size(), 1u);
  const FunctionDecl& vert = p->function("vert");
  ASSERT_EQ(vert.params.size(), 6u);
  EXPECT_EQ(vert.return_type.kind(), TypeKind::Void);
  EXPECT_TRUE(vert.params[0]->explicit_in);
  EXPECT_EQ(vert.params[0]->direction, ParamDirection::In);
  EXPECT_EQ(vert.params[0]->semantic, "POSITION");
  EXPECT_EQ(vert.params[1]->direction, ParamDirection::Out);
  EXPECT_EQ(vert.params[1]->semantic, "SV_Position");
  EXPECT_EQ(vert.params[2]->direction, ParamDirection::InOut);
  EXPECT_FALSE(vert.params[2]->explicit_in);
  EXPECT_TRUE(vert.params[3]->is_uniform);
  EXPECT_EQ(vert.params[4]->interpolation, Interpolation::Centroid);
  EXPECT_EQ(vert.params[4]->name, "uv");
  ASSERT_NE(vert.params[5]->default_value, nullptr);
  EXPECT_EQ(sexpr(*vert.params[5]->default_value), "2.0");
  const auto& cs = p->decl<FunctionDecl>(2);
  EXPECT_EQ(cs.params.size(), 0u);
  ASSERT_EQ(cs.attributes.size(), 1u);
  EXPECT_EQ(cs.attributes[0].name, "numthreads");
  EXPECT_EQ(sexpr_list(cs.attributes[0].args), " 8 8 1");
  const auto& noname = p->decl<FunctionDecl>(4);
  ASSERT_EQ(noname.params.size(), 2u);
  EXPECT_EQ(noname.params[0]->name, "");
}

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
  std::vector<std::string> spellings = {"0.0", "1.", ".5", "1e5", "1e+5", "1e-5", "1e", "1e+", "1.5.3", ".", "e5",
                                        "0x1p3", "1.0e22", "1.0e23", "9007199254740993.0", "123456789012345.6",
                                        "0.000000000000000000000000001", "1e-22", "1e-23", "00012.500e-3", "1e400",
                                        "1e-400", "4.9e-324", "1.7976931348623157e308", "0e99999", "12a", "1.5f"};
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
  auto p = parse_text("static const uint a = 4294967295u; static const int b = 0xFFFFFFFF;\n"
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
  EXPECT_EQ(big->errors(), (std::vector<std::string>{"1:22: integer literal is too large",
                                                     "2:22: integer literal is too large"}));
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
      "struct Light { float3 color; };\nStructuredBuffer<Light> lights; RWByteAddressBuffer raw; RWTexture3D<uint> grid;\n"
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
      {"struct L { float a; };\nTexture2D<L> t;", "2:11: the texel type of 'Texture2D' must be a scalar or vector, not 'L'"},
      {"Texture2D<float4x4> t;", "1:11: the texel type of 'Texture2D' must be a scalar or vector, not 'float4x4'"},
      {"StructuredBuffer b;", "1:18: expected '<' after 'StructuredBuffer': a structured buffer needs an element type"},
      {"ConstantBuffer<float4> c;", "1:16: ConstantBuffer holds a struct, not 'float4'"},
  };
  for (const auto& [source, error] : cases) EXPECT_EQ(parse_text(source)->errors(), std::vector<std::string>{error}) << source;
}

TEST(Parser, AttributesWithStringsAreIgnoredWithANote) {
  auto p = parse_text("[RootSignature(\"RootFlags(0), \" \"CBV(b0)\")]\nfloat4 f() : SV_Target { return 0; }\n"
                      "[domain(\"tri\")] [partitioning(\"integer\")] void g() {}\n");
  EXPECT_EQ(p->errors(), std::vector<std::string>{});
  std::vector<std::string> notes;
  for (const Diagnostic& d : p->diagnostics.diagnostics())
    if (d.severity == Severity::Note) notes.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
  EXPECT_EQ(notes, (std::vector<std::string>{"1:2: attribute 'RootSignature' is ignored", "3:2: attribute 'domain' is ignored",
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

TEST(Parser, ErrorMessagesArePinned) {
  struct Case {
    const char* source;
    std::vector<std::string> errors;
  };
  const Case cases[] = {
      {"void f() { float x = 1 }", {"1:23: expected ';' after declaration"}},
      {"void f() { x = 1 }", {"1:17: expected ';' after expression"}},
      {"void f() { x = (1 + 2; }", {"1:22: expected ')' to match '('"}},
      {"void f() { x = 1 + ; }", {"1:20: expected an expression"}},
      {"void f() { else x = 1; }", {"1:12: unexpected 'else'"}},
      {"void f() { x = 1 @ 2; }", {"1:18: unknown character '@'"}},
      {"void f(Foo x) {}", {"1:8: 'Foo' is not a type"}},
      {"void f(1) {}", {"1:8: expected a type"}},
      {"float x = 99999999999;", {"1:11: integer literal is too large"}},
      {"double d;", {"1:1: double is not supported"}},
      {"cbuffer C { float4 c : packoffset(r0); };", {"1:35: invalid packoffset 'r0'; write packoffset(cN) or packoffset(cN.y)"}},
      {"cbuffer C { float c : packoffset(c0.q); };", {"1:37: invalid packoffset component 'q'; use x, y, z or w"}},
      {"float4 c : packoffset(c0);", {"1:12: packoffset is only allowed on the members of a cbuffer"}},
      {"void f(int i) { switch (i) { i = 2; case 0: break; } i = 1; }", {"1:30: expected 'case' or 'default' in a switch"}},
      {"void f(int i) { switch (i) { case 0 break; } }", {"1:36: expected ':' after the case value"}},
      {"void f() { goto end; }", {"1:12: goto is not supported"}},
      {"class C {};", {"1:1: 'class' is not supported"}},
      {"void f() { if x) {} }", {"1:15: expected '(' after 'if'"}},
      {"void f() { int a[2] = { 1, 2 ; }", {"1:30: expected '}' to match '{'"}},
      {"float4 f() : { return 0; }", {"1:14: expected a semantic or register after ':'"}},
      {"Texture2D t : register(x0);", {"1:24: invalid register 'x0'"}},
      {"struct S { float a; }\nfloat b;", {"1:22: expected ';' after struct declaration"}},
      {"vector<float, 5> v;", {"1:15: vector size must be between 1 and 4"}},
      {"float a[0];", {"1:9: array size must be positive"}},
      {"void f() { float a[] ; }", {"1:18: an unsized array needs an initializer list"}},
      {"float f() { return 1 }", {"1:21: expected ';' after return statement"}},
      {"void f() { x = a ? b; }", {"1:21: expected ':' in conditional expression"}},
      {"void f() { x = {1, 2}; }", {"1:16: initializer lists are only allowed in initializers"}},
      {"void v;", {"1:1: 'void' is only valid as a function return type"}},
      {"+", {"1:1: expected a declaration"}},
      {"void f() { x = a.; }", {"1:18: expected a member name after '.'"}},
      {"void f() { do x++; until (x); }", {"1:20: expected 'while' after the body of 'do'"}},
      {"void f() {", {"1:11: expected '}' to match '{'"}},
      {"void f() { float3 = 1; }", {"1:19: expected a name"}},
      {"void f() { x = \"s\"; }", {"1:16: string literals are only allowed in annotations"}},
  };
  for (const Case& c : cases) {
    auto p = parse_text(c.source);
    EXPECT_EQ(p->errors(), c.errors) << c.source;
  }
}

TEST(Parser, RegistersAttributesAndQualifierDiagnostics) {
  auto p = parse_text(
      "Texture2D a : register(T3);\n"
      "SamplerState b : register(ps_5_0, s1);\n"
      "RWTexture2D<float4> c : register(u2, space4);\n"
      "void f(float x) { [unroll(4)] for (int i = 0; i < 4; i++) {} [loop] while (x > 0) x -= 1; [flatten] if (x) {} }\n");
  EXPECT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->var("a").binding.register_class, 't');
  EXPECT_EQ(p->var("a").binding.index, 3u);
  EXPECT_EQ(p->var("b").binding.register_class, 's');
  EXPECT_EQ(p->var("b").binding.index, 1u);
  EXPECT_EQ(p->var("c").binding.register_class, 'u');
  EXPECT_EQ(p->var("c").binding.space, 4u);
  EXPECT_EQ(p->var("c").type, Type::buffer(BufferKind::RWTexture2D, Type::vector(ScalarType::Float, 4)));
  const auto& body = p->function("f").body->statements;
  ASSERT_EQ(body.size(), 3u);
  ASSERT_EQ(body[0]->attributes.size(), 1u);
  EXPECT_EQ(sexpr_list(body[0]->attributes[0].args), " 4");
  EXPECT_EQ(body[1]->attributes[0].name, "loop");
  EXPECT_EQ(body[2]->attributes[0].name, "flatten");

  auto bad = parse_text(
      "Texture2D t : register(t0, zone1);\n"
      "out float g;\n"
      "void f(static float x) {}\n"
      "struct S { float a; };\n"
      "struct S { float b; };\n"
      "float h[] = {};\n"
      "struct P { float p : register(t0); };\n"
      "float k <float UIMin = ;> = 1.0;\n"
      "float after;\n");
  EXPECT_EQ(bad->errors(), (std::vector<std::string>{
                               "1:28: invalid register space 'zone1'",
                               "2:1: 'out' is only allowed on parameters",
                               "3:8: 'static' is not allowed here",
                               "5:8: redefinition of type 'S'",
                               "6:7: an unsized array needs a non-empty initializer list",
                               "7:22: register bindings are only allowed on global variables and cbuffers",
                               "8:24: expected a literal in annotation",
                           }));
  EXPECT_NO_THROW(bad->var("k"));
  EXPECT_EQ(sexpr(*bad->var("k").initializer), "1.0");
  EXPECT_NO_THROW(bad->var("after"));
}

TEST(Parser, UnmatchedParenthesisHasANoteAtTheOpening) {
  auto p = parse_text("void f() {\n  x = foo(1,\n 2;\n}\n");
  const auto& d = p->diagnostics.diagnostics();
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].to_string(), "test.hlsl:3:3: error: expected ')' to match '('");
  EXPECT_EQ(d[1].to_string(), "test.hlsl:2:10: note: to match this '('");
}

TEST(Parser, RecoveryReportsEachMistakeOnce) {
  auto p = parse_text(
      "struct V { float4 pos : SV_Position; float2 uv : TEXCOORD0 };\n"  // 1: missing ';' after field
      "float4 tint = float4(1, 1, 1, 1);\n"
      "float4 frag(V i) : SV_Target {\n"
      "  float4 c = tint * ;\n"                                             // 4: missing operand
      "  c.rgb = saturate(c.rgb;\n"                                        // 5: missing ')'
      "  if (c.a > 0.5) { c.a = 1; }\n"
      "  return c;\n"
      "}\n"
      "float after;\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:59: expected ';' after declaration",
                                                   "4:21: expected an expression",
                                                   "5:25: expected ')' to match '('"}));
  ASSERT_EQ(p->unit.decls.size(), 4u);
  EXPECT_EQ(p->decl<StructDecl>(0).fields.size(), 2u);
  const FunctionDecl& frag = p->function("frag");
  ASSERT_EQ(frag.body->statements.size(), 2u);
  EXPECT_EQ(frag.body->statements[0]->kind, StmtKind::If);
  EXPECT_EQ(frag.body->statements[1]->kind, StmtKind::Return);
  EXPECT_EQ(p->var("after").type, Type::scalar(ScalarType::Float));
}

TEST(Parser, RecoveryInsideConditionsAndInitializerLists) {
  auto p = parse_text(
      "static const float k[3] = { 1, 2 +, 3 };\n"
      "void f(float x) {\n"
      "  if (x > ) { x = 1; } else { x = 2; }\n"
      "  for (int i = 0; i < ; i++) { x += i; }\n"
      "  while (x +) x -= 1;\n"
      "  x = 3;\n"
      "}\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:35: expected an expression", "3:11: expected an expression",
                                                   "4:23: expected an expression",
                                                   "5:13: expected an expression"}));
  const FunctionDecl& f = p->function("f");
  ASSERT_FALSE(f.body->statements.empty());
  const Stmt& last = *f.body->statements.back();
  ASSERT_EQ(last.kind, StmtKind::Expr);
  EXPECT_EQ(sexpr(*static_cast<const ExprStmt&>(last).expr), "(= x 3)");
}

TEST(Parser, UnknownCharactersAreReportedOnceEach) {
  auto p = parse_text("float a = 1; $ float b = 2;\nvoid f() { float c = 1 ` 2; @ }\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:14: unknown character '$'", "2:24: unknown character '`'",
                                                   "2:29: unknown character '@'"}));
}

TEST(Parser, DeepNestingIsOneErrorNotAStackOverflow) {
  const int kDepth = 10000;
  const auto start = std::chrono::steady_clock::now();

  auto parens = parse_text("float x = " + std::string(kDepth, '(') + "1" + std::string(kDepth, ')') + ";\nfloat y;\n");
  ASSERT_EQ(parens->errors().size(), 1u);
  EXPECT_NE(parens->errors()[0].find("nesting is too deep (more than 256 levels)"), std::string::npos);
  EXPECT_NO_THROW(parens->var("y"));

  std::string braces = "void f() " + std::string(kDepth, '{') + std::string(kDepth, '}') + "\nfloat y;\n";
  auto blocks = parse_text(braces);
  EXPECT_EQ(blocks->errors(), std::vector<std::string>{"1:267: nesting is too deep (more than 256 levels)"});
  EXPECT_NO_THROW(blocks->var("y"));

  auto lists = parse_text("float z[1] = " + std::string(kDepth, '{') + "1" + std::string(kDepth, '}') + ";\nfloat y;\n");
  EXPECT_EQ(lists->errors().size(), 1u);
  EXPECT_NO_THROW(lists->var("y"));

  // Unbalanced, unary chains, long operator chains, else-if chains and member chains.
  std::string unary(kDepth, '-');
  auto minus = parse_text("float m = " + unary + "1;\nfloat y;\n");
  EXPECT_EQ(minus->errors().size(), 1u);
  auto open_only = parse_text("float m = " + std::string(kDepth, '(') + ";\n");
  EXPECT_GE(open_only->errors().size(), 1u);
  std::string chain = "float m = 1";
  for (int i = 0; i < kDepth; ++i) chain += " + 1";
  auto sum = parse_text(chain + ";\nfloat y;\n");
  EXPECT_EQ(sum->errors().size(), 1u);
  EXPECT_NO_THROW(sum->var("y"));
  std::string elses = "void f(int i) { ";
  for (int i = 0; i < kDepth; ++i) elses += "if (i == 0) i = 1; else ";
  auto else_if = parse_text(elses + "i = 2; }\nfloat y;\n");
  EXPECT_EQ(else_if->errors().size(), 1u);
  EXPECT_NO_THROW(else_if->var("y"));
  std::string members = "void f(float4 v) { v = v";
  for (int i = 0; i < kDepth; ++i) members += ".x";
  auto swizzles = parse_text(members + "; }\n");
  EXPECT_EQ(swizzles->errors().size(), 1u);
  std::string templates = "Texture2D";
  for (int i = 0; i < kDepth; ++i) templates += "<Texture2D";
  auto nested_types = parse_text(templates + " t;\n");
  EXPECT_GE(nested_types->errors().size(), 1u);

  const auto elapsed = std::chrono::steady_clock::now() - start;
  EXPECT_LT(std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count(), 2000);
}

TEST(Parser, ModeratelyDeepNestingIsFine) {
  auto p = parse_text("float x = " + std::string(100, '(') + "1" + std::string(100, ')') + ";\n");
  EXPECT_EQ(p->errors(), std::vector<std::string>{});
}

TEST(Parser, EveryPrefixOfAShaderParsesWithoutCrashing) {
  auto full = parse_text(kUnityShader);
  for (size_t n = 0; n < full->tokens.size(); ++n) {
    std::vector<Token> prefix(full->tokens.begin(), full->tokens.begin() + std::ptrdiff_t(n));
    DiagnosticEngine diagnostics(full->sources);
    TranslationUnit unit = parse(prefix, diagnostics);  // no EndOfFile token at all
    prefix.push_back(full->tokens.back());
    DiagnosticEngine diagnostics2(full->sources);
    unit = parse(prefix, diagnostics2);
    EXPECT_LE(diagnostics2.error_count(), n + 1);
  }
}

TEST(Parser, RandomTokenStreamsTerminate) {
  // Tokens from a pool that covers every construct, shuffled: the parser must neither crash,
  // nor hang, nor read out of bounds (ASan runs this), and report at most one error per token.
  auto pool = parse_text(std::string(kUnityShader) +
                         "void g() { switch (1) {} do {} while (0); x = a ? b : c; x <<= 1; x >>= 1; }\n"
                         "float2x2 m = {1, 2, 3, 4}; struct S; typedef S T; vector<float, 2> v; matrix<int, 2, 2> mi;"
                         "class else goto case default packoffset register 1.5h 0x1Fu \"s\" # ## ` @ [ ] ( ) { } < > >> ;");
  std::vector<Token> source = pool->tokens;
  source.pop_back();
  std::mt19937 rng(12345);
  for (int round = 0; round < 300; ++round) {
    std::vector<Token> stream;
    const size_t length = rng() % 200;
    for (size_t i = 0; i < length; ++i) stream.push_back(source[rng() % source.size()]);
    if (round % 2 == 0) stream.push_back(pool->tokens.back());
    DiagnosticEngine diagnostics(pool->sources);
    TranslationUnit unit = parse(stream, diagnostics);
    EXPECT_LE(diagnostics.error_count(), stream.size() + 1);
  }
  DiagnosticEngine empty_diagnostics(pool->sources);
  EXPECT_TRUE(parse({}, empty_diagnostics).decls.empty());
}


// ---------------------------------------------------------------------------------------------
// Productions and recovery alone, through parser_internal.h

using parser_detail::kSkipCloseAngle;
using parser_detail::kSkipCloseBrace;
using parser_detail::kSkipOpenBrace;
using parser_detail::kSkipSemicolon;
using parser_detail::Parser;
using parser_detail::SkipEnd;

// "line:col text" of the token the parser is at.
std::string at(const Parser& parser) {
  const Token& token = parser.cur();
  return std::to_string(token.loc.line) + ":" + std::to_string(token.loc.column) + " " + std::string(token.text);
}

TEST(ParserProductions, AnExpressionAloneEndsBeforeTheFirstTokenNotInIt) {
  auto lexed = lex_text("a + b * -c[i].x, d = e ? f : g) h");
  Parser parser(lexed->tokens, lexed->diagnostics);
  const ExprPtr expr = parser.parse_expression();
  ASSERT_NE(expr, nullptr);
  EXPECT_EQ(sexpr(*expr), "(, (+ a (* b (- (. ([] c i) x)))) (= d (? e f g)))");
  EXPECT_EQ(at(parser), "1:31 )");
  EXPECT_EQ(lexed->errors(), std::vector<std::string>{});
}

TEST(ParserProductions, AFailedExpressionStopsWhereItFailedWithoutSkipping) {
  auto lexed = lex_text("a * (b + ) ; c");
  Parser parser(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(parser.parse_expression(), nullptr);
  EXPECT_EQ(lexed->errors(), std::vector<std::string>{"1:10: expected an expression"});
  EXPECT_EQ(at(parser), "1:10 )");  // skipping is the caller's recovery point's
}

TEST(ParserProductions, AStatementAlone) {
  auto lexed = lex_text("if (x) return 1; else { y = 2; } z;");
  Parser parser(lexed->tokens, lexed->diagnostics);
  const StmtPtr statement = parser.parse_statement();
  ASSERT_NE(statement, nullptr);
  ASSERT_EQ(statement->kind, StmtKind::If);
  const auto& branch = static_cast<const IfStmt&>(*statement);
  EXPECT_EQ(sexpr(*branch.condition), "x");
  ASSERT_EQ(branch.then_branch->kind, StmtKind::Return);
  EXPECT_EQ(sexpr(*static_cast<const ReturnStmt&>(*branch.then_branch).value), "1");
  ASSERT_EQ(branch.else_branch->kind, StmtKind::Block);
  EXPECT_EQ(static_cast<const BlockStmt&>(*branch.else_branch).statements.size(), 1u);
  EXPECT_EQ(at(parser), "1:34 z");
  EXPECT_EQ(lexed->errors(), std::vector<std::string>{});
}

TEST(ParserProductions, ABadIfConditionIsSkippedAsAGroupAndTheBodyStillRead) {
  auto lexed = lex_text("if (a b) c = 1; d;");
  Parser parser(lexed->tokens, lexed->diagnostics);
  const StmtPtr statement = parser.parse_statement();
  ASSERT_NE(statement, nullptr);  // recovered already: an empty statement, not a failure
  EXPECT_EQ(statement->kind, StmtKind::Empty);
  EXPECT_EQ(lexed->errors(), std::vector<std::string>{"1:7: expected ')' to match '('"});
  EXPECT_EQ(at(parser), "1:17 d");
}

TEST(ParserProductions, AStructFromOneProductionIsATypeInTheNext) {
  auto lexed = lex_text("struct S { float a; }; (S)x");
  Parser parser(lexed->tokens, lexed->diagnostics);
  EXPECT_TRUE(parser.parse_top_level());
  const ExprPtr expr = parser.parse_expression();
  ASSERT_NE(expr, nullptr);
  EXPECT_EQ(sexpr(*expr), "(cast S x)");
  EXPECT_TRUE(parser.at_end());
}

TEST(ParserSkipUntil, AStopTokenInsideABracketedGroupDoesNotCount) {
  auto lexed = lex_text("f(a; b) ; c }");
  Parser parser(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(parser.skip_until({.stops = kSkipSemicolon | kSkipCloseBrace}), SkipEnd::Stop);
  EXPECT_EQ(at(parser), "1:9 ;");
  EXPECT_EQ(parser.skip_until({.stops = kSkipSemicolon, .consume = true}), SkipEnd::Stop);
  EXPECT_EQ(at(parser), "1:11 c");
}

TEST(ParserSkipUntil, ABarrierCountsAtAnyDepth) {
  auto lexed = lex_text("a (b [c ; d] e) f ;");
  Parser parser(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(parser.skip_until({.barriers = kSkipSemicolon}), SkipEnd::Barrier);
  EXPECT_EQ(at(parser), "1:9 ;");
  auto again = lex_text("a (b [c ; d] e) f ;");
  Parser whole(again->tokens, again->diagnostics);
  EXPECT_EQ(whole.skip_until({.stops = kSkipSemicolon}), SkipEnd::Stop);
  EXPECT_EQ(at(whole), "1:19 ;");
}

TEST(ParserSkipUntil, AtFileScopeABraceGroupEndsTheSkipButAParenthesisGroupDoesNot) {
  auto lexed = lex_text("int f(int a) { return a; } ; float g;");
  Parser parser(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(parser.skip_until({.stops = kSkipSemicolon, .after_braces = true}), SkipEnd::AfterBraces);
  EXPECT_EQ(at(parser), "1:28 ;");
}

TEST(ParserSkipUntil, AFlatSkipDoesNotGroupBrackets) {
  const std::string text = "float a = (1 > b ; }";
  auto lexed = lex_text(text);
  Parser flat(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(flat.skip_until({.stops = kSkipCloseAngle, .barriers = kSkipOpenBrace | kSkipCloseBrace, .flat = true}),
            SkipEnd::Stop);
  EXPECT_EQ(at(flat), "1:14 >");
  Parser grouped(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(grouped.skip_until({.stops = kSkipCloseAngle, .barriers = kSkipOpenBrace | kSkipCloseBrace}),
            SkipEnd::Barrier);
  EXPECT_EQ(at(grouped), "1:20 }");
}

TEST(ParserSkipUntil, EndsAtTheEndOfInputAndNeverRecursesIntoBrackets) {
  auto unclosed = lex_text("a ( ; b");
  Parser parser(unclosed->tokens, unclosed->diagnostics);
  EXPECT_EQ(parser.skip_until({.stops = kSkipSemicolon}), SkipEnd::EndOfFile);
  EXPECT_TRUE(parser.at_end());

  // Far deeper than kMaxParseDepth, or than any stack would take one call per bracket.
  const std::string deep = std::string(100000, '(') + ";" + std::string(100000, ')') + " x ;";
  auto lexed = lex_text(deep);
  Parser skipper(lexed->tokens, lexed->diagnostics);
  EXPECT_EQ(skipper.skip_until({.stops = kSkipSemicolon}), SkipEnd::Stop);
  EXPECT_EQ(at(skipper), "1:" + std::to_string(deep.size()) + " ;");
}


// ---------------------------------------------------------------------------------------------
// The nodes' memory

TEST(AstArena, NodesMadeInAScopeComeFromItsArenaOneAfterAnother) {
  AstArena arena;
  std::unique_ptr<NameExpr> first, second;
  {
    AstArenaScope scope(arena);
    first = std::make_unique<NameExpr>(Loc{});
    second = std::make_unique<NameExpr>(Loc{});
  }
  const auto gap = reinterpret_cast<const char*>(second.get()) - reinterpret_cast<const char*>(first.get());
  EXPECT_GT(gap, 0);
  EXPECT_LE(size_t(gap), sizeof(NameExpr) + 2 * AstArena::kAlignment);
  // Outside any scope the heap is back; both kinds of node are deleted the same way.
  auto from_heap = std::make_unique<NameExpr>(Loc{});
  from_heap->name = std::string(100, 'n');
  first->name = std::string(100, 'f');
  first.reset();
  from_heap.reset();
}

TEST(AstArena, ScopesNestAndRestoreTheOuterArena) {
  AstArena outer_arena, inner_arena;
  AstArenaScope outer(outer_arena);
  auto before = std::make_unique<BlockStmt>(Loc{});
  {
    AstArenaScope inner(inner_arena);
    auto inside = std::make_unique<BlockStmt>(Loc{});
  }
  auto after = std::make_unique<BlockStmt>(Loc{});
  const auto gap = reinterpret_cast<const char*>(after.get()) - reinterpret_cast<const char*>(before.get());
  EXPECT_GT(gap, 0);
  EXPECT_LE(size_t(gap), sizeof(BlockStmt) + 2 * AstArena::kAlignment);
}

TEST(AstArena, ManyAndLargeNodesAndUnitsMovedOver) {
  // More nodes than one block holds, names that own heap memory, a unit assigned over a
  // unit that holds a tree (the old tree goes before its arena).
  TranslationUnit unit;
  for (int round = 0; round < 3; ++round) {
    TranslationUnit next;
    {
      AstArenaScope scope(next.arena);
      for (int i = 0; i < 5000; ++i) {
        auto var = std::make_unique<VarDecl>(Loc{});
        var->name = "a_name_long_enough_for_the_heap_" + std::to_string(i);
        auto init = std::make_unique<InitListExpr>(Loc{});
        for (int k = 0; k < 3; ++k) init->elements.push_back(std::make_unique<IntLiteralExpr>(Loc{}));
        var->initializer = std::move(init);
        next.decls.push_back(std::move(var));
      }
    }
    unit = std::move(next);
    ASSERT_EQ(unit.decls.size(), 5000u);
    EXPECT_EQ(unit.decls.back()->name, "a_name_long_enough_for_the_heap_4999");
  }
  TranslationUnit moved(std::move(unit));
  EXPECT_EQ(moved.decls.size(), 5000u);
  // An arena's very large request gets a block of its own; allocation goes on in the current one.
  AstArena arena;
  void* small = arena.allocate(16);
  void* large = arena.allocate(1 << 20);
  void* small_again = arena.allocate(16);
  EXPECT_NE(large, nullptr);
  EXPECT_EQ(static_cast<char*>(small_again) - static_cast<char*>(small), 16);
}

}  // namespace
}  // namespace xshade::hlsl
