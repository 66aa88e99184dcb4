// The Result type every xshade library returns, and the Error it carries.
//
// Errors travel as values: a function that can fail returns Result<T>, whose error carries a
// message, an optional source location, any further diagnostics (a compiler's full list) and a
// kind, which says whose fault it is and so which exit code the command line gives.
#pragma once

#include <string>
#include <vector>

#include <tl/expected.hpp>

#include "base/diagnostic.h"

namespace xshade {

enum class ErrorKind {
  UserInput,    // a shader, scene, project file, image or mesh that is wrong: the user fixes it
  Usage,        // the command line asks for something that does not exist or cannot be
  CheckFailed,  // the input was fine and ran, and a check on what it made failed
  Backend,      // a driver, a lane or the machine could not do what was asked
  Internal,     // xshade broke its own rule
};

struct Error {
  std::string message;
  SourceLocation where;
  std::vector<Diagnostic> diagnostics;  // details, e.g. every error of a failed compile
  ErrorKind kind = ErrorKind::UserInput;

  // The message with its location, then each diagnostic on its own line, with its excerpt.
  std::string to_string() const;
};

template <class T>
using Result = tl::expected<T, Error>;

// A failure names its kind where the error is born, where whose fault it is is known: there is no
// overload without one.
inline tl::unexpected<Error> fail(ErrorKind kind, std::string message, SourceLocation where = {}) {
  return tl::unexpected<Error>(Error{std::move(message), std::move(where), {}, kind});
}

inline tl::unexpected<Error> fail(Error error) { return tl::unexpected<Error>(std::move(error)); }

}  // namespace xshade
