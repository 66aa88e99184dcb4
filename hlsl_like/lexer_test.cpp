#include "hlsl_like/lexer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/hang_guard.h"

namespace xshade::hlsl {
namespace {

const char* kind_name(TokenKind kind) {
  switch (kind) {
    case TokenKind::EndOfFile: return "eof";
    case TokenKind::Identifier: return "id";
    case TokenKind::IntLiteral: return "int";
    case TokenKind::FloatLiteral: return "float";
    case TokenKind::StringLiteral: return "str";
    case TokenKind::AngledHeader: return "header";
    case TokenKind::Punct: return "punct";
    case TokenKind::Hash: return "hash";
    case TokenKind::HashHash: return "hashhash";
    case TokenKind::Unknown: return "unknown";
  }
  return "?";
}

// Lexes a whole text; keeps the source, the diagnostics and the tokens together.
struct Lexed {
  explicit Lexed(std::string text) {
    file = sources.add("t.hlsl", std::move(text));
    Lexer lexer(sources.text(file), file, diagnostics, &store);  // spliced tokens outlive the lexer
    for (;;) {
      tokens.push_back(lexer.next());
      if (tokens.back().kind == TokenKind::EndOfFile) break;
    }
  }
  // "kind text" for each token but the EndOfFile.
  std::vector<std::string> kinds() const {
    std::vector<std::string> out;
    for (const Token& t : tokens)
      if (t.kind != TokenKind::EndOfFile) out.push_back(std::string(kind_name(t.kind)) + " " + std::string(t.text));
    return out;
  }
  std::vector<std::string> texts() const {
    std::vector<std::string> out;
    for (const Token& t : tokens)
      if (t.kind != TokenKind::EndOfFile) out.push_back(std::string(t.text));
    return out;
  }
  std::string where(size_t i) const {
    return std::to_string(tokens[i].loc.line) + ":" + std::to_string(tokens[i].loc.column);
  }
  std::vector<std::string> messages() const {
    std::vector<std::string> out;
    for (const Diagnostic& d : diagnostics.diagnostics()) out.push_back(d.to_string());
    return out;
  }

  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  std::deque<std::string> store;
  uint32_t file = 0;
  std::vector<Token> tokens;
};

using Strings = std::vector<std::string>;

TEST(Lexer, EmptyTextIsOneEndOfFileAgainAndAgain) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t file = sources.add("e.hlsl", "");
  Lexer lexer(sources.text(file), file, diagnostics);
  for (int i = 0; i < 3; ++i) {
    const Token t = lexer.next();
    EXPECT_EQ(t.kind, TokenKind::EndOfFile);
    EXPECT_EQ(t.loc.line, 1u);
    EXPECT_EQ(t.loc.column, 1u);
  }
  EXPECT_TRUE(diagnostics.diagnostics().empty());
}

TEST(Lexer, IdentifiersAndKeywordsAreIdentifiers) {
  Lexed l("float4 _x9 main return __VA_ARGS__");
  EXPECT_EQ(l.kinds(), (Strings{"id float4", "id _x9", "id main", "id return", "id __VA_ARGS__"}));
}

TEST(Lexer, IntegerForms) {
  Lexed l("0 12 0x1F 0XaBc 7u 7U 3l 3L 10ul 077");
  EXPECT_EQ(l.kinds(), (Strings{"int 0", "int 12", "int 0x1F", "int 0XaBc", "int 7u", "int 7U", "int 3l", "int 3L",
                                "int 10ul", "int 077"}));
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, FloatForms) {
  Lexed l("1.0 .5 1. 2e-3 1.5e+2f 3E4 0.5f 1.h 2.0H 1.0F 4.0l 5.0L .5e1");
  EXPECT_EQ(l.kinds(),
            (Strings{"float 1.0", "float .5", "float 1.", "float 2e-3", "float 1.5e+2f", "float 3E4", "float 0.5f",
                     "float 1.h", "float 2.0H", "float 1.0F", "float 4.0l", "float 5.0L", "float .5e1"}));
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, ExponentWithoutDigitsIsAnError) {
  Lexed l("x = 1e;\ny = 2e+ ;");
  EXPECT_EQ(l.kinds(), (Strings{"id x", "punct =", "float 1e", "punct ;", "id y", "punct =", "float 2e+", "punct ;"}));
  EXPECT_EQ(l.messages(),
            (Strings{"t.hlsl:1:5: error: exponent has no digits", "t.hlsl:2:5: error: exponent has no digits"}));
}

TEST(Lexer, BadNumberSuffixesAndEmptyHex) {
  Lexed l("12abc 1.5q 0x 3uz");
  EXPECT_EQ(l.texts(), (Strings{"12abc", "1.5q", "0x", "3uz"}));
  EXPECT_EQ(l.messages(), (Strings{"t.hlsl:1:1: error: invalid suffix 'abc' on integer literal",
                                   "t.hlsl:1:7: error: invalid suffix 'q' on floating literal",
                                   "t.hlsl:1:12: error: hexadecimal literal has no digits",
                                   "t.hlsl:1:15: error: invalid suffix 'uz' on integer literal"}));
}

TEST(Lexer, DotIsPunctUnlessADigitFollows) {
  Lexed l("a.xyz 1.x");
  EXPECT_EQ(l.kinds()[0], "id a");
  EXPECT_EQ(l.kinds()[1], "punct .");
  EXPECT_EQ(l.kinds()[2], "id xyz");
  EXPECT_EQ(l.kinds()[3], "float 1.x");  // a suffix error, not a swizzle
}

TEST(Lexer, EveryPunctuatorByLongestMatch) {
  const Strings all{"(",  ")",  "[",  "]",  "{", "}",  ";",  ",",  ".",  "?",  ":",  "::", "+",  "-",   "*",
                    "/",  "%",  "++", "--", "=", "+=", "-=", "*=", "/=", "%=", "==", "!=", "<",  ">",   "<=",
                    ">=", "&&", "||", "!",  "~", "&",  "|",  "^",  "<<", ">>", "&=", "|=", "^=", "<<=", ">>="};
  std::string text;
  for (const std::string& p : all) text += p + " ";
  Lexed l(text);
  Strings expected;
  for (const std::string& p : all) expected.push_back("punct " + p);
  EXPECT_EQ(l.kinds(), expected);
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, PunctuatorsWithoutSpacesSplitGreedily) {
  Lexed l("a<<=b>>c+++d->e::f");
  EXPECT_EQ(l.texts(), (Strings{"a", "<<=", "b", ">>", "c", "++", "+", "d", "-", ">", "e", "::", "f"}));
}

TEST(Lexer, HashAndHashHash) {
  Lexed l("# ## ### a#b");
  EXPECT_EQ(l.kinds(), (Strings{"hash #", "hashhash ##", "hashhash ##", "hash #", "id a", "hash #", "id b"}));
}

TEST(Lexer, StringsWithEscapes) {
  Lexed l(R"("plain" "with \"quote\" and \\" "")");
  EXPECT_EQ(l.kinds(), (Strings{R"(str "plain")", R"(str "with \"quote\" and \\")", R"(str "")"}));
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, UnterminatedStringIsAnErrorAtTheQuote) {
  Lexed l("a = \"open\r\nb");
  EXPECT_EQ(l.texts(), (Strings{"a", "=", "\"open", "b"}));
  EXPECT_EQ(l.messages(), (Strings{"t.hlsl:1:5: error: unterminated string literal"}));
  EXPECT_EQ(l.where(3), "2:1");
  Lexed at_end("\"abc\\");
  EXPECT_EQ(at_end.messages(), (Strings{"t.hlsl:1:1: error: unterminated string literal"}));
}

TEST(Lexer, CommentsAreSkippedAndCountAsSpace) {
  Lexed l("a// line comment\nb/* block\n comment */c /**/d/*x*/");
  EXPECT_EQ(l.texts(), (Strings{"a", "b", "c", "d"}));
  EXPECT_EQ(l.where(1), "2:1");
  EXPECT_EQ(l.where(2), "3:12");
  EXPECT_TRUE(l.tokens[1].at_line_start);
  EXPECT_TRUE(l.tokens[2].space_before);    // the comment stands for a space
  EXPECT_FALSE(l.tokens[2].at_line_start);  // newlines inside a comment start no line
  EXPECT_TRUE(l.tokens[3].space_before);
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, UnterminatedCommentIsAnErrorAtItsStartThenEndOfFile) {
  Lexed l("x\n  /* never\n closed");
  ASSERT_EQ(l.tokens.size(), 2u);
  EXPECT_EQ(l.tokens[1].kind, TokenKind::EndOfFile);
  EXPECT_EQ(l.messages(), (Strings{"t.hlsl:2:3: error: unterminated comment"}));
}

TEST(Lexer, LineCommentContinuesOverASplice) {
  Lexed l("a // comment \\\n still comment\nb");
  EXPECT_EQ(l.texts(), (Strings{"a", "b"}));
  EXPECT_EQ(l.where(1), "3:1");
}

TEST(Lexer, BackslashNewlineSplicesInsideTokens) {
  Lexed l("ab\\\ncd 1\\\r\n.5 +\\\n= \"x\\\ny\"\nnext");
  EXPECT_EQ(l.kinds(), (Strings{"id abcd", "float 1.5", "punct +=", "str \"xy\"", "id next"}));
  EXPECT_EQ(l.where(0), "1:1");
  EXPECT_EQ(l.where(1), "2:4");
  EXPECT_EQ(l.where(2), "3:4");
  EXPECT_EQ(l.where(3), "4:3");
  EXPECT_EQ(l.where(4), "6:1");
  EXPECT_TRUE(l.tokens[4].at_line_start);
  EXPECT_TRUE(l.messages().empty());
}

TEST(Lexer, SpliceBetweenTokensIsNotANewLine) {
  Lexed l("a \\\n b\\\nc");
  EXPECT_EQ(l.texts(), (Strings{"a", "bc"}));
  EXPECT_FALSE(l.tokens[1].at_line_start);
  EXPECT_EQ(l.where(1), "2:2");
}

TEST(Lexer, CrLfLineEndings) {
  Lexed l("a\r\n  b\r\n\r\nc");
  EXPECT_EQ(l.texts(), (Strings{"a", "b", "c"}));
  EXPECT_EQ(l.where(1), "2:3");
  EXPECT_EQ(l.where(2), "4:1");
  EXPECT_TRUE(l.tokens[2].at_line_start);
}

TEST(Lexer, ColumnsAreByteColumnsAfterTabs) {
  Lexed l("\tx\t\ty\n \tz");
  EXPECT_EQ(l.where(0), "1:2");
  EXPECT_EQ(l.where(1), "1:5");
  EXPECT_EQ(l.where(2), "2:3");
}

TEST(Lexer, LineStartAndSpaceFlags) {
  Lexed l("a b(c)\n  d");
  EXPECT_TRUE(l.tokens[0].at_line_start);
  EXPECT_FALSE(l.tokens[0].space_before);
  EXPECT_TRUE(l.tokens[1].space_before);
  EXPECT_FALSE(l.tokens[1].at_line_start);
  EXPECT_FALSE(l.tokens[2].space_before);  // (
  EXPECT_TRUE(l.tokens[5].at_line_start);
  EXPECT_TRUE(l.tokens[5].space_before);
}

TEST(Lexer, UnusedBytesComeBackAsUnknownOneByteEach) {
  std::string text = "a@$`'";
  text += '\0';
  text += "\xC3\xA9z";
  Lexed l(text);
  ASSERT_EQ(l.tokens.size(), 10u);
  EXPECT_EQ(l.tokens[0].kind, TokenKind::Identifier);
  for (size_t i = 1; i <= 7; ++i) {
    EXPECT_EQ(l.tokens[i].kind, TokenKind::Unknown) << i;
    EXPECT_EQ(l.tokens[i].text.size(), 1u);
  }
  EXPECT_EQ(l.tokens[5].text[0], '\0');
  EXPECT_EQ(l.tokens[8].text, "z");
  EXPECT_TRUE(l.messages().empty());  // reported by whoever meets them
  Lexed lone_backslash("a \\ b");
  EXPECT_EQ(lone_backslash.kinds(), (Strings{"id a", "unknown \\", "id b"}));
}

TEST(Lexer, ByteOrderMarkAtTheStartIsSkipped) {
  Lexed l(
      "\xEF\xBB\xBF"
      "float x;\n"
      "\xEF\xBB\xBF");
  EXPECT_EQ(l.kinds()[0], "id float");
  EXPECT_EQ(l.where(0), "1:1");
  EXPECT_TRUE(l.tokens[0].at_line_start);
  EXPECT_EQ(l.tokens[3].kind, TokenKind::Unknown);  // only at the very start
}

TEST(Lexer, RestOfLineForErrorDirectives) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t file = sources.add("r.hlsl", "#error  this /* c */ is \\\nbad // tail\r\nnext");
  Lexer lexer(sources.text(file), file, diagnostics);
  EXPECT_EQ(lexer.next().kind, TokenKind::Hash);
  EXPECT_EQ(lexer.next().text, "error");
  EXPECT_EQ(lexer.rest_of_line(), "this   is bad");
  const Token next = lexer.next();
  EXPECT_EQ(next.text, "next");
  EXPECT_TRUE(next.at_line_start);
  EXPECT_EQ(next.loc.line, 3u);
}

TEST(Lexer, HeaderNamesAfterInclude) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t file = sources.add("h.hlsl", "<dir/a b.h> x\n<open\n");
  Lexer lexer(sources.text(file), file, diagnostics);
  const Token header = lexer.next_header_name();
  EXPECT_EQ(header.kind, TokenKind::AngledHeader);
  EXPECT_EQ(header.text, "<dir/a b.h>");
  EXPECT_EQ(lexer.next_header_name().text, "x");
  const Token open = lexer.next_header_name();  // no '>' on the line: just a '<'
  EXPECT_TRUE(open.is_punct("<"));
}

TEST(Lexer, LineEndedAndSkipToDirective) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  const uint32_t file = sources.add("s.hlsl",
                                    "#if 0 /* x */\n"
                                    "don't \"#endif\" 1e /* \n#endif */ x\n"
                                    "  ## not\n"
                                    "   # endif\n"
                                    "tail\n");
  Lexer lexer(sources.text(file), file, diagnostics);
  EXPECT_EQ(lexer.next().kind, TokenKind::Hash);
  EXPECT_EQ(lexer.next().text, "if");
  EXPECT_FALSE(lexer.line_ended());
  EXPECT_EQ(lexer.next().text, "0");
  EXPECT_TRUE(lexer.line_ended());
  const Token hash = lexer.skip_to_directive();
  EXPECT_EQ(hash.kind, TokenKind::Hash);
  EXPECT_EQ(hash.loc.line, 5u);
  EXPECT_EQ(hash.loc.column, 4u);
  EXPECT_EQ(lexer.next().text, "endif");
  EXPECT_TRUE(lexer.line_ended());
  EXPECT_EQ(lexer.next().text, "tail");
  EXPECT_EQ(lexer.skip_to_directive().kind, TokenKind::EndOfFile);
  EXPECT_TRUE(diagnostics.diagnostics().empty());
}

