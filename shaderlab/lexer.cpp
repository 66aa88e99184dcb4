#include "shaderlab/lexer.h"

#include <cctype>
#include <cstdio>

namespace xshade::shaderlab {
namespace {

bool word_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool word_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

bool Token::is_word(std::string_view word) const { return kind == TokenKind::Word && same_word(text, word); }

void Lexer::advance(size_t count) {
  for (size_t i = 0; i < count && pos_ < text_.size(); ++i, ++pos_) {
    if (text_[pos_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
  }
}

void Lexer::skip_space_and_comments() {
  for (;;) {
    const char c = at();
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
      advance();
    } else if (c == '/' && at(1) == '/') {
      while (pos_ < text_.size() && at() != '\n') advance();
    } else if (c == '/' && at(1) == '*') {
      advance(2);
      while (pos_ < text_.size() && !(at() == '*' && at(1) == '/')) advance();
      advance(2);  // an unterminated comment ends with the file
    } else {
      return;
    }
  }
}

Token Lexer::peek() {
  if (!peeked_) {
    peeked_token_ = next();
    peeked_ = true;
  }
  return peeked_token_;
}

Token Lexer::program(Token start, ProgramLanguage language, bool include, std::string_view end_word) {
  start.kind = TokenKind::Program;
  start.language = language;
  start.include = include;
  start.text_line = line_;
  start.text_column = column_;
  const size_t begin = pos_;
  // Unity ends the block at the first end word that stands alone as a word, wherever it is.
  for (size_t found = text_.find(end_word, pos_); found != std::string_view::npos;
       found = text_.find(end_word, found + 1)) {
    const bool alone_before = found == 0 || !word_char(text_[found - 1]);
    const size_t after = found + end_word.size();
    const bool alone_after = after >= text_.size() || !word_char(text_[after]);
    if (!alone_before || !alone_after) continue;
    start.text = std::string(text_.substr(begin, found - begin));
    advance(after - pos_);
    return start;
  }
  start.kind = TokenKind::Bad;
  start.text = start.text + " has no " + std::string(end_word) + " before the end of the file";
  advance(text_.size() - pos_);
  return start;
}

Token Lexer::next() {
  if (peeked_) {
    peeked_ = false;
    return peeked_token_;
  }
  skip_space_and_comments();
  Token token;
  token.line = line_;
  token.column = column_;
  const char c = at();
  if (pos_ >= text_.size()) return token;
  if (c == '"') {
    advance();
    const size_t begin = pos_;
    while (pos_ < text_.size() && at() != '"' && at() != '\n') advance();
    if (at() != '"') {
      token.kind = TokenKind::Bad;
      token.text = "a string that does not end on its line";
      return token;
    }
    token.kind = TokenKind::String;
    token.text = std::string(text_.substr(begin, pos_ - begin));
    advance();
    return token;
  }
  const bool signed_number = (c == '-' || c == '+') && (digit(at(1)) || (at(1) == '.' && digit(at(2))));
  if (digit(c) || signed_number || (c == '.' && digit(at(1)))) {
    const size_t begin = pos_;
    advance();
    while (digit(at()) || at() == '.' ||
           ((at() == 'e' || at() == 'E') && (digit(at(1)) || ((at(1) == '-' || at(1) == '+') && digit(at(2)))))) {
      if (at() == 'e' || at() == 'E') advance();
      advance();
    }
    token.kind = TokenKind::Number;
    // 2D, 3D, 2DArray: a type name that starts with a digit.
    if (word_start(at())) {
      while (word_char(at())) advance();
      token.kind = TokenKind::Word;
    }
    token.text = std::string(text_.substr(begin, pos_ - begin));
    return token;
  }
  if (word_start(c)) {
    const size_t begin = pos_;
    while (word_char(at())) advance();
    token.kind = TokenKind::Word;
    token.text = std::string(text_.substr(begin, pos_ - begin));
    // Program blocks, by Unity's words (upper case, as Unity requires them).
    struct Block {
      std::string_view open, close;
      ProgramLanguage language;
      bool include;
    };
    static constexpr Block kBlocks[] = {
        {"CGPROGRAM", "ENDCG", ProgramLanguage::Cg, false},
        {"CGINCLUDE", "ENDCG", ProgramLanguage::Cg, true},
        {"HLSLPROGRAM", "ENDHLSL", ProgramLanguage::Hlsl, false},
        {"HLSLINCLUDE", "ENDHLSL", ProgramLanguage::Hlsl, true},
        {"GLSLPROGRAM", "ENDGLSL", ProgramLanguage::Glsl, false},
        {"GLSLINCLUDE", "ENDGLSL", ProgramLanguage::Glsl, true},
    };
    for (const Block& block : kBlocks)
      if (token.text == block.open) return program(token, block.language, block.include, block.close);
    return token;
  }
  token.kind = TokenKind::Punct;
  token.text = std::string(1, c);
  advance();
  if (std::string_view("{}()[],=+-").find(c) == std::string_view::npos) {
    token.kind = TokenKind::Bad;
    const bool printable = c > ' ' && c < 127;
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned char>(c));
    token.text =
        std::string("a character ShaderLab does not use: '") + (printable ? std::string(1, c) : std::string(hex)) + "'";
  }
  return token;
}

std::string Lexer::raw_until(char open, char close, bool& closed) {
  int depth = 1;
  const size_t begin = pos_;
  while (pos_ < text_.size()) {
    const char c = at();
    if (c == '\n') break;  // an attribute ends on its line
    if (c == open) ++depth;
    if (c == close && --depth == 0) {
      std::string raw(text_.substr(begin, pos_ - begin));
      advance();
      closed = true;
      return raw;
    }
    advance();
  }
  closed = false;
  return std::string(text_.substr(begin, pos_ - begin));
}

}  // namespace xshade::shaderlab
