// The parser's errors and recovery, one test per rule: pinned messages, each mistake once, deep
// nesting, broken text; and productions and skip_until alone, through parser_internal.h.
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
      {"cbuffer C { float4 c : packoffset(r0); };",
       {"1:35: invalid packoffset 'r0'; write packoffset(cN) or packoffset(cN.y)"}},
      {"cbuffer C { float c : packoffset(c0.q); };", {"1:37: invalid packoffset component 'q'; use x, y, z or w"}},
      {"float4 c : packoffset(c0);", {"1:12: packoffset is only allowed on the members of a cbuffer"}},
      {"void f(int i) { switch (i) { i = 2; case 0: break; } i = 1; }",
       {"1:30: expected 'case' or 'default' in a switch"}},
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
      "void f(float x) { [unroll(4)] for (int i = 0; i < 4; i++) {} [loop] while (x > 0) x -= 1; [flatten] if (x) {} "
      "}\n");
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
      "  float4 c = tint * ;\n"      // 4: missing operand
      "  c.rgb = saturate(c.rgb;\n"  // 5: missing ')'
      "  if (c.a > 0.5) { c.a = 1; }\n"
      "  return c;\n"
      "}\n"
      "float after;\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:59: expected ';' after declaration",
                                                   "4:21: expected an expression", "5:25: expected ')' to match '('"}));
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
                                                   "4:23: expected an expression", "5:13: expected an expression"}));
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

  auto lists =
      parse_text("float z[1] = " + std::string(kDepth, '{') + "1" + std::string(kDepth, '}') + ";\nfloat y;\n");
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
  auto pool =
      parse_text(std::string(kUnityShader) +
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

}  // namespace
}  // namespace xshade::hlsl::parser_test