TEST(Lexer, TokensPointIntoTheSource) {
  Lexed l("alpha beta");
  EXPECT_EQ(l.tokens[1].text.data(), l.sources.text(l.file).data() + 6);
}

TEST(Lexer, OneMebibyteLineIsFastAndSafe) {
  std::string text;
  text.reserve(1 << 20);
  while (text.size() < (1u << 20)) text += "a1+b.5*";
  const auto start = std::chrono::steady_clock::now();
  Lexed l(text);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GT(l.tokens.size(), 500000u);
  EXPECT_LT(seconds, 1.0 * kTimeScale);
  Lexed one_identifier(std::string(1 << 20, 'x'));
  ASSERT_EQ(one_identifier.tokens.size(), 2u);
  EXPECT_EQ(one_identifier.tokens[0].text.size(), 1u << 20);
}

TEST(Lexer, BinaryGarbageNeverBreaksIt) {
  std::mt19937 random(1234);
  for (int round = 0; round < 200; ++round) {
    std::string text(size_t(random() % 300), '\0');
    for (char& c : text) {
      // Mostly the characters that matter to the lexer, some anything.
      static const char kInteresting[] = "\\\n\r\"/*#.0e+x<>=&|'";
      c = random() % 2 ? kInteresting[random() % (sizeof kInteresting - 1)] : char(random() % 256);
    }
    SourceManager sources;
    DiagnosticEngine diagnostics(sources);
    const uint32_t file = sources.add("g.hlsl", text);
    Lexer lexer(sources.text(file), file, diagnostics);
    size_t count = 0;
    while (lexer.next().kind != TokenKind::EndOfFile) ASSERT_LT(++count, text.size() + 1);
    Lexer skipper(sources.text(file), file, diagnostics);
    for (int i = 0; i < 400 && skipper.skip_to_directive().kind != TokenKind::EndOfFile; ++i) skipper.rest_of_line();
  }
}

}  // namespace
}  // namespace xshade::hlsl
