// Why this file is long: one case per rule of the preprocessor as DXC and fxc apply it (macros,
// expansion, conditionals, #include, #pragma, errors), read as the list of them.
#include "hlsl_like/preprocessor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "hlsl_like/hang_guard.h"
#include "hlsl_like/lexer.h"
#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;

class PreprocessorTest : public ::testing::Test {
 protected:
  void TearDown() override {
    if (!dir_.empty()) {
      std::error_code error;
      fs::remove_all(dir_, error);
    }
  }

  // Preprocesses `text` as the in-memory file "main.hlsl"; returns the output tokens' text
  // joined by single spaces (without the EndOfFile).
  std::string run(std::string text, PreprocessorOptions options = {}) {
    return run_file(sources_.add("main.hlsl", std::move(text)), std::move(options));
  }
  std::string run_file(uint32_t file, PreprocessorOptions options = {}) {
    diagnostics_ = std::make_unique<DiagnosticEngine>(sources_);
    pp_ = std::make_unique<Preprocessor>(sources_, *diagnostics_, std::move(options));
    tokens_ = pp_->run(file);
    std::string joined;
    for (const Token& t : tokens_) {
      if (t.kind == TokenKind::EndOfFile) continue;
      if (!joined.empty()) joined += ' ';
      joined += t.text;
    }
    return joined;
  }
  Strings messages() const {
    Strings out;
    for (const Diagnostic& d : diagnostics_->diagnostics()) out.push_back(d.to_string());
    return out;
  }
  std::string where(const Token& t) const { return sources_.resolve(t.loc).to_string(); }
  // Evaluates `text` as the #if expression evaluator alone sees a line: no macro expansion, and
  // a `defined` left in it asks whether the name is one of `defined_names`.
  std::optional<pp_detail::ExpressionValue> evaluate(std::string text, const Strings& defined_names = {}) {
    const uint32_t file = sources_.add("expr.hlsl", std::move(text));
    diagnostics_ = std::make_unique<DiagnosticEngine>(sources_);
    std::vector<pp_detail::PPTok> tokens;
    Lexer lexer(sources_.text(file), file, *diagnostics_);
    for (Token t = lexer.next(); t.kind != TokenKind::EndOfFile; t = lexer.next()) {
      pp_detail::PPTok token;
      token.tok = t;
      tokens.push_back(token);
    }
    const Loc end = tokens.empty() ? Loc{} : tokens.back().tok.loc;
    return pp_detail::evaluate_expression(tokens, end, *diagnostics_, [&](std::string_view name) {
      return std::find(defined_names.begin(), defined_names.end(), name) != defined_names.end();
    });
  }
  size_t count_eof() const {
    size_t n = 0;
    for (const Token& t : tokens_) n += t.kind == TokenKind::EndOfFile;
    return n;
  }

  // A fresh temporary directory for include tests.
  fs::path temp_dir() {
    if (dir_.empty()) {
      std::random_device random;
      dir_ = fs::temp_directory_path() / ("xshade_pp_test_" + std::to_string(random()) + std::to_string(random()));
      fs::create_directories(dir_);
      dir_ = fs::weakly_canonical(dir_);
    }
    return dir_;
  }
  fs::path write(const std::string& relative, const std::string& text) {
    const fs::path path = temp_dir() / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  uint32_t load(const fs::path& path) {
    Result<uint32_t> file = sources_.load(path);
    EXPECT_TRUE(file.has_value());
    return file.value_or(0);
  }

  SourceManager sources_;
  std::unique_ptr<DiagnosticEngine> diagnostics_ = std::make_unique<DiagnosticEngine>(sources_);
  std::unique_ptr<Preprocessor> pp_;
  std::vector<Token> tokens_;
  fs::path dir_;
};

// --- plain text ----------------------------------------------------------------------------------

TEST_F(PreprocessorTest, PassesTokensThroughWithTheirLocationsAndOneEndOfFile) {
  EXPECT_EQ(run("float4 main() : SV_Target\n{\n  return 1.0;\n}\n"), "float4 main ( ) : SV_Target { return 1.0 ; }");
  EXPECT_TRUE(messages().empty());
  ASSERT_EQ(count_eof(), 1u);
  EXPECT_EQ(tokens_.back().kind, TokenKind::EndOfFile);
  EXPECT_EQ(where(tokens_[7]), "main.hlsl:3:3");  // return
  EXPECT_TRUE(tokens_[7].at_line_start);
  EXPECT_TRUE(tokens_[8].space_before);
  EXPECT_EQ(pp_->files(), (std::vector<uint32_t>{1}));
}

TEST_F(PreprocessorTest, EmptyInputIsJustEndOfFile) {
  EXPECT_EQ(run(""), "");
  EXPECT_EQ(tokens_.size(), 1u);
  EXPECT_EQ(run("// only a comment\n#define X 1\n"), "");
  EXPECT_EQ(count_eof(), 1u);
}

// --- macros ----------------------------------------------------------------------------------------

TEST_F(PreprocessorTest, ObjectLikeMacrosTakeTheInvocationLocation) {
  EXPECT_EQ(run("#define PI 3.14159\n#define TWO_PI (2.0 * PI)\nfloat x =\n   TWO_PI;\n"),
            "float x = ( 2.0 * 3.14159 ) ;");
  for (size_t i = 3; i <= 7; ++i) EXPECT_EQ(where(tokens_[i]), "main.hlsl:4:4") << i;
  EXPECT_TRUE(tokens_[3].at_line_start);
  EXPECT_FALSE(tokens_[4].at_line_start);
  EXPECT_EQ(tokens_[5].kind, TokenKind::Punct);
  EXPECT_EQ(tokens_[6].kind, TokenKind::FloatLiteral);
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, KeywordsMayBeMacros) {
  EXPECT_EQ(run("#define half float\n#define fixed4 half4\nhalf a; fixed4 b;"), "float a ; half4 b ;");
}

TEST_F(PreprocessorTest, EmptyMacroLeavesItsSpacingToTheNextToken) {
  EXPECT_EQ(run("#define EMPTY\nEMPTY x EMPTY y"), "x y");
  EXPECT_TRUE(tokens_[0].at_line_start);
  EXPECT_TRUE(tokens_[1].space_before);
}

TEST_F(PreprocessorTest, FunctionLikeMacros) {
  EXPECT_EQ(run("#define ADD(a, b) ((a) + (b))\n"
                "#define NONE() 7\n"
                "#define ONE(x) [x]\n"
                "ADD(1, f(2, 3)) NONE() ONE() ONE((a, b))\n"
                "ADD\n(4,\n 5)"),
            "( ( 1 ) + ( f ( 2 , 3 ) ) ) 7 [ ] [ ( a , b ) ] ( ( 4 ) + ( 5 ) )");
  EXPECT_TRUE(messages().empty());
  EXPECT_EQ(where(tokens_[0]), "main.hlsl:4:1");
  EXPECT_EQ(where(tokens_[2]), "main.hlsl:4:5");  // an argument keeps its own location
}

TEST_F(PreprocessorTest, FunctionLikeNameWithoutParenthesisIsLeftAlone) {
  EXPECT_EQ(run("#define F(x) x\nF + F;\nint F;\n#define G F\nG(3) G"), "F + F ; int F ; 3 F");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, ObjectLikeNeedsSpaceBeforeParenthesisToBeObjectLike) {
  EXPECT_EQ(run("#define P (x)\n#define Q(x) x\nP Q(y)"), "( x ) y");
}

TEST_F(PreprocessorTest, Stringizing) {
  EXPECT_EQ(run("#define S(x) #x\nS(a  +  b) S( lead  ) S(\"q\\n\") S() S(a\n  b)"),
            R"("a + b" "lead" "\"q\\n\"" "" "a b")");
  EXPECT_EQ(tokens_[0].kind, TokenKind::StringLiteral);
  EXPECT_EQ(where(tokens_[0]), "main.hlsl:2:1");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, StringizeDoesNotExpandButAnIndirectionDoes) {
  EXPECT_EQ(run("#define str(x) #x\n#define xstr(x) str(x)\n#define V 42\nstr(V) xstr(V) xstr(V  +   V)"),
            R"("V" "42" "42 + 42")");
}

TEST_F(PreprocessorTest, TokenPasting) {
  EXPECT_EQ(run("#define CAT(a, b) a ## b\n"
                "#define CAT3(a, b, c) a##b##c\n"
                "CAT(x, y) CAT(1, 2) CAT(, y) CAT(x, ) CAT(,) CAT(+, =) CAT(<<, =) CAT3(a, , c) CAT(x y, z w)"),
            "xy 12 y x += <<= ac x yz w");
  EXPECT_TRUE(messages().empty());
  EXPECT_EQ(tokens_[0].kind, TokenKind::Identifier);
  EXPECT_EQ(tokens_[1].kind, TokenKind::IntLiteral);
  EXPECT_EQ(tokens_[4].kind, TokenKind::Punct);
  EXPECT_EQ(where(tokens_[0]), "main.hlsl:3:1");
}

TEST_F(PreprocessorTest, PastedIdentifierIsExpandedAgain) {
  EXPECT_EQ(run("#define CAT(a, b) a##b\n#define xy 99\n#define PASTE_STR(a) #a ## _suffix\nCAT(x, y)"), "99");
}

TEST_F(PreprocessorTest, PastingThatGivesNoTokenIsAnError) {
  EXPECT_EQ(run("#define CAT(a, b) a ## b\n  CAT(a, +) CAT(/, /)"), "a + / /");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:2:3: error: pasting \"a\" and \"+\" does not give a valid token",
                                 "main.hlsl:2:13: error: pasting \"/\" and \"/\" does not give a valid token"}));
}

