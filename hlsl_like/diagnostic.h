// Source locations, diagnostics and the Result type every xshade library returns.
//
// Errors travel as values: a function that can fail returns Result<T>, whose error carries a
// message, an optional source location and any further diagnostics (a compiler's full list).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tl/expected.hpp>

namespace xshade {

struct SourceLocation {
  std::string file;   // empty when the error has no source file
  uint32_t line = 0;  // 1-based; 0 = unknown
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

  // "file:line:col: error: message", the form compilers print and editors jump to.
  std::string to_string() const;
};

struct Error {
  std::string message;
  SourceLocation where;
  std::vector<Diagnostic> diagnostics;  // details, e.g. every error of a failed compile

  // The message with its location, then one line per diagnostic.
  std::string to_string() const;
};

template <class T>
using Result = tl::expected<T, Error>;

inline tl::unexpected<Error> fail(std::string message, SourceLocation where = {}) {
  return tl::unexpected<Error>(Error{std::move(message), std::move(where), {}});
}

inline tl::unexpected<Error> fail(Error error) { return tl::unexpected<Error>(std::move(error)); }

}  // namespace xshade
