// ShaderLab's tokens: words (keywords and names, `2D` among them), strings, numbers, punctuation,
// and a program block (CGPROGRAM ... ENDCG and its kin) as one token holding its text. Comments
// (// and /* */) are skipped outside program blocks. Every token knows its line and column.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "shaderlab/shader.h"

namespace xshade::shaderlab {

enum class TokenKind { Word, String, Number, Punct, Program, End, Bad };

struct Token {
  TokenKind kind = TokenKind::End;
  std::string text;  // a word, a string's contents, a number as written, a punctuation character
  uint32_t line = 1, column = 1;
  // A Program token: which block, and where its text starts.
  ProgramLanguage language = ProgramLanguage::Cg;
  bool include = false;
  uint32_t text_line = 1, text_column = 1;

  bool is(char punct) const { return kind == TokenKind::Punct && text.size() == 1 && text[0] == punct; }
  bool is_word(std::string_view word) const;  // ignoring case, as ShaderLab reads keywords
};

class Lexer {
 public:
  // A UTF-8 byte order mark at the start is not part of the text.
  explicit Lexer(std::string_view text) : text_(text.starts_with("\xEF\xBB\xBF") ? text.substr(3) : text) {}

  Token next();
  Token peek();
  // The raw text up to the `close` that ends a bracket opened just before (nested brackets of
  // the same kind counted), consumed with it; for attribute arguments such as [Header(A, b.)],
  // which are not tokens. Sets `closed` false when the text ends first.
  std::string raw_until(char open, char close, bool& closed);
  uint32_t line() const { return line_; }
  uint32_t column() const { return column_; }

 private:
  void skip_space_and_comments();
  char at(size_t offset = 0) const { return pos_ + offset < text_.size() ? text_[pos_ + offset] : '\0'; }
  void advance(size_t count = 1);
  Token program(Token start, ProgramLanguage language, bool include, std::string_view end_word);

  std::string_view text_;
  size_t pos_ = 0;
  uint32_t line_ = 1, column_ = 1;
  bool peeked_ = false;
  Token peeked_token_;
};

}  // namespace xshade::shaderlab
