// How deep a TOML file may nest before it is parsed. toml++ reads a dotted key (`a.b.c = 1`, a
// table header `[a.b.c]`) by recursing once per part, so a file of one key with 100,000 parts
// overflows the stack and kills the process before toml++ can report anything. Every TOML file
// xshade reads (scene files, the project file, the golden manifest) is held to this limit first,
// by a lexer that only knows where strings and comments are.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "base/result.h"

namespace xshade::harness {

// The most parts a dotted key or table header may have, and the deepest inline tables and
// arrays may nest. xshade's own files use at most 3 parts (`grid.vary._Metallic`) and 3 levels;
// toml++ survives some 30,000 parts on an 8 MB stack (less under AddressSanitizer, whose frames
// are larger) and caps inline nesting at 256 itself. 100 is far above any real file and far
// below either.
inline constexpr size_t kMaxTomlNesting = 100;

// Refuses `text` when a dotted key or table header has more than kMaxTomlNesting parts, or
// inline tables and arrays nest deeper than that, at the key's first part or the bracket that
// goes too deep (file:line:col in `file`). Text inside strings and comments does not count. A
// syntax error is left for toml++ to report.
Result<void> check_toml_nesting(std::string_view text, const std::string& file);

}  // namespace xshade::harness
