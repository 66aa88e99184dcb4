// Tokens: what the lexer makes, the preprocessor expands and the parser reads.
#pragma once

#include <cstdint>
#include <string_view>

#include "hlsl_like/source_manager.h"

namespace xshade::hlsl {

enum class TokenKind : uint8_t {
  EndOfFile,
  Identifier,     // keywords too: the parser tells them apart, so macros may share their names
  IntLiteral,     // 12, 0x1F, 7u, 3l
  FloatLiteral,   // 1.0, .5f, 2e-3, 1.5h
  StringLiteral,  // "..." (annotations, #include)
  AngledHeader,   // <name> after #include
  Punct,          // operators and punctuation; `text` says which
  Hash,           // # (directives, stringizing)
  HashHash,       // ## (token pasting)
  Unknown,        // a character the language has no use for; reported by whoever meets it
};

struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  bool at_line_start = false;  // first token on its line: where directives begin
  bool space_before = false;   // whitespace precedes it: needed to rebuild and stringize text
  std::string_view text;       // into the source, or into the preprocessor's own text store
  Loc loc;

  bool is(TokenKind k) const { return kind == k; }
  bool is_punct(std::string_view p) const { return kind == TokenKind::Punct && text == p; }
  bool is_identifier(std::string_view name) const { return kind == TokenKind::Identifier && text == name; }
};

}  // namespace xshade::hlsl
