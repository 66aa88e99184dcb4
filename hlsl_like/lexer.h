// Source text to tokens, one at a time.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <string_view>

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl {

class Lexer {
 public:
  // `text` must outlive the tokens: they point into it. A token that a backslash-newline splits
  // gets its joined text from `text_store` (the lexer's own store when none is given, which then
  // lives only as long as the lexer).
  Lexer(std::string_view text, uint32_t file, DiagnosticEngine& diagnostics,
        std::deque<std::string>* text_store = nullptr);

  // The next token; EndOfFile at the end, and again on every later call. Comments are skipped
  // (an unterminated block comment is an error at its start), backslash-newline joins lines,
  // and a character the language does not use comes back as Unknown for the caller to report.
  Token next();

  // Inside a directive: the rest of the current line as raw text (for #error), without the
  // line ending; the lexer moves to the next line. Comments become one space, spliced lines are
  // joined, and surrounding whitespace is trimmed.
  std::string_view rest_of_line();
  // After `#include`: reads <name> as one AngledHeader token when the next character is '<'.
  Token next_header_name();

  // For directives: skips whitespace and comments and says whether the next token starts a new
  // line (or the text has ended), i.e. whether the current directive line is over.
  bool line_ended();
  // For skipped conditional blocks: skips whole lines (minding comments, strings and splices,
  // reporting nothing but an unterminated comment) up to one whose first token is '#', and
  // returns that '#'; EndOfFile when there is none.
  Token skip_to_directive();

 private:
  static constexpr size_t npos = static_cast<size_t>(-1);

  void next_other(Token& token);  // next() for a token other than the common ones; pos_ at its start
  void skip_space();
  void skip_block_comment(size_t star);  // pos_ at the '/', `star` at the '*'
  void skip_line_comment(size_t second_slash);
  void skip_line();  // the rest of the line and its newline, lexing nothing
  size_t splice_at(size_t p) const;
  size_t past_splices(size_t p) const {  // the common case, no backslash, inline
    return p < text_.size() && text_[p] == '\\' ? past_splices_slow(p) : p;
  }
  size_t past_splices_slow(size_t p) const;
  int char_at(size_t p) const { return p < text_.size() ? static_cast<unsigned char>(text_[p]) : -1; }
  void move_to(size_t p);  // pos_ = p, counting the lines in between
  void new_line(size_t next_line_start) {
    ++line_;
    line_start_ = next_line_start;
  }
  Loc loc_at(size_t p) const { return Loc{file_, line_, static_cast<uint32_t>(p - line_start_ + 1)}; }
  size_t lex_number(size_t start, Loc loc, TokenKind& kind);
  std::string_view store(std::string text);
  std::string_view token_text(size_t start, size_t end);

  std::string_view text_;
  uint32_t file_;
  DiagnosticEngine& diagnostics_;
  size_t pos_ = 0;
  uint32_t line_ = 1;
  size_t line_start_ = 0;
  bool at_line_start_ = true;
  bool space_ = false;          // whitespace or a comment since the last token
  size_t first_splice_ = npos;  // inside the token being lexed
  // The text's last character cannot continue a name (a file ends with a line end, as a rule):
  // then a name stops before the end of the text on its own, and its characters are read with
  // no test of the end.
  bool ends_outside_names_ = false;
  std::deque<std::string>* store_;
  std::unique_ptr<std::deque<std::string>> own_store_;
};

}  // namespace xshade::hlsl
