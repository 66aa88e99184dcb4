// Semantic analysis, one test per rule: types, conversions, overloads (DXC's costs as a table),
// l-values, entry points, reach.
// Why this file is long: it is one short case per rule, read as the list of the rules.
#include "hlsl_like/sema.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/intrinsics.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl {
namespace {

using Strings = std::vector<std::string>;

// Source text through the real preprocessor and parser into analyze(). `#pragma vertex NAME`
// and `#pragma fragment NAME` name the entry points, as the compiler driver does.
struct Analyzed {
  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  std::unique_ptr<Preprocessor> preprocessor;
  std::vector<Token> tokens;
  TranslationUnit unit;
  EntryPoints entry_points;

  // "line:col: severity: message" for every diagnostic, in order.
  Strings messages() const {
    Strings out;
    for (const Diagnostic& d : diagnostics.diagnostics()) {
      std::string text = d.to_string();
      const std::string prefix = "test.hlsl:";
      if (text.rfind(prefix, 0) == 0) text = text.substr(prefix.size());
      out.push_back(text);
    }
    return out;
  }

  const FunctionDecl& function(const std::string& name) const {
    for (const auto& decl : unit.decls) {
      if (decl && decl->kind == DeclKind::Function && decl->name == name &&
          static_cast<const FunctionDecl&>(*decl).body) {
        return static_cast<const FunctionDecl&>(*decl);
      }
    }
    throw std::runtime_error("no function " + name);
  }
  const VarDecl& global(const std::string& name) const {
    for (const auto& decl : unit.decls) {
      if (decl && decl->kind == DeclKind::Var && decl->name == name) return static_cast<const VarDecl&>(*decl);
    }
    throw std::runtime_error("no global " + name);
  }
  // The statement at `index` of the body of `name`.
  const Stmt& statement(const std::string& name, size_t index) const {
    return *function(name).body->statements.at(index);
  }
  const Expr& expression(const std::string& name, size_t index) const {
    const Stmt& stmt = statement(name, index);
    if (stmt.kind == StmtKind::Expr) return *static_cast<const ExprStmt&>(stmt).expr;
    if (stmt.kind == StmtKind::Return) return *static_cast<const ReturnStmt&>(stmt).value;
    if (stmt.kind == StmtKind::Decl) return *static_cast<const DeclStmt&>(stmt).vars.at(0)->initializer;
    throw std::runtime_error("no expression");
  }
  const VarDecl& local(const std::string& name, size_t index) const {
    return *static_cast<const DeclStmt&>(statement(name, index)).vars.at(0);
  }
};

std::unique_ptr<Analyzed> analyze_source(const std::string& text) {
  auto analyzed = std::make_unique<Analyzed>();
  const uint32_t file = analyzed->sources.add("test.hlsl", text);
  analyzed->preprocessor = std::make_unique<Preprocessor>(analyzed->sources, analyzed->diagnostics, PreprocessorOptions{});
  analyzed->tokens = analyzed->preprocessor->run(file);
  analyzed->unit = parse(analyzed->tokens, analyzed->diagnostics);
  EntryPointNames names;
  for (const Pragma& pragma : analyzed->preprocessor->pragmas()) {
    if (pragma.args.empty()) continue;
    if (pragma.name == "vertex") {
      names.vertex = std::string(pragma.args[0].text);
      names.vertex_loc = pragma.args[0].loc;
    } else if (pragma.name == "fragment") {
      names.fragment = std::string(pragma.args[0].text);
      names.fragment_loc = pragma.args[0].loc;
    }
  }
  analyzed->entry_points = analyze(analyzed->unit, names, analyzed->diagnostics);
  return analyzed;
}

Strings messages_of(const std::string& text) { return analyze_source(text)->messages(); }

// An expression tree as an S-expression; implicit conversions show as (to TYPE operand).
std::string dump(const Expr* e);

std::string dump_list(const AstVector<ExprPtr>& list) {
  std::string out;
  for (const ExprPtr& item : list) out += " " + dump(item.get());
  return out;
}

std::string dump(const Expr* e) {
  if (!e) return "null";
  switch (e->kind) {
    case ExprKind::IntLiteral: return std::to_string(static_cast<const IntLiteralExpr*>(e)->value);
    case ExprKind::FloatLiteral: return static_cast<const FloatLiteralExpr*>(e)->spelling;
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr*>(e)->value ? "true" : "false";
    case ExprKind::Name: return static_cast<const NameExpr*>(e)->name;
    case ExprKind::Unary: {
      const auto* x = static_cast<const UnaryExpr*>(e);
      static const char* const kOps[] = {"+", "-", "!", "~", "pre++", "pre--", "post++", "post--"};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->operand.get()) + ")";
    }
    case ExprKind::Binary: {
      const auto* x = static_cast<const BinaryExpr*>(e);
      static const char* const kOps[] = {"+", "-", "*", "/", "%", "<<", ">>", "&", "|", "^", "&&", "||",
                                         "<", ">", "<=", ">=", "==", "!=", ","};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->lhs.get()) + " " + dump(x->rhs.get()) + ")";
    }
    case ExprKind::Assign: {
      const auto* x = static_cast<const AssignExpr*>(e);
      static const char* const kOps[] = {"=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->target.get()) + " " + dump(x->value.get()) + ")";
    }
    case ExprKind::Conditional: {
      const auto* x = static_cast<const ConditionalExpr*>(e);
      return "(? " + dump(x->condition.get()) + " " + dump(x->then_value.get()) + " " + dump(x->else_value.get()) + ")";
    }
    case ExprKind::Call: {
      const auto* x = static_cast<const CallExpr*>(e);
      if (x->object) return "(." + x->callee + " " + dump(x->object.get()) + dump_list(x->args) + ")";
      if (x->call_kind == CallKind::Constructor) return "(" + x->constructed.name() + dump_list(x->args) + ")";
      return "(" + x->callee + dump_list(x->args) + ")";
    }
    case ExprKind::Member: {
      const auto* x = static_cast<const MemberExpr*>(e);
      return "(. " + dump(x->object.get()) + " " + x->member + ")";
    }
    case ExprKind::Index: {
      const auto* x = static_cast<const IndexExpr*>(e);
      return "([] " + dump(x->object.get()) + " " + dump(x->index.get()) + ")";
    }
    case ExprKind::Cast: {
      const auto* x = static_cast<const CastExpr*>(e);
      return "(cast " + x->target.name() + " " + dump(x->operand.get()) + ")";
    }
    case ExprKind::InitList: {
      const auto* x = static_cast<const InitListExpr*>(e);
      return "({} " + x->type.name() + dump_list(x->elements) + ")";
    }
    case ExprKind::Conversion: {
      const auto* x = static_cast<const ConversionExpr*>(e);
      return "(to " + x->type.name() + " " + dump(x->operand.get()) + ")";
    }
  }
  return "?";
}

// `expr` as the only statement of a function after `globals`: its type, its tree and the
// diagnostics. Globals are on line 1, the function on line 2: "void t() { " is 11 columns.
struct Probe {
  std::string type;
  std::string tree;
  Strings messages;
};