TEST_F(PreprocessorTest, HashRulesInDefinitions) {
  run("#define A(x) # y\n#define B ## x\n#define C x ##\n#define D # y\nD");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:1:14: error: '#' is not followed by a macro parameter",
                                 "main.hlsl:2:11: error: '##' cannot appear at either end of a macro expansion",
                                 "main.hlsl:3:13: error: '##' cannot appear at either end of a macro expansion"}));
  EXPECT_EQ(tokens_[0].kind, TokenKind::Hash);  // in an object-like macro # is just a token
}

TEST_F(PreprocessorTest, ArgumentsArePreExpandedAndNestedCallsWork) {
  EXPECT_EQ(run("#define f(x) (x + 1)\n#define g(x) f(f(x))\n#define N 5\ng(N) f(f(f(0)))"),
            "( ( 5 + 1 ) + 1 ) ( ( ( 0 + 1 ) + 1 ) + 1 )");
}

TEST_F(PreprocessorTest, SelfReferenceTerminatesAndWarnsOnce) {
  EXPECT_EQ(run("#define A B\n#define B A\nA A\n#define foo foo + 1\nfoo"), "A A foo + 1");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:3:1: warning: macro 'A' refers to itself; it is not expanded again",
                                 "main.hlsl:5:1: warning: macro 'foo' refers to itself; it is not expanded again"}));
  EXPECT_EQ(diagnostics_->error_count(), 0u);
}

TEST_F(PreprocessorTest, TheCStandardRescanExamples) {
  // C11 6.10.3.5: hide sets follow the tokens, not the nesting.
  EXPECT_EQ(run("#define f(a) a*g\n#define g(a) f(a)\nf(2)(9)"), "2 * 9 * g");
  EXPECT_EQ(run("#define x 3\n#define f(a) f(x * (a))\n#undef x\n#define x 2\n#define g f\n#define z z[0]\n"
                "#define h g(~\n#define m(a) a(w)\n#define w 0,1\n#define t(a) a\n#define p() int\n"
                "#define q(x) x\n#define r(x,y) x ## y\n"
                "f(y+1) + f(f(z)) % t(t(g)(0) + t)(1);\ng(x+(3,4)-w) | h 5) & m\n(f)^m(m);"),
            "f ( 2 * ( y + 1 ) ) + f ( 2 * ( f ( 2 * ( z [ 0 ] ) ) ) ) % f ( 2 * ( 0 ) ) + t ( 1 ) ; "
            "f ( 2 * ( 2 + ( 3 , 4 ) - 0 , 1 ) ) | f ( 2 * ( ~ 5 ) ) & f ( 2 * ( 0 , 1 ) ) ^ m ( 0 , 1 ) ;");
}

TEST_F(PreprocessorTest, WrongArgumentCount) {
  run("#define F(a, b) a b\n#define G(x) x\n#define H() 1\n#define V(a, ...) a\nF(1, 2, 3) G(1, 2) H(1) V() G()");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:5:1: error: macro 'F' takes 2 arguments, 3 given",
                                 "main.hlsl:5:12: error: macro 'G' takes 1 argument, 2 given",
                                 "main.hlsl:5:20: error: macro 'H' takes 0 arguments, 1 given"}));
}

TEST_F(PreprocessorTest, UnterminatedCall) {
  EXPECT_EQ(run("#define F(a, b) a b\nx F(1, (2)\n"), "x");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:2:3: error: unterminated call of macro 'F'"}));
  EXPECT_EQ(count_eof(), 1u);
}

