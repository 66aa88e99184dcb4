#include "shaderlab/lexer.h"

#include <vector>

#include <gtest/gtest.h>

namespace xshade::shaderlab {
namespace {

std::vector<Token> all(std::string_view text) {
  Lexer lex(text);
  std::vector<Token> tokens;
  for (Token token = lex.next(); token.kind != TokenKind::End; token = lex.next()) tokens.push_back(token);
  return tokens;
}

TEST(ShaderLabLexer, WordsStringsNumbersAndPunctuationWithTheirPlaces) {
  const auto tokens = all("_MainTex (\"Albedo\", 2D) = \"white\" {}\n  Range(-0.5, 1e-3)");
  ASSERT_EQ(tokens.size(), 16u);
  EXPECT_EQ(tokens[0].kind, TokenKind::Word);
  EXPECT_EQ(tokens[0].text, "_MainTex");
  EXPECT_EQ(tokens[2].kind, TokenKind::String);
  EXPECT_EQ(tokens[2].text, "Albedo");
  EXPECT_EQ(tokens[4].kind, TokenKind::Word) << "2D is a type name, not a number";
  EXPECT_EQ(tokens[4].text, "2D");
  EXPECT_EQ(tokens[10].text, "Range");
  EXPECT_EQ(tokens[10].line, 2u);
  EXPECT_EQ(tokens[10].column, 3u);
  EXPECT_EQ(tokens[12].kind, TokenKind::Number);
  EXPECT_EQ(tokens[12].text, "-0.5");
  EXPECT_EQ(tokens[14].text, "1e-3");
}

TEST(ShaderLabLexer, CommentsAreSkippedOutsidePrograms) {
  const auto tokens = all("Cull // Off\n/* ZWrite\n On */ Back");
  ASSERT_EQ(tokens.size(), 2u);
  EXPECT_EQ(tokens[1].text, "Back");
  EXPECT_EQ(tokens[1].line, 3u);
}

// A program block is one token: its text as written (comments and all) and where the text starts,
// ended by the first end word that stands alone.
TEST(ShaderLabLexer, AProgramBlockIsOneTokenWithWhereItsTextStarts) {
  const auto tokens = all("Pass {\n  CGPROGRAM\n  // ENDCGX is not the end\n  float4 f; ENDCG\n}");
  ASSERT_EQ(tokens.size(), 4u);
  const Token& program = tokens[2];
  EXPECT_EQ(program.kind, TokenKind::Program);
  EXPECT_EQ(program.language, ProgramLanguage::Cg);
  EXPECT_FALSE(program.include);
  EXPECT_EQ(program.text, "\n  // ENDCGX is not the end\n  float4 f; ");
  EXPECT_EQ(program.line, 2u);
  EXPECT_EQ(program.text_line, 2u);
  EXPECT_EQ(program.text_column, 12u);
  EXPECT_TRUE(tokens[3].is('}'));

  const auto hlsl = all("HLSLINCLUDE\nfloat x;\nENDHLSL");
  ASSERT_EQ(hlsl.size(), 1u);
  EXPECT_EQ(hlsl[0].language, ProgramLanguage::Hlsl);
  EXPECT_TRUE(hlsl[0].include);
}

TEST(ShaderLabLexer, AnUnendedProgramOrStringIsABadTokenThatSaysSo) {
  const auto program = all("CGPROGRAM\nfloat4 f;");
  ASSERT_EQ(program.size(), 1u);
  EXPECT_EQ(program[0].kind, TokenKind::Bad);
  EXPECT_EQ(program[0].text, "CGPROGRAM has no ENDCG before the end of the file");
  const auto text = all("Shader \"Unlit/Texture\n{");
  ASSERT_GE(text.size(), 2u);
  EXPECT_EQ(text[1].kind, TokenKind::Bad);
}

TEST(ShaderLabLexer, AttributeTextIsTakenRawUpToItsBracket) {
  Lexer lex("[Header(Main maps: albedo, [not] a list)] _X");
  ASSERT_TRUE(lex.next().is('['));
  bool closed = false;
  EXPECT_EQ(lex.raw_until('[', ']', closed), "Header(Main maps: albedo, [not] a list)");
  EXPECT_TRUE(closed);
  EXPECT_EQ(lex.next().text, "_X");
}

}  // namespace
}  // namespace xshade::shaderlab
