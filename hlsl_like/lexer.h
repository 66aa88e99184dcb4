// Source text to tokens, one at a time.
#pragma once

#include <string_view>

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl {

class Lexer {
 public:
  // `text` must outlive the tokens: they point into it.
  Lexer(std::string_view text, uint32_t file, DiagnosticEngine& diagnostics);

  // The next token; EndOfFile at the end, and again on every later call. Comments are skipped
  // (an unterminated block comment is an error at its start), backslash-newline joins lines,
  // and a character the language does not use comes back as Unknown for the caller to report.
  Token next();

  // Inside a directive: the rest of the current line as raw text (for #error), without the
  // line ending; the lexer moves to the next line.
  std::string_view rest_of_line();
  // After `#include`: reads <name> as one AngledHeader token when the next character is '<'.
  Token next_header_name();

 private:
  std::string_view text_;
  uint32_t file_;
  DiagnosticEngine& diagnostics_;
  size_t pos_ = 0;
  uint32_t line_ = 1;
  size_t line_start_ = 0;
  bool at_line_start_ = true;
};

}  // namespace xshade::hlsl