TEST_F(PreprocessorTest, VariadicMacros) {
  EXPECT_EQ(run("#define V(fmt, ...) call(fmt, __VA_ARGS__)\n#define W(...) #__VA_ARGS__\nV(a, b, c) V(a) W(x, y)"),
            R"(call ( a , b , c ) call ( a , ) "x, y")");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, DefinitionErrors) {
  run("#define\n#define 3 x\n#define F(a, a) a\n#define G(a b) a\n#define H(a\n#define defined 1\n#undef\n");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:1:2: error: macro name missing in #define",
                                 "main.hlsl:2:9: error: macro name must be an identifier",
                                 "main.hlsl:3:14: error: duplicate macro parameter 'a'",
                                 "main.hlsl:4:13: error: expected ',' or ')' in macro parameter list",
                                 "main.hlsl:5:10: error: missing ')' in macro parameter list",
                                 "main.hlsl:6:9: error: 'defined' cannot be used as a macro name",
                                 "main.hlsl:7:2: error: macro name missing in #undef"}));
}

TEST_F(PreprocessorTest, RedefinitionWarnsUnlessIdentical) {
  run("#define A 1 + 2\n#define A 1 + 2\n#define A 1 +2\n");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:3:9: warning: macro 'A' redefined",
                                 "main.hlsl:1:9: note: previous definition is here"}));
}

TEST_F(PreprocessorTest, Undef) {
  EXPECT_EQ(run("#define A 1\nA\n#undef A\nA\n#undef NEVER_DEFINED\n"), "1 A");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, DirectivesInsideMacroArgumentsAreProcessed) {
  EXPECT_EQ(run("#define F(x) [x]\nF(a\n#ifdef NOPE\nb\n#else\nc\n#endif\n)"), "[ a c ]");
}

TEST_F(PreprocessorTest, LineAndFileBuiltins) {
  EXPECT_EQ(run("a\n__LINE__ __FILE__\n#define L __LINE__\n\nL"), "a 2 \"main.hlsl\" 5");
  EXPECT_EQ(tokens_[1].kind, TokenKind::IntLiteral);
  EXPECT_EQ(tokens_[2].kind, TokenKind::StringLiteral);
}

TEST_F(PreprocessorTest, DefinesFromTheOptions) {
  PreprocessorOptions options;
  options.defines = {{"FOO", "1"}, {"EMPTY", ""}, {"SQ(x)", "((x) * (x))"}, {"1bad", "1"}};
  EXPECT_EQ(run("#if FOO\nyes EMPTY SQ(3)\n#endif", options), "yes ( ( 3 ) * ( 3 ) )");
  EXPECT_EQ(messages(), (Strings{"error: invalid macro name '1bad' in the options"}));
}

TEST_F(PreprocessorTest, PredefinedMacrosExpandLikeDefinesFromTheOptions) {
  auto table = PredefinedMacros::read({{"PI", "3.14f"}, {"TWICE(x)", "((x) + (x))"}, {"fixed4", "half4"}});
  ASSERT_TRUE(table) << table.error().message;
  PreprocessorOptions options;
  options.predefined = *table;
  options.defines = {{"EXTRA", "TWICE(PI)"}};
  EXPECT_EQ(run("fixed4 c = EXTRA;\n#if defined(PI) && !defined(NOPE)\nyes\n#endif", options),
            "half4 c = ( ( 3.14f ) + ( 3.14f ) ) ; yes");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, PredefinedMacrosCanBeUndefinedAndRedefinedWithoutChangingTheTable) {
  auto table = PredefinedMacros::read({{"A", "1"}, {"B", "2"}});
  ASSERT_TRUE(table);
  PreprocessorOptions options;
  options.predefined = *table;
  EXPECT_EQ(run("#undef A\nA\n#ifndef A\nundefined\n#endif\n#define B 3\nB", options), "A undefined 3");
  // Silently: the table stands in for include files (Unity's) that define the same names.
  EXPECT_TRUE(messages().empty());
  // A later preprocessor sharing the table sees it as it was read.
  EXPECT_EQ(run("A B", options), "1 2");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, APredefinedMacroNamingItselfIsExpandedOnceInEachRun) {
  auto table = PredefinedMacros::read({{"SELF", "SELF + 1"}});
  ASSERT_TRUE(table);
  PreprocessorOptions options;
  options.predefined = *table;
  const Strings warning{"main.hlsl:1:1: warning: macro 'SELF' refers to itself; it is not expanded again"};
  EXPECT_EQ(run("SELF", options), "SELF + 1");
  EXPECT_EQ(messages(), warning);
  // The second run warns again: what one run marks on a macro stays out of the shared table.
  EXPECT_EQ(run("SELF SELF", options), "SELF + 1 SELF + 1");
  EXPECT_EQ(messages(), warning);
}

TEST_F(PreprocessorTest, AnInvalidPredefinedMacroIsAnError) {
  auto table = PredefinedMacros::read({{"GOOD", "1"}, {"2bad", "1"}});
  ASSERT_FALSE(table);
  EXPECT_EQ(table.error().message, "predefined macros: invalid macro name '2bad' in the options");
}

TEST_F(PreprocessorTest, ADefinitionIsReadIntoParametersAndABodyThatNamesThem) {
  auto table = PredefinedMacros::read({{"F(a, ...)", "#a a ## __VA_ARGS__ b"}, {"G", "(x)"}});
  ASSERT_TRUE(table) << table.error().message;
  const auto& by_name = (*table)->table().by_name;
  auto body_of = [](const pp_detail::Macro& macro) {
    std::string body;
    for (const pp_detail::BodyToken& b : macro.body)
      body += std::string(b.tok.text) + (b.param >= 0 ? "=" + std::to_string(b.param) : "") + " ";
    return body;
  };
  ASSERT_EQ(by_name.count("F"), 1u);
  const pp_detail::Macro& f = *by_name.at("F");
  EXPECT_TRUE(f.function_like);
  EXPECT_TRUE(f.variadic);
  EXPECT_EQ(f.params, (std::vector<std::string_view>{"a", "__VA_ARGS__"}));
  EXPECT_EQ(body_of(f), "# a=0 a=0 ## __VA_ARGS__=1 b ");
  // A space before the parenthesis makes it the body of an object-like macro.
  ASSERT_EQ(by_name.count("G"), 1u);
  const pp_detail::Macro& g = *by_name.at("G");
  EXPECT_FALSE(g.function_like);
  EXPECT_TRUE(g.params.empty());
  EXPECT_EQ(body_of(g), "( x ) ");
}

// --- conditionals ----------------------------------------------------------------------------------

