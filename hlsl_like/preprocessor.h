// The C-style preprocessor of hlsl_like: #include, macros, conditionals and pragmas.
//
// Works on tokens, as C's does: keywords are plain identifiers here, so a macro may be named like
// one. The output is the whole translation unit's token stream, ending in EndOfFile, with each
// token at the location the user wrote it (a token from a macro body is placed at the macro's
// invocation, where the user can see it).
#pragma once

#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl {

struct MacroDefinition {
  std::string name;
  std::string value;  // "1" when given as -D NAME alone
};

// Macros read once and then shared, read-only, by every preprocessor given them (the prelude):
// a compile starts from the table instead of lexing and parsing the same #define lines again.
// A preprocessor copies a macro of the table into its own state only when the source uses it.
class PredefinedMacros {
 public:
  // Each definition is read as a `#define NAME VALUE` line; the first invalid one is the error.
  static Result<std::shared_ptr<const PredefinedMacros>> read(const std::vector<MacroDefinition>& definitions);
  ~PredefinedMacros();

  struct Table;  // the macros, their text and their lookup: preprocessor_internal.h
  const Table& table() const { return *table_; }

 private:
  explicit PredefinedMacros(std::unique_ptr<Table> table);
  std::unique_ptr<Table> table_;
};

struct PreprocessorOptions {
  std::vector<std::filesystem::path> include_dirs;     // searched after the including file's folder
  std::shared_ptr<const PredefinedMacros> predefined;  // defined first; may be empty
  std::vector<MacroDefinition> defines;                // -D on the command line, keywords of a variant
};

// A `#pragma` line other than `#pragma once`, kept for the front end to interpret
// (vertex, fragment, multi_compile, shader_feature, ...).
struct Pragma {
  std::string_view name;    // the first word after #pragma
  std::vector<Token> args;  // the rest of the line, not macro-expanded
  Loc loc;                  // of the name
  // In the program Unity reads pragmas from: the main file, or a file reached from it by
  // Unity's `#include_with_pragmas` alone. A file a plain #include reads along the way is not:
  // Unity ignores its own pragmas there (multi_compile, vertex, target, ...).
  bool in_program = true;
};

// Where `#include "name"` (or `<name>` when `angled`) from `including_file` resolves: an absolute
// name as it is; otherwise the including file's folder (quoted form only, and only for a file
// on disk), then `include_dirs` in order. Every folder looked in is added to `searched`.
std::optional<std::filesystem::path> find_include(std::string_view name, const std::filesystem::path& including_file,
                                                  bool angled, const std::vector<std::filesystem::path>& include_dirs,
                                                  std::vector<std::filesystem::path>* searched = nullptr);

class Preprocessor {
 public:
  Preprocessor(SourceManager& sources, DiagnosticEngine& diagnostics, PreprocessorOptions options);

  // Preprocesses `main_file` (an index in `sources`). Errors go to the diagnostics engine; the
  // stream is still complete enough for the parser to report more.
  std::vector<Token> run(uint32_t main_file);

  const std::vector<Pragma>& pragmas() const { return pragmas_; }
  // Every file read, the main file first: what a compile depends on.
  const std::vector<uint32_t>& files() const { return files_; }
  // The predefined macros (the prelude's) the source #defines or #undefs itself, as Unity's
  // include files do: another compiler handed the prelude must not have these, or it sees two
  // definitions.
  const std::set<std::string>& redefined_predefined() const { return redefined_predefined_; }

  // Limits that keep hostile input finite; each is an error when reached.
  static constexpr size_t kMaxIncludeDepth = 64;
  static constexpr size_t kMaxExpansionDepth = 256;
  static constexpr size_t kMaxConditionalDepth = 256;

 private:
  struct Impl;
  friend class PredefinedMacros;  // reads its definitions with the same Impl
  SourceManager& sources_;
  DiagnosticEngine& diagnostics_;
  PreprocessorOptions options_;
  std::vector<Pragma> pragmas_;
  std::vector<uint32_t> files_;
  std::set<std::string> redefined_predefined_;
  std::deque<std::string> text_store_;  // text of tokens made by # and ##; stable addresses
};

}  // namespace xshade::hlsl