Probe probe(const std::string& globals, const std::string& expr) {
  auto analyzed = analyze_source(globals + "\nvoid t() { " + expr + "; }\n");
  Probe result;
  result.messages = analyzed->messages();
  const auto& body = analyzed->function("t").body->statements;
  if (!body.empty() && body.back() && body.back()->kind == StmtKind::Expr) {
    const Expr* e = static_cast<const ExprStmt&>(*body.back()).expr.get();
    result.type = e ? e->type.name() : "null";
    result.tree = dump(e);
  }
  return result;
}

std::string type_of(const std::string& globals, const std::string& expr) {
  Probe result = probe(globals, expr);
  EXPECT_EQ(result.messages, Strings{}) << expr;
  return result.type;
}

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
  EXPECT_EQ(messages_of("void t() {\n  float3 x = foo * 2 + 1;\n}\n"),
            (Strings{"2:14: error: unknown name 'foo'"}));
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
  auto a = analyze_source("cbuffer C { float4 tint; };\nstatic float k = 2;\nfloat4 t(float s) { return tint * s * k; }\n");
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
  EXPECT_EQ(messages_of("struct A { float x; };\nstruct B { float x; };\nvoid t(A a) { B b = a; float f = a; }\n"),
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
  auto a = analyze_source("void t(int n, float x) { while (n) { n--; } if (x) {} do {} while (false); for (;;) { break; } }");
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
  auto a = analyze_source("void t(float3 v, int i, float f, float3 w) {\n  v *= 2;\n  i *= 0.5;\n  f += w;\n  v += f;\n}\n");
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
  auto a = analyze_source("float3 f(float4 v) {\n  return v;\n}\nvoid g() {\n  return 1;\n}\nfloat h() {\n  return;\n}\n");
  EXPECT_EQ(a->messages(),
            (Strings{"2:10: warning: implicit truncation of vector type from 'float4' to 'float3'",
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
  EXPECT_EQ(dump(&a->expression("t", 1)), "({} float2[2] (float2 (to float 0) (to float 1)) (float2 (to float 1) (to float 0)))");
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
  EXPECT_EQ(messages_of("static const float k;\nvoid t() { const int n; }\n"),
            (Strings{"1:20: error: static const 'k' needs an initializer", "2:22: error: const 'n' needs an initializer"}));
}

// ---------------------------------------------------------------------------------------------
// Members and indexing

TEST(SemaMembers, StructFields) {
  auto a = analyze_source("struct S { float a; float3 b; };\nfloat3 t(S s) { return s.b; }\nvoid u(S s) { s.c = 1; }\n");
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
  auto a = analyze_source("float4x4 m;\nfloat2 t() { return m._m00_m11; }\nfloat u() { return m._44; }\n"
                          "float3 w() { return m._12_21_34; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("t", 0))), (std::vector<uint8_t>{0, 5}));
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("u", 0))), (std::vector<uint8_t>{15}));
  EXPECT_EQ(a->expression("u", 0).type.name(), "float");
  EXPECT_EQ(swizzle_of(static_cast<const MemberExpr&>(a->expression("w", 0))), (std::vector<uint8_t>{1, 4, 11}));
  EXPECT_EQ(probe("float2x2 m;", "m._m22").messages, (Strings{"2:14: error: swizzle '_m22' is out of range for 'float2x2'"}));
  EXPECT_EQ(probe("float2x3 m;", "m._13").type, "float");
  EXPECT_EQ(probe("float2x3 m;", "m._31").messages, (Strings{"2:14: error: swizzle '_31' is out of range for 'float2x3'"}));
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

TEST(SemaCalls, ConstructorsCountComponents) {
  EXPECT_EQ(type_of("float2 p;", "float4(p, 0, 1)"), "float4");
  EXPECT_EQ(probe("float2 p;", "float4(p, 0, 1)").tree, "(float4 p (to float 0) (to float 1))");
  EXPECT_EQ(probe("", "float3(1)").tree, "(float3 (to float3 1))");
  EXPECT_EQ(type_of("", "float2x2(1, 0, 0, 1)"), "float2x2");
  EXPECT_EQ(type_of("float2 a; float2 b;", "float2x2(a, b)"), "float2x2");
  EXPECT_EQ(probe("", "float3(1, 2)").messages, (Strings{"2:12: error: 'float3' constructor needs 3 components, 2 given"}));
  EXPECT_EQ(probe("float3 v;", "float4(v, 1, 2)").messages,
            (Strings{"2:12: error: 'float4' constructor needs 4 components, 5 given"}));
}

// DXC's pick among user overloads, case by case: the candidates, the arguments' declarations,
// the call's arguments, and the signature DXC calls (or "ambiguous"). DXC sums a cost per
// argument (truncation >> int -> float >> float -> int >> int <-> uint >> half -> float >> splat;
// literals fit their family exactly) and an equal lowest sum is ambiguous.
struct OverloadCase {
  const char* overloads;
  const char* locals;
  const char* args;
  const char* dxc_pick;
};

std::string pick_of(const OverloadCase& c) {
  auto a = analyze_source(std::string(c.overloads) + "\nvoid t() { " + c.locals + " f(" + c.args + "); }\n");
  for (const std::string& message : a->messages())
    if (message.find("ambiguous call") != std::string::npos) return "ambiguous";
  for (const std::string& message : a->messages())
    if (message.find("error") != std::string::npos) return message;
  const FunctionDecl& t = a->function("t");
  const auto& call = static_cast<const CallExpr&>(*static_cast<const ExprStmt&>(*t.body->statements.back()).expr);
  return call.function ? sema_detail::function_signature(*call.function) : "none";
}

TEST(SemaCalls, OverloadsAreRankedAsDxcRanksThem) {
  const OverloadCase cases[] = {
      // Unity's PositivePow(float3, float): a splat costs less than a truncation.
      {"void f(float a, float b) {}\nvoid f(float3 a, float3 b) {}", "float3 v; float s;", "v, s", "void f(float3, float3)"},
      {"void f(float a) {}\nvoid f(int a) {}", "bool b;", "b", "ambiguous"},
      {"void f(float a) {}\nvoid f(int a) {}", "half h;", "h", "void f(float)"},
      {"void f(float a) {}\nvoid f(int a) {}", "uint u;", "u", "void f(int)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "1", "void f(int)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "1.0", "void f(float)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "-2.5", "void f(float)"},
      {"void f(float2 a) {}\nvoid f(float4 a) {}", "float3 v;", "v", "void f(float2)"},
      {"void f(float a) {}\nvoid f(float4 a) {}", "float2 v;", "v", "void f(float)"},
      {"void f(half a) {}\nvoid f(float a) {}", "int i;", "i", "void f(float)"},
      {"void f(half a) {}\nvoid f(float a) {}", "", "1.0", "ambiguous"},
      {"void f(half a) {}\nvoid f(float a) {}", "half h;", "h", "void f(half)"},
      {"void f(int2 a) {}\nvoid f(float2 a) {}", "uint2 u;", "u", "void f(int2)"},
      {"void f(int2 a) {}\nvoid f(float2 a) {}", "half2 h;", "h", "void f(float2)"},
      {"void f(float3x3 a) {}\nvoid f(float4x4 a) {}", "float4x3 m;", "m", "void f(float3x3)"},
      {"void f(float a) {}\nvoid f(float2x2 a) {}", "float1x1 m;", "m", "void f(float)"},
      {"void f(int a, float b) {}\nvoid f(float a, int b) {}", "int i;", "i, i", "ambiguous"},
      {"void f(float3 a) {}\nvoid f(half3 a) {}", "", "1", "ambiguous"},
      {"void f(float3 a) {}\nvoid f(half3 a) {}", "", "1.0", "ambiguous"},
      // Two splats cost less than one int -> float conversion (DXC's own example).
      {"void f(int a, float b) {}\nvoid f(float2 a, float2 b) {}", "float x;", "x, x", "void f(float2, float2)"},
      // An int -> float conversion costs more than a float -> int one.
      {"void f(float a) {}\nvoid f(uint a) {}", "int i;", "i", "void f(uint)"},
      // float -> int and float -> half are both casts on the parameter's side.
      {"void f(int a) {}\nvoid f(half a) {}", "float x;", "x", "ambiguous"},
      // Out parameters are costed for the copy back too.
      {"void f(out float a) {}\nvoid f(out int a) {}", "float x;", "x", "void f(out float)"},
  };
  for (const OverloadCase& c : cases)
    EXPECT_EQ(pick_of(c), c.dxc_pick) << c.overloads << " with f(" << c.args << ")";
}

TEST(SemaCalls, AmbiguousCallsListTheCandidates) {
  EXPECT_EQ(messages_of("void f(float a, int b) {}\nvoid f(int a, float b) {}\nvoid t() { f(1, 1); }\n"),
            (Strings{"3:12: error: ambiguous call to 'f' with (int, int)", "1:6: note: candidate 'void f(float, int)'",
                     "2:6: note: candidate 'void f(int, float)'"}));
}

TEST(SemaCalls, NoViableOverloadListsTheCandidates) {
  EXPECT_EQ(messages_of("struct S { float a; };\nvoid f(S s) {}\nvoid f(float2 a, float2 b) {}\n"
                        "void t(float3 v, S s) { f(v, s); }\n"),
            (Strings{"4:25: error: no overload of 'f' takes (float3, S)", "2:6: note: candidate 'void f(S)'",
                     "3:6: note: candidate 'void f(float2, float2)'"}));
}

TEST(SemaCalls, ASingleFunctionConvertsItsArguments) {
  auto a = analyze_source("float f(float3 v, out float o) { o = 1; return v.x; }\n"
                          "void t(float4 p) {\n  float r;\n  f(p, r);\n  f(p);\n  f(p, 1);\n}\n");
  EXPECT_EQ(a->messages(), (Strings{"4:5: warning: implicit truncation of vector type from 'float4' to 'float3'",
                                    "5:3: error: 'f' takes 2 arguments, 1 given",
                                    "6:5: warning: implicit truncation of vector type from 'float4' to 'float3'",
                                    "6:8: error: argument 2 of 'f' is an out parameter and needs an assignable expression"}));
}

TEST(SemaCalls, DefaultArgumentsMayBeLeftOut) {
  auto a = analyze_source("float f(float a, float b = 2) { return a * b; }\nvoid t() { f(1); f(1, 2); f(); }\n");
  EXPECT_EQ(a->messages(), (Strings{"2:27: error: 'f' takes 1 to 2 arguments, 0 given"}));
}

TEST(SemaCalls, FunctionsMustBeDeclaredBeforeUse) {
  EXPECT_EQ(messages_of("void t() { g(); }\nvoid g() {}\n"),
            (Strings{"1:12: error: function 'g' is used before its declaration"}));
  auto a = analyze_source("void g();\nvoid t() { g(); }\nvoid g() {}\n");
  EXPECT_EQ(a->messages(), Strings{});
  const auto& call = static_cast<const CallExpr&>(a->expression("t", 0));
  EXPECT_EQ(call.function, &a->function("g"));  // the definition, not the prototype
  EXPECT_EQ(static_cast<const FunctionDecl&>(*a->unit.decls[0]).definition, &a->function("g"));
  EXPECT_EQ(messages_of("void g();\nvoid t() { g(); }\n"),
            (Strings{"2:12: error: function 'g' is called but never defined"}));
}

TEST(SemaCalls, RedefinitionOfAFunction) {
  EXPECT_EQ(messages_of("void g() {}\nvoid g() {}\nvoid g(int a) {}\n"),
            (Strings{"2:6: error: redefinition of 'g'", "1:6: note: previous definition of 'g' is here"}));
}

TEST(SemaCalls, RecursionIsAnError) {
  EXPECT_EQ(messages_of("float f(float x) { return f(x - 1); }\n"),
            (Strings{"1:27: error: recursive call to 'f' is not supported"}));
  EXPECT_EQ(messages_of("float b(float x);\nfloat a(float x) { return b(x); }\nfloat b(float x) { return a(x); }\n"),
            (Strings{"2:27: error: recursive call to 'b' is not supported"}));
}

TEST(SemaCalls, UnknownFunctions) {
  EXPECT_EQ(messages_of("void t() { foo(1); }\n"), (Strings{"1:12: error: unknown function 'foo'"}));
  EXPECT_EQ(messages_of("void t() { float x = lerpp(0, 1, 0.5); }\n"),
            (Strings{"1:22: error: unknown function 'lerpp'; did you mean 'lerp'?"}));
}

// ---------------------------------------------------------------------------------------------
// Intrinsics

TEST(SemaIntrinsics, LerpSplatsItsScalarWeight) {
  Probe p = probe("float3 a; float3 b; float s;", "lerp(a, b, s)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(p.tree, "(lerp a b (to float3 s))");
  EXPECT_EQ(probe("float3 a;", "lerp(0.04, a, 0.5)").tree, "(lerp (to float3 0.04) a (to float3 0.5))");
  EXPECT_EQ(probe("float3 a;", "lerp(a, 1)").messages, (Strings{"2:12: error: 'lerp' takes 3 arguments, 2 given"}));
}

TEST(SemaIntrinsics, GenericTypesFollowHlsl) {
  const std::string g = "half3 h; float3 f; int i; int3 i3; uint u; float x; half hs;";
  EXPECT_EQ(type_of(g, "lerp(h, h, 0.5)"), "half3");
  EXPECT_EQ(type_of(g, "lerp(h, f, 0.5)"), "float3");
  EXPECT_EQ(type_of(g, "sqrt(i)"), "float");
  EXPECT_EQ(probe(g, "sqrt(i)").tree, "(sqrt (to float i))");
  EXPECT_EQ(type_of(g, "max(i, 0)"), "int");
  EXPECT_EQ(type_of(g, "max(f, 0)"), "float3");
  EXPECT_EQ(type_of(g, "clamp(i3, 0, 4)"), "int3");
  EXPECT_EQ(type_of(g, "abs(i3)"), "int3");
  EXPECT_EQ(type_of(g, "saturate(h)"), "half3");
  EXPECT_EQ(type_of(g, "pow(x, 5)"), "float");
  EXPECT_EQ(type_of(g, "smoothstep(0, 1, f)"), "float3");
  EXPECT_EQ(type_of(g, "step(0.5, f)"), "float3");
  EXPECT_EQ(type_of(g, "sign(f)"), "int3");
  EXPECT_EQ(type_of(g, "frac(hs)"), "half");
  EXPECT_EQ(type_of(g, "fmod(x, 2)"), "float");
}

TEST(SemaIntrinsics, VectorIntrinsics) {
  const std::string g = "float3 a; float3 b; float4 c; int3 i; float2 p;";
  EXPECT_EQ(type_of(g, "dot(a, b)"), "float");
  EXPECT_EQ(type_of(g, "dot(i, i)"), "int");
  EXPECT_EQ(type_of(g, "length(c)"), "float");
  EXPECT_EQ(type_of(g, "distance(a, b)"), "float");
  EXPECT_EQ(type_of(g, "normalize(a)"), "float3");
  EXPECT_EQ(type_of(g, "cross(a, b)"), "float3");
  EXPECT_EQ(type_of(g, "reflect(-a, b)"), "float3");
  EXPECT_EQ(type_of(g, "refract(a, b, 0.66)"), "float3");
  EXPECT_EQ(probe(g, "cross(p, p)").messages, (Strings{"2:12: error: no overload of 'cross' takes (float2, float2)"}));
  Probe q = probe(g, "dot(c, a)");
  EXPECT_EQ(q.type, "float");
  EXPECT_EQ(q.messages, (Strings{"2:16: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
}

TEST(SemaIntrinsics, MulCoversEveryHlslOverload) {
  const std::string g =
      "float s; float3 v3; float4 v4; float4x4 m44; float3x4 m34; float4x3 m43; float2x3 m23; float3x4 n34;";
  EXPECT_EQ(type_of(g, "mul(v4, m44)"), "float4");   // row vector
  EXPECT_EQ(type_of(g, "mul(m44, v4)"), "float4");   // column vector
  EXPECT_EQ(type_of(g, "mul(m34, v4)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v4, m43)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v3, m34)"), "float4");
  EXPECT_EQ(type_of(g, "mul(m44, m44)"), "float4x4");
  EXPECT_EQ(type_of(g, "mul(m23, n34)"), "float2x4");
  EXPECT_EQ(type_of(g, "mul(s, v3)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v3, s)"), "float3");
  EXPECT_EQ(type_of(g, "mul(s, m44)"), "float4x4");
  EXPECT_EQ(type_of(g, "mul(v3, v3)"), "float");
  EXPECT_EQ(type_of(g, "mul(s, s)"), "float");
  EXPECT_EQ(probe(g, "mul(m44, m23)").messages,
            (Strings{"2:12: error: no overload of 'mul' takes (float4x4, float2x3)"}));
  EXPECT_EQ(probe(g, "mul(v3, m44)").messages, (Strings{"2:12: error: no overload of 'mul' takes (float3, float4x4)"}));
  Probe p = probe(g, "mul(v4, m34)");
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(p.tree, "(mul (to float3 v4) m34)");
  EXPECT_EQ(p.messages, (Strings{"2:16: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
  const auto a = analyze_source("float4x4 m; float4 v;\nfloat4 t() { return mul(m, v); }\n");
  const auto& call = static_cast<const CallExpr&>(a->expression("t", 0));
  EXPECT_EQ(call.call_kind, CallKind::Intrinsic);
  EXPECT_EQ(call.intrinsic, uint16_t(IntrinsicId::Mul));
}

TEST(SemaIntrinsics, PredicatesBitCastsAndMatrices) {
  const std::string g = "float3 f; int2 i; uint u; float3x4 m; float3x3 n; bool3 b;";
  EXPECT_EQ(type_of(g, "all(b)"), "bool");
  EXPECT_EQ(type_of(g, "any(f)"), "bool");
  EXPECT_EQ(type_of(g, "isnan(f)"), "bool3");
  EXPECT_EQ(type_of(g, "isfinite(f)"), "bool3");
  EXPECT_EQ(type_of(g, "asuint(f)"), "uint3");
  EXPECT_EQ(type_of(g, "asfloat(i)"), "float2");
  EXPECT_EQ(type_of(g, "asint(u)"), "int");
  EXPECT_EQ(type_of(g, "f16tof32(u)"), "float");
  EXPECT_EQ(type_of(g, "f32tof16(f)"), "uint3");
  EXPECT_EQ(type_of(g, "countbits(u)"), "uint");
  EXPECT_EQ(type_of(g, "reversebits(i)"), "uint2");
  EXPECT_EQ(type_of(g, "transpose(m)"), "float4x3");
  EXPECT_EQ(type_of(g, "determinant(n)"), "float");
  EXPECT_EQ(probe(g, "determinant(m)").messages, (Strings{"2:12: error: no overload of 'determinant' takes (float3x4)"}));
  EXPECT_EQ(type_of(g, "mad(f, f, 1)"), "float3");
  EXPECT_EQ(type_of(g, "ldexp(f, 2)"), "float3");
  EXPECT_EQ(type_of(g, "exp2(log10(f))"), "float3");
  EXPECT_EQ(type_of(g, "degrees(radians(1))"), "float");
  EXPECT_EQ(type_of(g, "trunc(round(ceil(floor(f))))"), "float3");
  EXPECT_EQ(type_of(g, "rcp(rsqrt(f))"), "float3");
}

TEST(SemaIntrinsics, OutParametersNeedAssignableArguments) {
  auto a = analyze_source("void t(float3 x) {\n  float3 s, c;\n  sincos(x, s, c);\n  sincos(x, 1.0, c);\n"
                          "  float3 ip;\n  float3 fr = modf(x, ip);\n}\n");
  EXPECT_EQ(a->messages(),
            (Strings{"4:13: error: argument 2 of 'sincos' is an out parameter and needs an assignable expression"}));
  EXPECT_EQ(dump(&a->expression("t", 1)), "(sincos x s c)");
  EXPECT_EQ(a->expression("t", 1).type.name(), "void");
}

TEST(SemaIntrinsics, ClipAndDerivatives) {
  EXPECT_EQ(type_of("float f; float2 p;", "clip(f - 0.5)"), "void");
  EXPECT_EQ(type_of("float f; float2 p;", "ddx(p)"), "float2");
  EXPECT_EQ(type_of("float f; float2 p;", "fwidth(f)"), "float");
}

TEST(SemaIntrinsics, Dx9Samplers) {
  const std::string g = "sampler2D s; float2 uv; float4 q; Texture2D tex;";
  Probe p = probe(g, "tex2D(s, uv)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(type_of(g, "tex2Dlod(s, float4(uv, 0, 2))"), "float4");
  EXPECT_EQ(type_of(g, "tex2Dbias(s, q)"), "float4");
  EXPECT_EQ(type_of(g, "tex2Dgrad(s, uv, ddx(uv), ddy(uv))"), "float4");
  EXPECT_EQ(probe(g, "tex2D(tex, uv)").messages, (Strings{"2:12: error: no overload of 'tex2D' takes (Texture2D, float2)"}));
}

TEST(SemaIntrinsics, Texture2DMethods) {
  const std::string g = "Texture2D tex; SamplerState ss; sampler2D s2; float2 uv; float4 v; int3 px;";
  Probe p = probe(g, "tex.Sample(ss, uv)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(type_of(g, "tex.SampleLevel(ss, uv, 0)"), "float4");
  EXPECT_EQ(probe(g, "tex.SampleLevel(ss, uv, 0)").tree, "(.SampleLevel tex ss uv (to float 0))");
  EXPECT_EQ(type_of(g, "tex.SampleBias(ss, uv, -1)"), "float4");
  EXPECT_EQ(type_of(g, "tex.SampleGrad(ss, uv, uv, uv)"), "float4");
  EXPECT_EQ(type_of(g, "tex.Load(px)"), "float4");
  EXPECT_EQ(type_of(g, "tex.Load(int3(1, 2, 0)).rgb"), "float3");
  EXPECT_EQ(type_of(g, "uint w, h; tex.GetDimensions(w, h)"), "void");
  EXPECT_EQ(type_of(g, "float fw, fh; tex.GetDimensions(fw, fh)"), "void");
  EXPECT_EQ(probe(g, "tex.Sample(s2, uv)").messages,
            (Strings{"2:16: error: no overload of 'Sample' of 'Texture2D' takes (sampler2D, float2)"}));
  EXPECT_EQ(probe(g, "v.Sample(ss, uv)").messages, (Strings{"2:14: error: 'float4' has no method 'Sample'"}));
  EXPECT_EQ(probe(g, "tex.Blur(ss, uv)").messages, (Strings{"2:16: error: 'Texture2D' has no method 'Blur'"}));
  auto a = analyze_source("Texture2D tex; SamplerState ss;\nfloat4 f(float2 uv) { return tex.Sample(ss, uv); }\n");
  const auto& call = static_cast<const CallExpr&>(a->expression("f", 0));
  EXPECT_EQ(call.call_kind, CallKind::Method);
  EXPECT_EQ(call.intrinsic, uint16_t(IntrinsicId::Sample));
}

TEST(SemaTextures, EachShapeTakesItsCoordinatesOffsetsAndGivesItsTexels) {
  const std::string g =
      "Texture1D t1; Texture2DArray t2a; Texture3D t3; TextureCube tc; TextureCubeArray tca; Texture2DMS<float4> tms;"
      "Texture2D<float> depth; Texture2D<uint2> ids; SamplerState s; SamplerComparisonState c; float2 uv; float3 p;";
  EXPECT_EQ(type_of(g, "t1.Sample(s, 0.5)"), "float4");
  EXPECT_EQ(type_of(g, "t2a.SampleLevel(s, p, 0, int2(1, 0))"), "float4");
  EXPECT_EQ(type_of(g, "t3.SampleGrad(s, p, p, p, int3(0, 0, 1))"), "float4");
  EXPECT_EQ(type_of(g, "tc.SampleBias(s, p, 1)"), "float4");
  EXPECT_EQ(type_of(g, "tca.SampleLevel(s, float4(p, 2), 0)"), "float4");
  EXPECT_EQ(type_of(g, "depth.Sample(s, uv)"), "float");  // the texel type
  EXPECT_EQ(type_of(g, "ids.Load(int3(0, 0, 0))"), "uint2");
  EXPECT_EQ(type_of(g, "ids[uint2(1, 2)]"), "uint2");
  EXPECT_EQ(type_of(g, "tms.Load(int2(1, 2), 3)"), "float4");
  EXPECT_EQ(type_of(g, "t3.Load(int4(1, 2, 3, 0), int3(1, 1, 1))"), "float4");
  EXPECT_EQ(type_of(g, "depth.SampleCmp(c, uv, 0.5)"), "float");
  EXPECT_EQ(type_of(g, "depth.SampleCmpLevelZero(c, uv, 0.5, int2(1, 1))"), "float");
  EXPECT_EQ(type_of(g, "depth.GatherRed(s, uv)"), "float4");
  EXPECT_EQ(type_of(g, "ids.GatherGreen(s, uv, int2(1, 0))"), "uint4");
  EXPECT_EQ(type_of(g, "tc.CalculateLevelOfDetail(s, p)"), "float");
  EXPECT_EQ(type_of(g, "uint w, h, l, n; tms.GetDimensions(w, h, n); t2a.GetDimensions(0, w, h, n, l)"), "void");
  // What a shape does not have.
  EXPECT_EQ(probe(g, "tc.Load(int4(0, 0, 0, 0))").messages, (Strings{"2:15: error: 'TextureCube' has no method 'Load'"}));
  EXPECT_EQ(probe(g, "tc.SampleLevel(s, p, 0, int3(1, 0, 0))").messages,
            (Strings{"2:15: error: 'SampleLevel' of 'TextureCube' takes 3 arguments, 4 given"}));
  EXPECT_EQ(probe(g, "tms.Sample(s, uv)").messages, (Strings{"2:16: error: 'Texture2DMS' has no method 'Sample'"}));
  EXPECT_EQ(probe(g, "t3.Gather(s, p)").messages, (Strings{"2:15: error: 'Texture3D' has no method 'Gather'"}));
  EXPECT_EQ(probe(g, "depth.SampleCmp(s, uv, 0.5)").messages,
            (Strings{"2:18: error: no overload of 'SampleCmp' of 'Texture2D<float>' takes (SamplerState, float2, float)"}));
  EXPECT_EQ(probe(g, "t2a.Sample(s, uv)").messages,
            (Strings{"2:16: error: no overload of 'Sample' of 'Texture2DArray' takes (SamplerState, float2)"}));
}

TEST(SemaTextures, Dx9SamplersOfEveryShape) {
  const std::string g = "sampler1D d1; sampler3D d3; samplerCUBE dc; float3 p;";
  EXPECT_EQ(type_of(g, "tex1D(d1, p.x)"), "float4");
  EXPECT_EQ(type_of(g, "tex3Dlod(d3, float4(p, 2))"), "float4");
  EXPECT_EQ(type_of(g, "texCUBE(dc, p)"), "float4");
  EXPECT_EQ(type_of(g, "texCUBEbias(dc, float4(p, -1))"), "float4");
  EXPECT_EQ(probe(g, "texCUBE(d3, p)").messages, (Strings{"2:12: error: no overload of 'texCUBE' takes (sampler3D, float3)"}));
}

TEST(SemaTextures, ResourcesNoTargetHereBindsAreTypedAsHlslDefinesThem) {
  // Checked as HLSL, so that a file that declares them compiles where its entry points do not
  // read them (the emitter refuses them where they are reached).
  auto a = analyze_source(
      "struct Light { float3 color; };\n"
      "StructuredBuffer<Light> lights; RWTexture2D<float4> output; ByteAddressBuffer raw; Buffer<float2> coords;\n"
      "float3 shade(uint i) { uint n, stride; lights.GetDimensions(n, stride);\n"
      "  output[uint2(i, 0)] = float4(lights[i].color, 1);\n"
      "  return lights.Load(i).color + float3(raw.Load2(4 * i), 0) + coords[i].xyy; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(messages_of("StructuredBuffer<float> b;\nvoid f() { b[0] = 1; }\n"),
            (Strings{"2:12: error: cannot assign to 'b': uniforms are read-only"}));
  EXPECT_EQ(messages_of("ByteAddressBuffer b;\nvoid f() { b.Store(0, 1); }\n"),
            (Strings{"2:14: error: 'ByteAddressBuffer' has no method 'Store'"}));
}

TEST(SemaConstantBuffers, AConstantBufferOfAStructIsReadByItsFields) {
  auto a = analyze_source("struct Scene { float4x4 view; float3 light; };\nConstantBuffer<Scene> scene : register(b1);\n"
                          "float3 f() { return scene.light + scene.view[0].xyz; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(messages_of("struct Scene { float3 light; };\nConstantBuffer<Scene> scene;\nvoid f() { scene.light = 1; }\n"),
            (Strings{"3:12: error: cannot assign to 'scene': uniforms are read-only"}));
  EXPECT_EQ(messages_of("struct Scene { float3 light; };\nConstantBuffer<Scene> scene;\nfloat f() { return scene.dark; }\n"),
            (Strings{"3:26: error: 'ConstantBuffer<Scene>' has no member 'dark'"}));
}

TEST(SemaStatements, SwitchTakesIntegerConstantsAndBreaks) {
  EXPECT_EQ(messages_of("int f(int m) { switch (m) { case 0: return 1; case 1 + 1: m = 2; break; default: break; }\n"
                        "  return m; }\n"),
            Strings{});
  EXPECT_EQ(messages_of("float f(uint m) { switch (m) { case 0: case 1: return 1; default: return 2; } }\n"), Strings{});
  EXPECT_EQ(messages_of("void f(float x) { switch (x) { default: break; } }\n"),
            (Strings{"1:27: warning: the condition of a switch is 'float': converted to int toward zero, as fxc does "
                     "(DXC refuses it); write (int)(...) to say so"}));
  EXPECT_EQ(messages_of("void f(float2 x) { switch (x) { default: break; } }\n"),
            (Strings{"1:28: error: the condition of a switch must be an integer scalar, not 'float2'"}));
  EXPECT_EQ(messages_of("void f(int m, int n) { switch (m) { case 1: break; case n: break; case 1: break; } }\n"),
            (Strings{"1:57: error: a case value must be an integer constant", "1:67: error: case value 1 appears twice",
                     "1:37: note: the first is here"}));
  EXPECT_EQ(messages_of("void f(int m) { switch (m) { default: break; default: break; } }\n"),
            (Strings{"1:46: error: a switch has one 'default'"}));
  EXPECT_EQ(messages_of("void f() { continue; }\nvoid g() { break; }\n"),
            (Strings{"1:12: error: 'continue' is only allowed inside a loop",
                     "2:12: error: 'break' is only allowed inside a loop or a switch"}));
}

TEST(SemaIntrinsics, SelectIsAComponentWiseChoice) {
  EXPECT_EQ(type_of("float3 a; float3 b;", "select(a > b, a, b)"), "float3");
  EXPECT_EQ(type_of("float a; int b;", "select(a > 0, a, b)"), "float");
  EXPECT_EQ(probe("float3 a; float3 b;", "select(a > b, a, b)").tree, "(select (> a b) a b)");
}

TEST(SemaIntrinsics, UserFunctionsNamedLikeIntrinsicsAreCalledWhenTheyFit) {
  auto a = analyze_source("struct S { float a; };\nfloat saturate(S s) { return s.a; }\n"
                          "void t(S s, float3 v) { saturate(s); saturate(v); }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(static_cast<const CallExpr&>(a->expression("t", 0)).call_kind, CallKind::Function);
  EXPECT_EQ(static_cast<const CallExpr&>(a->expression("t", 1)).call_kind, CallKind::Intrinsic);
}

// ---------------------------------------------------------------------------------------------
// Statements

TEST(SemaStatements, BreakAndContinueNeedALoop) {
  EXPECT_EQ(messages_of("void t() {\n  break;\n  for (;;) { if (true) continue; break; }\n  continue;\n}\n"),
            (Strings{"2:3: error: 'break' is only allowed inside a loop or a switch",
                     "4:3: error: 'continue' is only allowed inside a loop"}));
}

TEST(SemaStatements, ResourcesInStructsAndLocalsButNotInLocalArraysOrGlobalStructs) {
  EXPECT_EQ(messages_of("struct S { Texture2D t; SamplerState s; };\nTexture2D g;\n"
                        "void f(Texture2D t, S p) { Texture2D u = g; S v = p; v.t = u; }\n"),
            Strings{});
  EXPECT_EQ(messages_of("void f() { Texture2D t[2]; }\n"),
            (Strings{"1:22: error: variable 't' cannot have type 'Texture2D[2]'; arrays of resources are supported as "
                     "globals of textures, samplers and constant buffers only: declare each one separately"}));
  EXPECT_EQ(messages_of("struct S { Texture2D t; };\nS g;\n"),
            (Strings{"2:3: error: variable 'g' of struct 'S' holds resources: declare each resource as a global of "
                     "its own"}));
}

// ---------------------------------------------------------------------------------------------
// Entry points

TEST(SemaEntryPoints, MissingEntryPointIsReportedAtThePragma) {
  auto a = analyze_source("#pragma vertex vert\n#pragma fragment frag\nfloat4 vert(float4 p : POSITION) : SV_Position { return p; }\n");
  EXPECT_EQ(a->messages(), (Strings{"2:18: error: entry point 'frag' is not defined"}));
  EXPECT_NE(a->entry_points.vertex, nullptr);
  EXPECT_EQ(a->entry_points.fragment, nullptr);
}

TEST(SemaEntryPoints, InputsAndOutputsNeedSemantics) {
  const std::string source =
      "#pragma vertex vert\n"
      "struct appdata { float4 vertex : POSITION; float2 uv; };\n"
      "struct v2f { float4 pos : SV_Position; float2 uv; };\n"
      "v2f vert(appdata v, float3 n) { v2f o; o.pos = v.vertex; o.uv = v.uv + n.xy; return o; }\n";
  EXPECT_EQ(messages_of(source), (Strings{"2:51: error: input 'uv' of entry point 'vert' needs a semantic",
                                          "4:28: error: input 'n' of entry point 'vert' needs a semantic",
                                          "3:47: error: output 'uv' of entry point 'vert' needs a semantic"}));
}

TEST(SemaEntryPoints, VertexMustOutputAPosition) {
  EXPECT_EQ(messages_of("#pragma vertex vert\nfloat4 vert(float4 p : POSITION) : TEXCOORD0 { return p; }\n"),
            (Strings{"2:8: error: vertex entry point 'vert' does not output SV_Position"}));
  // POSITION is DX9's name for the clip position; out parameters are outputs too.
  EXPECT_EQ(messages_of("#pragma vertex vert\nvoid vert(float4 p : POSITION, out float4 o : POSITION) { o = p; }\n"),
            Strings{});
}

TEST(SemaEntryPoints, FragmentMustOutputATarget) {
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0) : TEXCOORD1 { return 1; }\n"),
            (Strings{"2:38: error: semantic 'TEXCOORD1' is not allowed on a fragment shader output",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
  EXPECT_EQ(messages_of("#pragma fragment frag\nstruct O { float4 c : SV_Target1; float d : SV_Depth; };\n"
                        "O frag(float4 p : SV_Position, bool face : SV_IsFrontFace) { O o; o.c = p; o.d = 0; return o; }\n"),
            Strings{});
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag() : color0 { return 1; }\n"), Strings{});
}

TEST(SemaEntryPoints, UnknownAndMisplacedSemantics) {
  // FOO is a user-defined semantic: a vertex input like any other; a pixel shader cannot output one.
  EXPECT_EQ(messages_of("#pragma vertex vert\nfloat4 vert(float4 p : FOO, float4 q : SV_Target) : SV_Position { return p; }\n"),
            (Strings{"2:40: error: semantic 'SV_Target' is not allowed on a vertex shader input"}));
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float4 p : SV_POSITION) : FOO { return p; }\n"),
            (Strings{"2:39: error: semantic 'FOO' is not allowed on a fragment shader output",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float4 p : SV_POSITION) : SV_TARGET8 { return p; }\n"),
            (Strings{"2:39: error: unknown semantic 'SV_TARGET8': a system value's name starts SV_ and names one of "
                     "Direct3D's, any other identifier (with an index of at most two digits) names a varying",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
}

TEST(SemaEntryPoints, FragmentOnlyOperationsAreErrorsInTheVertexStage) {
  const std::string source =
      "#pragma vertex vert\n"
      "#pragma fragment frag\n"
      "float helper(float x) { return ddx(x); }\n"
      "float4 vert(float4 p : POSITION) : SV_Position { if (p.x < 0) discard; return p * helper(p.y); }\n"
      "float4 frag(float4 p : SV_Position) : SV_Target { clip(p.x); return helper(p.x); }\n";
  EXPECT_EQ(messages_of(source), (Strings{"4:63: error: 'discard' is only available in fragment shaders",
                                          "3:32: error: 'ddx' is only available in fragment shaders"}));
}

TEST(SemaEntryPoints, ImplicitLodSamplingIsFragmentOnly) {
  const std::string source =
      "#pragma vertex vert\n"
      "Texture2D tex; SamplerState ss; sampler2D s2;\n"
      "float4 vert(float4 p : POSITION) : SV_Position {\n"
      "  return p + tex.SampleLevel(ss, p.xy, 0) + tex2Dlod(s2, p) + tex.Sample(ss, p.xy) + tex2D(s2, p.xy);\n"
      "}\n";
  EXPECT_EQ(messages_of(source), (Strings{"4:67: error: 'Sample' is only available in fragment shaders",
                                          "4:86: error: 'tex2D' is only available in fragment shaders"}));
}

TEST(SemaEntryPoints, EntryPointsAreReturned) {
  auto a = analyze_source("#pragma vertex vert\n#pragma fragment frag\n"
                          "float4 vert(float4 p : POSITION, uniform float4x4 mvp) : SV_Position { return mul(mvp, p); }\n"
                          "float4 frag() : SV_Target { return 1; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(a->entry_points.vertex, &a->function("vert"));
  EXPECT_EQ(a->entry_points.fragment, &a->function("frag"));
}

// ---------------------------------------------------------------------------------------------
// A complete shader

const char* const kRealisticShader = R"(#pragma vertex vert
#pragma fragment frag

#define PI 3.14159265

struct appdata {
  float4 vertex : POSITION;
  float3 normal : NORMAL;
  float2 uv : TEXCOORD0;
};

struct v2f {
  float4 pos : SV_Position;
  float3 normal : TEXCOORD1;
  float2 uv : TEXCOORD0;
  float3 world : TEXCOORD2;
};

cbuffer PerObject : register(b0) {
  float4x4 _ObjectToWorld;
  float4x4 _MatrixVP;
  float4 _Color;
  float _Smoothness;
  float _Metallic;
};

float3 _LightDir;
float3 _LightColor;
float3 _CameraPos;

Texture2D _MainTex : register(t0);
SamplerState sampler_MainTex : register(s0);
sampler2D _RampTex;

static const float2 kOffsets[4] = { float2(-0.5, -0.5), float2(0.5, -0.5), float2(-0.5, 0.5), float2(0.5, 0.5) };

float D_GGX(float NoH, float a) {
  float a2 = a * a;
  float d = NoH * NoH * (a2 - 1) + 1;
  return a2 / (PI * d * d + 1e-7);
}

float3 fresnel(float3 f0, float LoH) {
  return f0 + (1 - f0) * pow(saturate(1 - LoH), 5);
}

void diffuse_and_specular(float3 albedo, float metallic, out float3 diff, out float3 spec, inout float reflectivity) {
  spec = lerp(0.04, albedo, metallic);
  reflectivity = 0.96 * (1 - metallic);
  diff = albedo * reflectivity;
}

v2f vert(appdata v) {
  v2f o = (v2f)0;
  float4 world = mul(_ObjectToWorld, v.vertex);
  o.pos = mul(_MatrixVP, world);
  o.world = world.xyz;
  o.normal = normalize(mul((float3x3)_ObjectToWorld, v.normal));
  o.uv = v.uv;
  return o;
}

float4 frag(v2f i, bool front : SV_IsFrontFace) : SV_Target {
  float3 n = normalize(i.normal) * (front ? 1 : -1);
  float3 v = normalize(_CameraPos - i.world);
  float3 l = normalize(-_LightDir);
  float3 h = normalize(l + v);
  float NoL = saturate(dot(n, l));
  float NoV = max(abs(dot(n, v)), 1e-4);
  float NoH = saturate(dot(n, h));
  float LoH = saturate(dot(l, h));

  float4 texel = _MainTex.Sample(sampler_MainTex, i.uv);
  float3 albedo = _Color.rgb * texel.rgb;
  float3 diff, spec;
  float reflectivity = 0;
  diffuse_and_specular(albedo, _Metallic, diff, spec, reflectivity);

  float r = max(1 - _Smoothness, 0.002);
  float D = D_GGX(NoH, r);
  float3 F = fresnel(spec, LoH);
  float G = min(1, min(2 * NoH * NoV / LoH, 2 * NoH * NoL / LoH));
  float3 direct = (diff + D * F * G * PI / (4 * NoL * NoV)) * _LightColor * NoL;

  float3 ramp = tex2D(_RampTex, float2(NoL * 0.5 + 0.5, 0.5)).rgb;
  float3 blur = 0;
  [unroll] for (int k = 0; k < 4; ++k) {
    blur += _MainTex.SampleLevel(sampler_MainTex, i.uv + kOffsets[k] * 0.01, 0).rgb;
  }
  blur *= 0.25;
  uint w, hgt;
  _MainTex.GetDimensions(w, hgt);
  float2 texel_size = 1.0 / float2(w, hgt);
  float s, c;
  sincos(texel_size.x, s, c);
  clip(texel.a - 0.01);
  float3 color = direct * ramp + blur * 0.1 + s * 0;
  return float4(color, texel.a * _Color.a);
}
)";

TEST(SemaShader, ARealisticShaderHasNoDiagnostics) {
  auto a = analyze_source(kRealisticShader);
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(a->entry_points.vertex, &a->function("vert"));
  EXPECT_EQ(a->entry_points.fragment, &a->function("frag"));
}

// Every expression of an analyzed tree without errors has a type.
void expect_typed(const Expr* e, int depth = 0) {
  if (!e || depth > 300) return;
  EXPECT_FALSE(e->type.is_error()) << dump(e);
  switch (e->kind) {
    case ExprKind::Unary: expect_typed(static_cast<const UnaryExpr*>(e)->operand.get(), depth + 1); break;
    case ExprKind::Binary:
      expect_typed(static_cast<const BinaryExpr*>(e)->lhs.get(), depth + 1);
      expect_typed(static_cast<const BinaryExpr*>(e)->rhs.get(), depth + 1);
      break;
    case ExprKind::Call:
      for (const ExprPtr& arg : static_cast<const CallExpr*>(e)->args) expect_typed(arg.get(), depth + 1);
      break;
    case ExprKind::Conversion: expect_typed(static_cast<const ConversionExpr*>(e)->operand.get(), depth + 1); break;
    default: break;
  }
}

TEST(SemaShader, EveryExpressionGetsAType) {
  auto a = analyze_source(kRealisticShader);
  for (const auto& stmt : a->function("frag").body->statements) {
    if (stmt->kind == StmtKind::Decl) {
      for (const auto& var : static_cast<const DeclStmt&>(*stmt).vars) expect_typed(var->initializer.get());
    } else if (stmt->kind == StmtKind::Expr) {
      expect_typed(static_cast<const ExprStmt&>(*stmt).expr.get());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Robustness: whatever the parser makes of broken text, analysis must not crash.

TEST(SemaRobustness, EveryPrefixOfAShaderIsAnalyzedWithoutCrashing) {
  const std::string text = kRealisticShader;
  for (size_t length = 0; length <= text.size(); length += 13) {
    auto a = analyze_source(text.substr(0, length));
    (void)a;
  }
}

TEST(SemaRobustness, MutatedShadersAreAnalyzedWithoutCrashing) {
  const std::string text = kRealisticShader;
  std::mt19937 random(1234);
  const std::string pieces[] = {"(", ")", "{", "}", ";", ",", "=", "[", "]", ".", "x", "float4", "1", "?", ":",
                                "Texture2D", "out", "return", "discard", "mul(", "{1,2}", "_m00", "++", "S"};
  for (int round = 0; round < 150; ++round) {
    std::string mutated = text;
    for (int edit = 0; edit < 4; ++edit) {
      const size_t at = random() % mutated.size();
      const size_t length = random() % 8;
      mutated.replace(at, std::min(length, mutated.size() - at), pieces[random() % std::size(pieces)]);
    }
    auto a = analyze_source(mutated);
    (void)a;
  }
}

TEST(SemaRobustness, DeepExpressionsAreBounded) {
  // The parser stops at 256 levels; sema has its own bound for trees made otherwise.
  auto parsed = analyze_source("float t(float x) { return x" + std::string(600, '+') + "x; }\n");
  EXPECT_FALSE(parsed->messages().empty());
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  TranslationUnit unit;
  auto function = std::make_unique<FunctionDecl>(Loc{});
  function->name = "f";
  function->return_type = Type::scalar(ScalarType::Float);
  function->body = std::make_unique<BlockStmt>(Loc{});
  ExprPtr chain = std::make_unique<FloatLiteralExpr>(Loc{});
  for (int i = 0; i < 5000; ++i) {
    auto add = std::make_unique<BinaryExpr>(Loc{}, BinaryOp::Add);
    add->lhs = std::move(chain);
    add->rhs = std::make_unique<FloatLiteralExpr>(Loc{});
    chain = std::move(add);
  }
  auto ret = std::make_unique<ReturnStmt>(Loc{});
  ret->value = std::move(chain);
  function->body->statements.push_back(std::move(ret));
  unit.decls.push_back(std::move(function));
  analyze(unit, {}, diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].message, "expression or statement is nested too deeply");
}

TEST(SemaRobustness, NestedStructsAndConstantsStayLinear) {
  // Each struct holds two of the previous one and each constant uses the previous one twice:
  // walking them naively would take 2^30 steps.
  std::string source = "struct S0 { float a; };\nstatic const int c0 = 1;\n";
  for (int i = 1; i <= 30; ++i) {
    const std::string n = std::to_string(i), p = std::to_string(i - 1);
    source += "struct S" + n + " { S" + p + " a; S" + p + " b; };\n";
    source += "static const int c" + n + " = c" + p + " + c" + p + " - c" + p + ";\n";
  }
  source += "float4 arr[2];\n#pragma vertex vert\n"
            "float4 vert(S30 s) : SV_Position { S30 x = (S30)0; S30 y = {1, 2}; return arr[c30] + arr[c30 + 1]; }\n";
  auto a = analyze_source(source);
  EXPECT_EQ(a->messages(), (Strings{"65:60: error: initializer has 2 components, 'S30' needs 1073741824",
                                    "65:94: error: index 2 is out of range for 'float4[2]'",
                                    "1:19: error: input 'a' of entry point 'vert' needs a semantic",
                                    "65:8: error: entry point 'vert' has too many inputs or outputs"}));
}

TEST(SemaRobustness, ConstantFoldingDoesNotOverflow) {
  auto a = analyze_source(
      "static const int big = 2147483647;\n"
      "float t(float4 v) { return v[4294967295u * 4294967295u * 4294967295u] + v[-big - big - big] + v[(big << 31) << 31]"
      " + v[~big * big] + v[1 << 40] + v[5 % 0]; }\n");
  for (const std::string& message : a->messages()) EXPECT_EQ(message.find("out of range"), std::string::npos) << message;
}

TEST(SemaRobustness, HandBuiltTreesWithNullChildren) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  TranslationUnit unit;
  auto function = std::make_unique<FunctionDecl>(Loc{});
  function->name = "f";
  function->return_type = Type::scalar(ScalarType::Float);
  function->body = std::make_unique<BlockStmt>(Loc{});
  auto ret = std::make_unique<ReturnStmt>(Loc{});
  auto binary = std::make_unique<BinaryExpr>(Loc{}, BinaryOp::Add);  // both operands null
  ret->value = std::move(binary);
  function->body->statements.push_back(std::move(ret));
  auto stmt = std::make_unique<IfStmt>(Loc{});  // no condition, no branches
  function->body->statements.push_back(std::move(stmt));
  auto call = std::make_unique<CallExpr>(Loc{});
  call->callee = "lerp";
  call->args.push_back(nullptr);
  auto expr_stmt = std::make_unique<ExprStmt>(Loc{});
  expr_stmt->expr = std::move(call);
  function->body->statements.push_back(std::move(expr_stmt));
  function->body->statements.push_back(nullptr);
  unit.decls.push_back(std::move(function));
  unit.decls.push_back(nullptr);
  analyze(unit, {}, diagnostics);
  EXPECT_EQ(diagnostics.error_count(), 0u);
}

}  // namespace
}  // namespace xshade::hlsl