TEST_F(PreprocessorTest, IfArithmetic) {
  const char* true_expressions[] = {"1",
                                    "1 + 2 * 3 == 7",
                                    "(1 + 2) * 3 == 9",
                                    "(1 << 4) == 16",
                                    "256 >> 4 == 16",
                                    "-1 < 0",
                                    "!(-1 < 0u)",
                                    "0x10 == 16",
                                    "0XfF == 255",
                                    "010 == 8",
                                    "!0",
                                    "~0 == -1",
                                    "1 ? 2 : 0",
                                    "0 ? 0 : 3",
                                    "(0, 5)",
                                    "7 / 2 == 3",
                                    "-7 % 3 == -1",
                                    "-7 / 2 == -3",
                                    "1 && 0 || 1",
                                    "5 > 3 && 3 >= 3 && 2 <= 2 && 1 != 2",
                                    "(6 & 3) == 2",
                                    "(6 | 1) == 7",
                                    "(6 ^ 3) == 5",
                                    "7 & 3 == 3",
                                    "UNDEFINED == 0",
                                    "!UNDEFINED",
                                    "- - 1 == 1",
                                    "+1",
                                    "1u",
                                    "18446744073709551615 == -1",
                                    "(0 - 1) / 2 == 0",
                                    "0 || 0 || 2",
                                    "1 ? 0 ? 5 : 6 : 7 == 6",
                                    "-9223372036854775807 - 1 < 0",
                                    "(-9223372036854775807 - 1) / -1 < 0",
                                    "1 << 64 == 0",
                                    "-1 >> 70 == -1",
                                    "3L == 3"};
  for (const char* expression : true_expressions) {
    EXPECT_EQ(run(std::string("#if ") + expression + "\nyes\n#else\nno\n#endif"), "yes") << expression;
    EXPECT_TRUE(messages().empty()) << expression << ": " << (messages().empty() ? "" : messages()[0]);
  }
}

TEST_F(PreprocessorTest, IfWithMacrosAndDefined) {
  EXPECT_EQ(run("#define X 3\n#define Y\n#define F(a) (a * 2)\n"
                "#if defined X && defined(Y) && !defined Z && !defined(Z) && F(X) == 6\nyes\n#endif\n"
                "#define D defined(X)\n#if D\nalso\n#endif\n"
                "#ifdef X\nx\n#endif\n#ifndef X\nnot\n#endif\n#ifdef __LINE__\nline\n#endif"),
            "yes also x line");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, ShortCircuitedDivisionIsNotAnError) {
  EXPECT_EQ(run("#if 0 && (1 / 0)\na\n#elif 1 || 1 % 0\nb\n#endif\n#if 1 ? 2 : 1/0\nc\n#endif"), "b c");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, IfExpressionErrors) {
  run("#if 1 / 0\n#endif\n"
      "#if\n#endif\n"
      "#if (1\n#endif\n"
      "#if 1 +\n#endif\n"
      "#if 1.5\n#endif\n"
      "#if 1 2\n#endif\n"
      "#if 1 ? 2\n#endif\n"
      "#if defined\n#endif\n"
      "#if defined(X\n#endif\n"
      "#if 099\n#endif\n"
      "#if 99999999999999999999999\n#endif\n"
      "#if 2 % 0\n#endif\n"
      "#if \"s\"\n#endif\n");
  EXPECT_EQ(messages(),
            (Strings{"main.hlsl:1:7: error: division by zero in preprocessor expression",
                     "main.hlsl:3:2: error: #if with no expression", "main.hlsl:5:5: error: missing ')' in expression",
                     "main.hlsl:7:7: error: expected value in expression",
                     "main.hlsl:9:5: error: floating-point literal in preprocessor expression",
                     "main.hlsl:11:7: error: unexpected '2' in expression",
                     "main.hlsl:13:9: error: expected ':' in expression",
                     "main.hlsl:15:5: error: macro name missing after 'defined'",
                     "main.hlsl:17:5: error: missing ')' after 'defined'",
                     "main.hlsl:19:5: error: invalid digit '9' in octal literal",
                     "main.hlsl:21:5: error: integer literal is too large",
                     "main.hlsl:23:7: error: division by zero in preprocessor expression",
                     "main.hlsl:25:5: error: expected value in expression, found '\"s\"'"}));
}

TEST_F(PreprocessorTest, ElifChainsTakeTheFirstTrueGroup) {
  const std::string chain = "#if A == 1\none\n#elif A == 2\ntwo\n#elif A == 3\nthree\n#else\nother\n#endif";
  EXPECT_EQ(run("#define A 1\n" + chain), "one");
  EXPECT_EQ(run("#define A 2\n" + chain), "two");
  EXPECT_EQ(run("#define A 3\n" + chain), "three");
  EXPECT_EQ(run("#define A 4\n" + chain), "other");
  EXPECT_EQ(run("#define A 2\n#if 1\nfirst\n#elif A == 2\nsecond\n#endif"), "first");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, NestedSkippingOnlyTracksNesting) {
  EXPECT_EQ(run("#if 0\n"
                "  #if 1\n  a\n  #elif 1 / 0\n  b\n  #endif\n"
                "  #bogus directive\n  #error not reached\n  #include \"nothing.hlsl\"\n"
                "  don't \"unterminated\n  1e /* #endif */\n"
                "#elif 0\nc\n#elif 1\nd\n  #ifdef X\n  e\n  #else\n  f\n  #endif\n#elif 1 / 0\n#else\ng\n#endif\nh"),
            "d f h");
  EXPECT_EQ(messages(), Strings{});
}

TEST_F(PreprocessorTest, ConditionalStructureErrors) {
  run("#else\n#endif\n#elif 1\n#if 1\n#else\n#else\n#elif 1\n#endif\n#if 0\n#else\n#else\n#endif "
      "junk\n#ifdef\n#endif\n");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:1:2: error: #else without #if", "main.hlsl:2:2: error: #endif without #if",
                                 "main.hlsl:3:2: error: #elif without #if", "main.hlsl:6:2: error: #else after #else",
                                 "main.hlsl:7:2: error: #elif after #else", "main.hlsl:11:2: error: #else after #else",
                                 "main.hlsl:12:8: warning: extra tokens at end of #endif directive",
                                 "main.hlsl:13:2: error: macro name missing in #ifdef"}));
}

TEST_F(PreprocessorTest, UnterminatedIfIsReportedAtTheIf) {
  EXPECT_EQ(run("a\n#if 1\nb\n  #ifdef Q\nc\n"), "a b");
  EXPECT_EQ(messages(),
            (Strings{"main.hlsl:2:2: error: unterminated #if", "main.hlsl:4:4: error: unterminated #ifdef"}));
}

