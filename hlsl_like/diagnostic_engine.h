// Where every phase of the front end reports problems: collected with locations, counted, and
// printed the way compilers print them, with the source line and a caret.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "hlsl_like/source_manager.h"

namespace xshade::hlsl {

class DiagnosticEngine {
 public:
  explicit DiagnosticEngine(const SourceManager& sources) : sources_(sources) {}

  void error(Loc loc, std::string message) { report(Severity::Error, loc, std::move(message)); }
  void warning(Loc loc, std::string message) { report(Severity::Warning, loc, std::move(message)); }
  void note(Loc loc, std::string message) { report(Severity::Note, loc, std::move(message)); }
  void report(Severity severity, Loc loc, std::string message);

  // Forgets everything reported so far (a front end that runs a phase again reports anew).
  void clear() {
    diagnostics_.clear();
    locs_.clear();
    errors_ = warnings_ = 0;
  }

  size_t error_count() const { return errors_; }
  size_t warning_count() const { return warnings_; }
  bool has_errors() const { return errors_ > 0; }
  // After this many errors further ones are dropped and one note says so: a run of cascading
  // errors helps nobody, and bad input must not make the output grow without bound.
  static constexpr size_t kErrorLimit = 50;

  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  const SourceManager& sources() const { return sources_; }

  // "file:line:col: error: message", the source line, and a caret under the column. The line
  // is shown as a terminal can print it: a tab becomes spaces to the next multiple of
  // kTabWidth columns and any other byte outside printable ASCII becomes \xNN, with the caret
  // still under the character it points at.
  std::string render(size_t index) const;
  static constexpr size_t kTabWidth = 8;
  std::string render_all() const;
  // The errors, each with its excerpt (Diagnostic::excerpt): what a failed compile reports.
  std::vector<Diagnostic> errors_with_excerpts() const;

 private:
  // The source line and caret of diagnostic `index`, as render shows them below its message.
  std::string excerpt(size_t index) const;

  const SourceManager& sources_;
  std::vector<Diagnostic> diagnostics_;
  std::vector<Loc> locs_;  // beside diagnostics_, for the source line of each
  size_t errors_ = 0;
  size_t warnings_ = 0;
};

// How every message quotes what the author wrote (a name, a semantic, a type): in single quotes,
// cut to kMaxQuotedLength characters and "...", with bytes outside printable ASCII as \xNN.
// A fuzzed 1 MiB identifier must not become a 1 MiB message, nor a NUL byte cut it short.
inline constexpr size_t kMaxQuotedLength = 64;
std::string in_quotes(std::string_view text);
// The same without the quotes, for the parts of a longer quoted text (a function signature).
std::string clipped(std::string_view text);

}  // namespace xshade::hlsl
