// Source locations and diagnostics: where in which file something was found, and what.
#pragma once

#include <cstdint>
#include <string>

namespace xshade {

struct SourceLocation {
  std::string file;     // empty when the error has no source file
  uint32_t line = 0;    // 1-based; 0 = unknown
  uint32_t column = 0;  // 1-based; 0 = unknown

  bool known() const { return !file.empty(); }
  // "file:line:col", "file:line" or "file", as much as is known.
  std::string to_string() const;
};

enum class Severity { Note, Warning, Error };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;
  // The source line and a caret under the column, each line indented, as a compiler prints them
  // below the message; empty where the source is not at hand.
  std::string excerpt = {};

  // "file:line:col: error: message", the form compilers print and editors jump to.
  std::string to_string() const;
};

}  // namespace xshade