TEST_F(PreprocessorTest, TenThousandNestedIfsGiveAnErrorNotACrash) {
  for (const char* condition : {"1", "0"}) {
    std::string text;
    for (int i = 0; i < 10000; ++i) text += std::string("#if ") + condition + "\n";
    text += "x\n";
    for (int i = 0; i < 10000; ++i) text += "#endif\n";
    text += "after";
    const auto start = std::chrono::steady_clock::now();
    const std::string out = run(text);
    EXPECT_LT(seconds_since(start), 1.0 * kTimeScale);
    EXPECT_EQ(out, "after");
    if (condition[0] == '1') {
      EXPECT_EQ(messages(), (Strings{"main.hlsl:257:2: error: #if nested too deeply (more than 256 levels)"}));
    } else {
      EXPECT_TRUE(messages().empty());  // skipped: only counted
    }
  }
}

TEST_F(PreprocessorTest, DeepExpressionsAreBounded) {
  std::string parens(10000, '(');
  std::string minuses;
  for (int i = 0; i < 100000; ++i) minuses += "- ";
  EXPECT_EQ(run("#if " + parens + "1\n#endif\n#if " + minuses + "1\nok\n#endif"), "ok");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:1:133: error: expression nested too deeply"}));
}

TEST_F(PreprocessorTest, TheExpressionEvaluatorGivesCsValuesAndSignedness) {
  struct Case {
    const char* text;
    uint64_t value;
    bool is_unsigned;
  };
  const Case cases[] = {
      {"1 + 2 * 3", 7, false},
      {"18446744073709551615", ~uint64_t(0), true},          // too large for a signed value
      {"0x7fffffffffffffff + 1", uint64_t(1) << 63, false},  // wraps and stays signed
      {"-1 >> 70", ~uint64_t(0), false},                     // a signed shift too far keeps the sign
      {"1u << 63 >> 63", 1, true},
      {"-1 / 2u", ~uint64_t(0) >> 1, true},  // an unsigned operand makes the division unsigned
      {"0 ? 1u : -1", ~uint64_t(0), true},   // so does the branch of ?: not taken
      {"2 > 1u", 1, false},                  // a comparison gives a signed 0 or 1
      {"UNDEFINED + 2", 2, false},
      {"(1, 2)", 2, false},
  };
  for (const Case& c : cases) {
    const std::optional<pp_detail::ExpressionValue> value = evaluate(c.text);
    ASSERT_TRUE(value) << c.text;
    EXPECT_EQ(value->v, c.value) << c.text;
    EXPECT_EQ(value->is_unsigned, c.is_unsigned) << c.text;
    EXPECT_TRUE(messages().empty()) << c.text;
  }
}

TEST_F(PreprocessorTest, TheExpressionEvaluatorAsksAboutADefinedLeftInTheLine) {
  const Strings defined{"X", "Y"};
  const std::optional<pp_detail::ExpressionValue> all = evaluate("defined X && defined(Y) && !defined Z", defined);
  ASSERT_TRUE(all);
  EXPECT_EQ(all->v, 1u);
  const std::optional<pp_detail::ExpressionValue> sum = evaluate("defined(X) + defined Q + defined Y", defined);
  ASSERT_TRUE(sum);
  EXPECT_EQ(sum->v, 2u);
  EXPECT_TRUE(messages().empty());
  EXPECT_FALSE(evaluate("defined(X", defined));
  EXPECT_EQ(messages(), (Strings{"expr.hlsl:1:1: error: missing ')' after 'defined'"}));
}

TEST_F(PreprocessorTest, TheExpressionEvaluatorReportsItsFirstErrorAndGivesNothing) {
  EXPECT_FALSE(evaluate("1 / 0 + (2"));
  EXPECT_EQ(messages(), (Strings{"expr.hlsl:1:3: error: division by zero in preprocessor expression"}));
  EXPECT_FALSE(evaluate("1 +"));
  EXPECT_EQ(messages(), (Strings{"expr.hlsl:1:3: error: expected value in expression"}));
  // A division in an operand that is not evaluated is no error.
  const std::optional<pp_detail::ExpressionValue> value = evaluate("1 || 1 / 0");
  ASSERT_TRUE(value);
  EXPECT_EQ(value->v, 1u);
  EXPECT_TRUE(messages().empty());
}

// --- directives --------------------------------------------------------------------------------------

TEST_F(PreprocessorTest, ErrorAndWarningDirectives) {
  EXPECT_EQ(run("a\n#error shader needs  \"FOO\" // why\n#warning careful\n#error\nb"), "a b");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:2:2: error: shader needs  \"FOO\"", "main.hlsl:3:2: warning: careful",
                                 "main.hlsl:4:2: error: #error"}));
}

TEST_F(PreprocessorTest, PragmasAreRecordedUnexpanded) {
  EXPECT_EQ(run("#define FOO 1\n#pragma vertex vert\n#pragma multi_compile _ FOO BAR\n#pragma once\nx\n#pragma\n"),
            "x");
  const std::vector<Pragma>& pragmas = pp_->pragmas();
  ASSERT_EQ(pragmas.size(), 2u);
  EXPECT_EQ(pragmas[0].name, "vertex");
  ASSERT_EQ(pragmas[0].args.size(), 1u);
  EXPECT_EQ(pragmas[0].args[0].text, "vert");
  EXPECT_EQ(sources_.resolve(pragmas[0].loc).to_string(), "main.hlsl:2:9");
  EXPECT_EQ(pragmas[1].name, "multi_compile");
  ASSERT_EQ(pragmas[1].args.size(), 3u);
  EXPECT_EQ(pragmas[1].args[0].text, "_");
  EXPECT_EQ(pragmas[1].args[1].text, "FOO");
  EXPECT_EQ(pragmas[1].args[2].text, "BAR");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:6:2: warning: empty #pragma"}));
}

TEST_F(PreprocessorTest, UnknownDirectivesAndNullDirective) {
  EXPECT_EQ(run("#foo bar\n#\n# 42\nx # y\n  # define Z 1\nZ"), "x # y 1");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:1:2: error: unknown directive '#foo'",
                                 "main.hlsl:3:3: error: unknown directive '#42'"}));
  EXPECT_EQ(tokens_[1].kind, TokenKind::Hash);
}

TEST_F(PreprocessorTest, DirectiveLinesSpliceAndCarryComments) {
  EXPECT_EQ(run("#define LONG a + \\\n  b /* comment\n still */ + c\nLONG"), "a + b + c");
}

// --- includes ------------------------------------------------------------------------------------------

TEST_F(PreprocessorTest, IncludeQuotedIsRelativeToTheIncludingFile) {
  write("shaders/sub/common.hlsl", "float common;\n#include \"../other.hlsl\"\n");
  write("shaders/other.hlsl", "float other;");
  const fs::path main = write("shaders/main.hlsl", "#include \"sub/common.hlsl\"\nfloat main_;");
  EXPECT_EQ(run_file(load(main)), "float common ; float other ; float main_ ;");
  EXPECT_TRUE(messages().empty());
  ASSERT_EQ(pp_->files().size(), 3u);
  EXPECT_EQ(sources_.path(pp_->files()[0]), main);
  EXPECT_EQ(sources_.path(pp_->files()[1]), temp_dir() / "shaders/sub/common.hlsl");
  EXPECT_EQ(sources_.resolve(tokens_[0].loc).line, 1u);
  EXPECT_EQ(sources_.resolve(tokens_[0].loc).file, (temp_dir() / "shaders/sub/common.hlsl").string());
}

TEST_F(PreprocessorTest, IncludeWithWindowsSeparators) {
  write("sub/lib.hlsl", "lib");
  const fs::path main = write("main.hlsl", "#include \"sub\\lib.hlsl\"");
  EXPECT_EQ(run_file(load(main)), "lib");
  EXPECT_EQ(messages(), Strings{});
}

TEST_F(PreprocessorTest, IncludeSearchOrder) {
  write("local/a.hlsl", "local_a");
  write("dir1/a.hlsl", "dir1_a");
  write("dir1/b.hlsl", "dir1_b");
  write("dir2/b.hlsl", "dir2_b");
  write("dir2/c.hlsl", "dir2_c");
  const fs::path main =
      write("local/main.hlsl", "#include \"a.hlsl\"\n#include <a.hlsl>\n#include \"b.hlsl\"\n#include <c.hlsl>\n");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "dir1", temp_dir() / "dir2"};
  EXPECT_EQ(run_file(load(main), options), "local_a dir1_a dir1_b dir2_c");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, IncludeNotFoundListsTheSearchedDirectories) {
  const fs::path main = write("m/main.hlsl", "#include \"x.hlsl\"\n#include   <y.hlsl>\nafter");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "dir1", temp_dir() / "dir2"};
  EXPECT_EQ(run_file(load(main), options), "after");
  const std::string d1 = (temp_dir() / "dir1").string();
  const std::string d2 = (temp_dir() / "dir2").string();
  const std::string m = (temp_dir() / "m").string();
  const std::string name = main.string();
  EXPECT_EQ(
      messages(),
      (Strings{name + ":1:10: error: cannot find include file 'x.hlsl' (searched: " + m + ", " + d1 + ", " + d2 + ")",
               name + ":2:12: error: cannot find include file 'y.hlsl' (searched: " + d1 + ", " + d2 + ")"}));
}

TEST_F(PreprocessorTest, IncludeFromAnInMemoryFileUsesOnlyTheIncludeDirectories) {
  write("inc/lib.hlsl", "lib");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "inc"};
  EXPECT_EQ(run("#include \"lib.hlsl\"\n#include \"none.hlsl\"", options), "lib");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:2:10: error: cannot find include file 'none.hlsl' (searched: " +
                                 (temp_dir() / "inc").string() + ")"}));
  run("#include <none.hlsl>\n#include\n#include foo\n#include \"\"");
  EXPECT_EQ(messages(),
            (Strings{"main.hlsl:1:10: error: cannot find include file 'none.hlsl' (no directories to search)",
                     "main.hlsl:2:2: error: expected \"file\" or <file> after #include",
                     "main.hlsl:3:10: error: expected \"file\" or <file> after #include",
                     "main.hlsl:4:10: error: empty file name in #include"}));
}

// A file found in an include directory is held to the folders through links in the directory,
// and through a link to the directory itself.
TEST_F(PreprocessorTest, IncludeDirectoryLinksAreFollowedAndHeldToTheFolders) {
  write("outside/secret.hlsl", "secret");
  write("real/inc/sub/lib.hlsl", "lib");
  fs::create_symlink(temp_dir() / "outside", temp_dir() / "real/inc/out");
  fs::create_symlink(temp_dir() / "real/inc/sub", temp_dir() / "real/inc/in");
  fs::create_symlink(temp_dir() / "real/inc", temp_dir() / "inc_link");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "inc_link"};
  EXPECT_EQ(run("#include \"sub/lib.hlsl\"\n#include \"in/lib.hlsl\"\n#include \"out/secret.hlsl\"\n"
                "#include <sub/../sub/lib.hlsl>\n#include <sub//lib.hlsl>",
                options),
            "lib lib lib lib");
  const std::string folder = (temp_dir() / "inc_link").string();
  EXPECT_EQ(messages(), (Strings{"main.hlsl:3:10: error: include file 'out/secret.hlsl' is outside the folders this "
                                 "shader was given (" +
                                 folder + "); an include may not leave them"}));
  ASSERT_EQ(pp_->files().size(), 2u);
  EXPECT_EQ(sources_.path(pp_->files()[1]), temp_dir() / "real/inc/sub/lib.hlsl");
}

// A quoted #include in an included file is looked up below that file's resolved folder: a link
// there (to a folder or to a file) is still followed and held to the folders, and `..` resolved,
// whether the main file came from disk (through a link to its folder) or from memory.
TEST_F(PreprocessorTest, LinksBelowAnIncludedFileAreFollowedAndHeldToTheFolders) {
  write("outside/secret.hlsl", "secret");
  write("shaders/inc/sub/lib.hlsl", "lib\n#include \"near.hlsl\"");
  write("shaders/inc/sub/near.hlsl", "near");
  write("shaders/up.hlsl", "up");
  write("shaders/inc/a.hlsl",
        "#include \"in/lib.hlsl\"\n#include \"out/secret.hlsl\"\n#include \"file_out.hlsl\"\n"
        "#include \"../up.hlsl\"\n#include \"sub/lib.hlsl\"\n");
  fs::create_symlink(temp_dir() / "outside", temp_dir() / "shaders/inc/out");
  fs::create_symlink(temp_dir() / "shaders/inc/sub", temp_dir() / "shaders/inc/in");
  fs::create_symlink(temp_dir() / "outside/secret.hlsl", temp_dir() / "shaders/inc/file_out.hlsl");
  fs::create_symlink(temp_dir() / "shaders", temp_dir() / "shaders_link");
  write("shaders/main.hlsl", "#include \"inc/a.hlsl\"\nmain");
  PreprocessorOptions from_link;
  from_link.include_dirs = {temp_dir() / "shaders_link"};
  for (const bool from_disk : {true, false}) {
    sources_ = SourceManager();  // a file keeps the name it was first loaded by
    const std::string out = from_disk ? run_file(load(temp_dir() / "shaders_link/main.hlsl"))
                                      : run("#include \"inc/a.hlsl\"\nmain", from_link);
    EXPECT_EQ(out, "lib near up lib near main");
    const std::string given = (temp_dir() / (from_disk ? "shaders" : "shaders_link")).string();
    const std::string a = given + "/inc/a.hlsl";
    const std::string refused =
        "' is outside the folders this shader was given (" + given + "); an include may not leave them";
    EXPECT_EQ(messages(), (Strings{a + ":2:10: error: include file 'out/secret.hlsl" + refused,
                                   a + ":3:10: error: include file 'file_out.hlsl" + refused}));
    ASSERT_EQ(pp_->files().size(), 5u);
    EXPECT_EQ(sources_.path(pp_->files()[2]), temp_dir() / "shaders/inc/sub/lib.hlsl");
    EXPECT_EQ(sources_.name(pp_->files()[3]), (temp_dir() / "shaders/inc/sub/near.hlsl").string());
  }
}

// One #include line names a file of the including file's folder: the same line in files of two
// folders names two files, and again in the first folder the first file. Nothing found in one run
// is taken for granted in the next.
TEST_F(PreprocessorTest, AnIncludeLineIsLookedUpFromItsFolderInEachRun) {
  write("a/common.hlsl", "a_common");
  write("b/common.hlsl", "b_common");
  write("a/x.hlsl", "#include \"common.hlsl\"\n#include \"common.hlsl\"\n");
  write("b/y.hlsl", "#include \"common.hlsl\"\n#include <late.hlsl>\n");
  write("dir2/late.hlsl", "dir2_late");
  const fs::path main = write("main.hlsl", "#include \"a/x.hlsl\"\n#include \"b/y.hlsl\"\n#include \"a/x.hlsl\"\n");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "dir1", temp_dir() / "dir2"};
  EXPECT_EQ(run_file(load(main), options), "a_common a_common b_common dir2_late a_common a_common");
  write("dir1/late.hlsl", "dir1_late");
  EXPECT_EQ(run_file(load(main), options), "a_common a_common b_common dir1_late a_common a_common");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, IncludeThroughAMacro) {
  write("inc/lib.hlsl", "lib");
  PreprocessorOptions options;
  options.include_dirs = {temp_dir() / "inc"};
  EXPECT_EQ(run("#define LIB \"lib.hlsl\"\n#define ANGLED <lib.hlsl>\n#include LIB\n#include ANGLED", options),
            "lib lib");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, PragmaOnceAndGuardsIncludeAFileOnce) {
  write("once.hlsl", "#pragma once\nonce");
  write("guarded.hlsl", "// leading comment\n#ifndef GUARDED\n#define GUARDED\nguarded\n#endif\n");
  write("plain.hlsl", "plain");
  const fs::path main = write("main.hlsl",
                              "#include \"once.hlsl\"\n#include \"guarded.hlsl\"\n#include \"plain.hlsl\"\n"
                              "#include \"once.hlsl\"\n#include \"guarded.hlsl\"\n#include \"plain.hlsl\"\n");
  EXPECT_EQ(run_file(load(main)), "once guarded plain plain");
  EXPECT_TRUE(messages().empty());
  EXPECT_EQ(pp_->files().size(), 4u);  // each once
  EXPECT_TRUE(pp_->pragmas().empty());
}

TEST_F(PreprocessorTest, GuardedFileIsReadAgainWhenItsGuardIsUndefined) {
  write("g.hlsl", "#ifndef G\n#define G\ng\n#endif");
  const fs::path main = write("main.hlsl", "#include \"g.hlsl\"\n#undef G\n#include \"g.hlsl\"\n#include \"g.hlsl\"");
  EXPECT_EQ(run_file(load(main)), "g g");
}

TEST_F(PreprocessorTest, ThreeFileIncludeCycle) {
  write("a.hlsl", "a\n#include \"b.hlsl\"\n");
  write("b.hlsl", "b\n#include \"c.hlsl\"\n");
  write("c.hlsl", "c\n#include \"a.hlsl\"\n");
  const fs::path a = temp_dir() / "a.hlsl";
  // The second round (a b c, read only to reach the cycle) is dropped: the chain's tokens come once.
  EXPECT_EQ(run_file(load(a)), "a b c");
  EXPECT_EQ(messages(), (Strings{(temp_dir() / "c.hlsl").string() +
                                 ":2:2: error: #include cycle: a.hlsl -> b.hlsl -> c.hlsl -> a.hlsl -> ..."}));
}

TEST_F(PreprocessorTest, IncludeCycleDropsThePragmasAndConditionalsOfTheRepeatedRound) {
  write("a.hlsl", "#pragma vertex a\n#if 1\na1\n#include \"b.hlsl\"\na2\n#endif\n");
  write("b.hlsl", "#ifdef NEVER\n#else\nb1\n#include \"a.hlsl\"\nb2\n#endif\n");
  const fs::path main = write("main.hlsl", "m1\n#include \"a.hlsl\"\nm2\n");
  // main a b a b [a: cycle]; the second a and b are dropped and b's first reading goes on.
  EXPECT_EQ(run_file(load(main)), "m1 a1 b1 b2 a2 m2");
  EXPECT_EQ(messages(), (Strings{(temp_dir() / "b.hlsl").string() +
                                 ":4:2: error: #include cycle: a.hlsl -> b.hlsl -> a.hlsl -> ..."}));
  ASSERT_EQ(pp_->pragmas().size(), 1u);
  EXPECT_EQ(pp_->pragmas()[0].name, "vertex");
}

TEST_F(PreprocessorTest, GuardedSelfIncludeIsFine) {
  const fs::path self = write("self.hlsl", "#ifndef SELF\n#define SELF\nself\n#include \"self.hlsl\"\n#endif\n");
  EXPECT_EQ(run_file(load(self)), "self");
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, IncludeDepthLimit) {
  const size_t chain = Preprocessor::kMaxIncludeDepth + 6;
  for (size_t i = 0; i < chain; ++i)
    write("f" + std::to_string(i) + ".hlsl", "#include \"f" + std::to_string(i + 1) + ".hlsl\"\n" + std::to_string(i));
  write("f" + std::to_string(chain) + ".hlsl", "end");
  run_file(load(temp_dir() / "f0.hlsl"));
  const std::string last = (temp_dir() / ("f" + std::to_string(Preprocessor::kMaxIncludeDepth - 1) + ".hlsl")).string();
  EXPECT_EQ(messages(), (Strings{last + ":1:2: error: #include nested too deeply (more than 64 levels)"}));
  EXPECT_EQ(tokens_.front().text, std::to_string(Preprocessor::kMaxIncludeDepth - 1));
  EXPECT_EQ(pp_->files().size(), Preprocessor::kMaxIncludeDepth);
}

TEST_F(PreprocessorTest, ConditionalsDoNotCrossFiles) {
  write("open.hlsl", "#if 1\nopen\n");
  const fs::path main = write("main.hlsl", "#include \"open.hlsl\"\nafter\n#endif\n");
  EXPECT_EQ(run_file(load(main)), "open after");
  EXPECT_EQ(messages(), (Strings{(temp_dir() / "open.hlsl").string() + ":1:2: error: unterminated #if",
                                 main.string() + ":3:2: error: #endif without #if"}));
}

TEST_F(PreprocessorTest, MacroCallDoesNotRunPastTheEndOfAnIncludedFile) {
  write("f.hlsl", "#define F(x) [x]\nF");
  const fs::path main = write("main.hlsl", "#include \"f.hlsl\"\n(1)");
  EXPECT_EQ(run_file(load(main)), "F ( 1 )");
}

// --- limits and robustness --------------------------------------------------------------------------------

TEST_F(PreprocessorTest, ExponentialExpansionIsCutOff) {
  std::string text = "#define X0 a b\n";
  for (int i = 1; i <= 40; ++i)
    text += "#define X" + std::to_string(i) + " X" + std::to_string(i - 1) + " X" + std::to_string(i - 1) + "\n";
  text +=
      "X40\n#define D(x) x x\n#define D2(x) D(D(x))\n#define D4(x) D2(D2(x))\n#define D8(x) D4(D4(x))\n"
      "D8(D8(D8(D8(q))))";
  const auto start = std::chrono::steady_clock::now();
  run(text);
  EXPECT_LT(seconds_since(start), 1.5 * kTimeScale);
  ASSERT_FALSE(messages().empty());
  EXPECT_EQ(messages()[0],
            "main.hlsl:42:1: error: macro expansion is too large (more than 1048576 tokens); "
            "macros are no longer expanded");
  EXPECT_EQ(count_eof(), 1u);
}

TEST_F(PreprocessorTest, DoublingTextsArePaidForToo) {
  // Each level doubles a pasted token, or a stringized string with its escapes.
  std::string text = "#define D(x) x ## x\n#define E(x) D(x)\n#define S(x) #x #x\n#define T(x) S(x)\n";
  for (const char* macro : {"E", "T"}) {
    for (int i = 0; i < 60; ++i) text += std::string(macro) + "(";
    text += "ab" + std::string(60, ')') + "\n";
  }
  const auto start = std::chrono::steady_clock::now();
  run(text);
  EXPECT_LT(seconds_since(start), 1.5 * kTimeScale);
  ASSERT_FALSE(messages().empty());
  EXPECT_NE(messages()[0].find("error: macro expansion is too large"), std::string::npos) << messages()[0];
}

TEST_F(PreprocessorTest, LongMacroChainHitsTheExpansionDepthLimit) {
  std::string text;
  for (int i = 0; i < 400; ++i) text += "#define M" + std::to_string(i) + " M" + std::to_string(i + 1) + "\n";
  text += "M0\n";
  EXPECT_EQ(run(text), "M256");
  EXPECT_EQ(messages(), (Strings{"main.hlsl:401:1: error: macro expansion nested too deeply (more than 256 levels)"}));
}

TEST_F(PreprocessorTest, DeeplyNestedCallsAreBounded) {
  std::string text = "#define F(x) x\n";
  for (int i = 0; i < 1000; ++i) text += "F(";
  text += "1";
  text += std::string(1000, ')');
  const auto start = std::chrono::steady_clock::now();
  run(text);
  EXPECT_LT(seconds_since(start), 1.0 * kTimeScale);
  EXPECT_EQ(diagnostics_->error_count(), 1u) << ::testing::PrintToString(messages());
  ASSERT_FALSE(messages().empty());
  // The 66th F is the first in an argument nested 65 levels deep: 2 columns per level.
  EXPECT_EQ(messages()[0], "main.hlsl:2:131: error: macro calls nested too deeply in arguments (more than 64 levels)");
}

TEST_F(PreprocessorTest, OneMebibyteLineRunsQuickly) {
  std::string text = "#define M(x) x\n";
  while (text.size() < (1u << 20)) text += "a+M(b)*1.5-";
  text += "z\n";
  const auto start = std::chrono::steady_clock::now();
  run(text);
  EXPECT_LT(seconds_since(start), 1.0 * kTimeScale);
  EXPECT_GT(tokens_.size(), 500000u);
  EXPECT_TRUE(messages().empty());
}

TEST_F(PreprocessorTest, RandomInputNeverBreaksIt) {
  static const char* kPieces[] = {
      "#define ", "#undef ", "#if ", "#ifdef ", "#ifndef ", "#elif ", "#else", "#endif",      "#include ",
      "#pragma ", "#error ", "\n",   "\n",      "\n",       " ",      "A",     "B",           "F",
      "G",        "(",       ")",    ",",       "#",        "##",     "...",   "__VA_ARGS__", "defined",
      "1",        "0",       "/",    "%",       "?",        ":",      "\"s\"", "<x>",         "/*",
      "*/",       "//",      "\\\n", "x",       "+",        "-",      "'",     "\0"};
  std::mt19937 random(42);
  const auto start = std::chrono::steady_clock::now();
  for (int round = 0; round < 300; ++round) {
    std::string text = "#define F(a, b) a ## b # a\n#define G(...) F(__VA_ARGS__) G\n#define A B F\n#define B A G(\n";
    const size_t pieces = random() % 200;
    for (size_t i = 0; i < pieces; ++i) {
      const char* piece = kPieces[random() % (sizeof kPieces / sizeof kPieces[0])];
      text += *piece ? std::string(piece) : std::string(1, '\0');
    }
    SourceManager sources;
    DiagnosticEngine diagnostics(sources);
    Preprocessor pp(sources, diagnostics, {});
    const std::vector<Token> tokens = pp.run(sources.add("r.hlsl", text));
    ASSERT_FALSE(tokens.empty());
    ASSERT_EQ(tokens.back().kind, TokenKind::EndOfFile);
  }
  EXPECT_LT(seconds_since(start), 1.5 * kTimeScale);
}

}  // namespace
}  // namespace xshade::hlsl
