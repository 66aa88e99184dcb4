// The preprocessor, private: its state and the steps its files share. Only those files include
// it, and preprocessor_test.cpp, which reaches a subsystem (the #if evaluator, the macro table)
// on its own through it.
//
//   preprocessor.cpp    the public entry, the token loop over the files, directive dispatch
//   pp_macros.cpp       #define/#undef, expansion, # and ##, __FILE__/__LINE__, predefined macros
//   pp_expressions.cpp  #if/#elif constant expressions
//   pp_includes.cpp     #include: resolution, the given folders, the include stack and its limits
//   pp_directives.cpp   the conditional stack, #pragma, #line, #error/#warning
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/lexer.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl {
namespace pp_detail {

// Work done by expansion (tokens made) before the preprocessor stops expanding: a few lines of
// doubling macros must not hang the compiler or fill memory.
inline constexpr size_t kMaxExpandedTokens = size_t(1) << 20;

struct PPTok {
  Token tok;
  bool no_expand = false;    // names a macro that was disabled when it was read: never expanded
  bool placemarker = false;  // an empty argument next to ##; removed after substitution
};

struct BodyToken {
  Token tok;
  int param = -1;  // index of the parameter this identifier names, or -1
};

struct Macro {
  std::string_view name;
  Loc loc;
  bool function_like = false;
  bool variadic = false;
  bool disabled = false;  // being expanded: its frame is on a stack
  bool warned_self = false;
  bool predefined = false;  // a copy of the predefined table's (the prelude's)
  std::vector<std::string_view> params;
  std::vector<BodyToken> body;
};

struct Frame {
  std::vector<PPTok> tokens;
  size_t pos = 0;
  Macro* macro = nullptr;
};

// A place tokens are read and expanded from: macro frames over a base that is either the files
// (the main context) or a token list (an argument being pre-expanded, a #if line).
struct Context {
  std::vector<Frame> frames;
  const std::vector<PPTok>* list = nullptr;
  size_t list_pos = 0;
  size_t list_end = 0;
  PPTok pushback;
  bool has_pushback = false;
  bool carry_space = false;  // an expansion that vanished leaves its spacing to the next token
  bool carry_line_start = false;
  bool in_if = false;         // a #if line: the operand of a `defined` from a macro is kept
  uint8_t defined_state = 0;  // 1 after `defined`, 2 after `defined (`
};

struct Args {
  std::vector<PPTok> tokens;
  std::vector<size_t> starts;  // argument i is tokens[starts[i], starts[i + 1])
};

struct Cond {
  Loc loc;
  std::string_view directive;  // if, ifdef or ifndef
  bool taken = false;          // a group of this chain has been (or is being) emitted
  bool seen_else = false;
};

// Multiple-include optimisation: a file wholly inside `#ifndef X ... #endif` is skipped unread
// when it is included again while X is defined.
enum class Guard : uint8_t { Start, Inside, Closed, None };

struct IncludeFrame {
  IncludeFrame(std::string_view text, uint32_t index, DiagnosticEngine& diagnostics, std::deque<std::string>* store,
               size_t conds, size_t output, size_t pragmas)
      : lexer(text, index, diagnostics, store),
        file(index),
        cond_base(conds),
        output_mark(output),
        pragma_mark(pragmas) {}
  Lexer lexer;
  uint32_t file;
  size_t cond_base;    // conditionals open when the file was entered
  size_t output_mark;  // output tokens and pragmas made before the file was entered
  size_t pragma_mark;
  bool finished = false;
  bool in_program = true;  // its pragmas are the program's (Pragma::in_program)
  Guard guard = Guard::Start;
  size_t guard_cond = 0;
  std::string_view guard_macro;
  // The folder a quoted #include in the file looks in first, made on its first #include.
  bool folder_known = false;
  std::string folder;
};

// The value of a #if expression or of one of its operands.
struct ExpressionValue {
  uint64_t v = 0;
  bool is_unsigned = false;
};

// A message quotes at most 80 characters of a name or token: hostile input can make them huge.
inline std::string clip(std::string_view text) {
  if (text.size() <= 80) return std::string(text);
  return std::string(text.substr(0, 80)) + "...";
}

inline bool is_punct1(const Token& token, char c) {
  return token.kind == TokenKind::Punct && token.text.size() == 1 && token.text[0] == c;
}

inline Token make_token(TokenKind kind, std::string_view text, Loc loc) {
  Token token;
  token.kind = kind;
  token.text = text;
  token.loc = loc;
  return token;
}

// find_include on strings: the including file's folder (null for an angled name or a file not on
// disk) and the path found, in `found` (overwritten, kept for its buffer), are the strings
// std::filesystem::path would hold.
bool find_include_path(std::string_view name, const std::string* including_folder,
                       const std::vector<std::filesystem::path>& include_dirs, std::string& found,
                       std::vector<std::filesystem::path>* searched);

// A #if or #elif line's tokens, macros already expanded, evaluated as C does: integer arithmetic
// on 64 bits, signed unless a u suffix or a too large literal makes a value unsigned. A `defined`
// still in the tokens (one that came out of a macro) asks `is_defined`. The first error is
// reported and gives nothing; `end` is where an error found at the end of the line is reported.
std::optional<ExpressionValue> evaluate_expression(const std::vector<PPTok>& tokens, Loc end,
                                                   DiagnosticEngine& diagnostics,
                                                   const std::function<bool(std::string_view)>& is_defined);

}  // namespace pp_detail

struct PredefinedMacros::Table {
  std::deque<std::string> text;  // what the macros' names and tokens point into
  std::deque<pp_detail::Macro> macros;
  std::unordered_map<std::string_view, const pp_detail::Macro*> by_name;
  std::array<uint64_t, 16> filter{};  // as Preprocessor::Impl::filter_
};

struct Preprocessor::Impl {
  using PPTok = pp_detail::PPTok;
  using Macro = pp_detail::Macro;
  using Context = pp_detail::Context;
  using Args = pp_detail::Args;
  using Cond = pp_detail::Cond;
  using Guard = pp_detail::Guard;
  using IncludeFrame = pp_detail::IncludeFrame;

  explicit Impl(Preprocessor& pp) : pp_(pp), sources_(pp.sources_), diagnostics_(pp.diagnostics_) {
    for (std::string_view builtin : {"__FILE__", "__LINE__"}) {
      const size_t bit = filter_bit(builtin);
      filter_[bit >> 6] |= uint64_t(1) << (bit & 63);
    }
    if (pp.options_.predefined) {
      predefined_ = &pp.options_.predefined->table();
      for (size_t i = 0; i < filter_.size(); ++i) filter_[i] |= predefined_->filter[i];
    }
  }

  std::vector<Token> run(uint32_t main_file);
  // Reads each definition as a #define line (the options' -D and keywords).
  void define(const std::vector<MacroDefinition>& definitions);
  // Hands every macro defined so far to a table of predefined macros.
  void export_macros(PredefinedMacros::Table& table);

 private:
  // Macros (pp_macros.cpp).
  // From the length and the first and last two characters, mixed: names that differ only in the
  // middle are rare, while float2 and fixed2, or float4x4 and fixed4x4, must not share a bit, or
  // every vector type in a shader would be looked up in the macro tables.
  static size_t filter_bit(std::string_view name) {
    const size_t n = name.size();
    const auto at = [&](size_t i) { return uint32_t(static_cast<unsigned char>(name[i])); };
    const uint32_t second = n > 1 ? at(1) : 0;
    const uint32_t before_last = n > 1 ? at(n - 2) : 0;
    const uint32_t mixed = uint32_t(n) * 0x9E3779B1u + at(0) * 0x85EBCA77u + at(n - 1) * 0xC2B2AE3Du +
                           second * 0x27D4EB2Fu + before_last * 0x165667B1u;
    return mixed >> 22;  // the top 10 bits: the best mixed
  }
  bool maybe_macro(std::string_view name) const {
    const size_t bit = filter_bit(name);
    return (filter_[bit >> 6] >> (bit & 63)) & 1;
  }
  Macro* find(std::string_view name) {
    if (name.empty() || !maybe_macro(name)) return nullptr;
    auto it = macros_.find(name);
    if (it != macros_.end()) return it->second;  // null after #undef of a predefined macro
    return predefined_ ? adopt_predefined(name) : nullptr;
  }
  // A predefined macro is copied on first use: expansion marks the macro it is expanding, and
  // the shared table must stay untouched.
  Macro* adopt_predefined(std::string_view name) {
    auto it = predefined_->by_name.find(name);
    if (it == predefined_->by_name.end()) return nullptr;
    macro_pool_.push_back(*it->second);
    Macro* adopted = &macro_pool_.back();
    adopted->predefined = true;
    macros_.emplace(adopted->name, adopted);
    return adopted;
  }
  bool is_defined(std::string_view name) { return find(name) != nullptr || name == "__FILE__" || name == "__LINE__"; }
  void do_define(Lexer& lex, Loc directive_loc);
  void do_undef(Lexer& lex, const Token& name);
  void add_macro(Macro macro);
  void warn_self(Macro& macro, Loc loc);
  std::string_view store(std::string text) {
    pp_.text_store_.push_back(std::move(text));
    return pp_.text_store_.back();
  }

  // Reading and expanding (pp_macros.cpp).
  bool raw_next(Context& ctx, PPTok& out, bool stop_at_file_end);
  bool expand_next(Context& ctx, PPTok& out, bool stop_at_file_end);
  bool try_expand(Context& ctx, PPTok& token);
  bool collect_args(Context& ctx, const Macro& macro, const Token& name, Args& args);
  void substitute(const Macro& macro, const Token& name, const Args* args, std::vector<PPTok>& out);
  void expand_list(const std::vector<PPTok>& list, size_t begin, size_t end, std::vector<PPTok>& out,
                   bool in_if = false);
  static bool defined_operand(Context& ctx, const Token& token);
  PPTok stringize(const Args& args, int param, Loc loc);
  void paste(std::vector<PPTok>& out, const PPTok& rhs, Loc loc);
  void pop_frame(Context& ctx);
  void unwind(Context& ctx);
  bool charge(size_t tokens, Loc loc);
  std::vector<PPTok> take_buffer() {
    if (spare_.empty()) return {};
    std::vector<PPTok> buffer = std::move(spare_.back());
    spare_.pop_back();
    return buffer;
  }
  void recycle(std::vector<PPTok>&& buffer) {
    buffer.clear();
    if (spare_.size() < 64) spare_.push_back(std::move(buffer));
  }

  // Tokens from the files and directive dispatch (preprocessor.cpp).
  bool next_file_token(PPTok& out, bool stop_at_file_end);
  bool special_file_token(IncludeFrame& frame, const Token& token, bool stop_at_file_end, bool& ended);
  static void note_token(IncludeFrame& frame) {
    if (frame.guard == Guard::Start || frame.guard == Guard::Closed) frame.guard = Guard::None;
  }
  void directive(IncludeFrame& frame);
  void skip_line(Lexer& lex) {
    while (!lex.line_ended()) lex.next();
  }
  void extra_tokens(Lexer& lex, std::string_view directive_name) {
    if (lex.line_ended()) return;
    const Token token = lex.next();
    diagnostics_.warning(token.loc, "extra tokens at end of #" + std::string(directive_name) + " directive");
    skip_line(lex);
  }

  // #include and the stack of files being read (pp_includes.cpp).
  void enter_file(uint32_t file);
  void finish_file(IncludeFrame& frame);
  void do_include(IncludeFrame& frame, const Token& name);
  void include_file(IncludeFrame& frame, const Token& name, std::string_view spelled, bool angled, Loc where);
  // The folders a compile was given: the include directories and the main file's folder. An
  // include may not resolve outside them (`#include "../../etc/passwd"` is an error, not a read).
  std::vector<std::filesystem::path> given_folders_;
  // The given folders resolved (base/paths.h), on the first #include of the run. A folder that
  // exists is resolved whole and names below it are looked up from its resolved path; one the
  // file system cannot resolve holds no file.
  struct ResolvedFolder {
    std::optional<std::filesystem::path> path;
    bool exists = false;
  };
  std::vector<ResolvedFolder> resolved_folders_;
  bool folders_resolved_ = false;
  // The main file's folder is the last given folder, and already resolved when the file's path
  // was (SourceManager::path_resolved_on_load).
  bool main_folder_resolved_ = false;
  void resolve_given_folders();
  bool inside_given_folders(const std::filesystem::path& resolved_file);
  // Where an #include's name was found. `found` is the path as the search spells it (what
  // messages call the file); `file` the file already loaded from it in this run, or 0; `resolved`
  // its resolved path when the search could tell it without resolving the whole path.
  struct IncludeTarget {
    std::string& found;
    uint32_t file = 0;
    std::optional<std::filesystem::path> resolved;
    std::optional<size_t> size;  // with `resolved`: the size its lstat told
  };
  // The search of find_include_path, told apart from it by what it remembers and how it asks the
  // file system: a path this run loaded is not asked about again, and below a folder known
  // resolved each name is checked to be no link (an lstat a name) instead of stat-ing the path
  // and then resolving it (a readlink a component of the whole path). False when no folder has it.
  bool locate_include(const IncludeFrame& frame, bool local, std::string_view spelled, IncludeTarget& target);
  // The file an #include names, found, held to the given folders and loaded; 0 after an error,
  // which is reported.
  uint32_t load_include(IncludeFrame& frame, bool local, std::string_view spelled, Loc where);
  // Each path an #include found, with the file it loaded: a file included from several places
  // (and every #include of a guarded file again) is resolved, held to the folders and looked up
  // once a run, since each of those asks the file system about every component of its path.
  std::vector<std::pair<std::string, uint32_t>> loaded_includes_;
  std::string found_include_;               // the path of the #include being read; kept for its buffer
  std::string portable_name_;               // its name, each backslash made a slash; kept for its buffer
  std::string resolved_include_;            // the path found below a resolved folder; kept for its buffer
  std::vector<std::string> plain_folders_;  // below resolved folders, found to be folders and no links
  // Each #include this run read, by where its search starts (the including file's folder for a
  // quoted name in a file on disk, else the include directories only) and the name as spelled:
  // the same line again (a guarded file included by many files of a folder) is answered without
  // a search. Only for a run, as the file system may change between compiles.
  struct IncludeLookup {
    bool local;
    std::string folder;
    std::string spelled;
    uint32_t file;
  };
  std::vector<IncludeLookup> include_lookups_;
  void abandon_files_from(size_t first);
  void ensure_file_tables() {
    const size_t count = sources_.file_count();
    if (seen_.size() < count) {
      seen_.resize(count, 0);
      once_.resize(count, 0);
      guard_of_.resize(count);
      path_resolved_.resize(count, 0);
    }
  }
  std::string short_name(uint32_t file) const { return std::filesystem::path(sources_.name(file)).filename().string(); }

  // Conditionals and the other directives (pp_directives.cpp).
  void do_if(IncludeFrame& frame, const Token& name, bool guard_start);
  void do_else(IncludeFrame& frame, const Token& name);  // #elif or #else
  void do_endif(IncludeFrame& frame, const Token& name);
  void skip_group(IncludeFrame& frame, bool to_endif_only);
  void pop_cond(IncludeFrame& frame);
  void else_seen(IncludeFrame& frame);
  void do_pragma(IncludeFrame& frame, const Token& name);
  void do_message(Lexer& lex, const Token& name);  // #error or #warning
  void do_line(Lexer& lex, const Token& name);

  // A #if or #elif line's value (pp_expressions.cpp).
  bool eval_line(Lexer& lex, const Token& name);

  Preprocessor& pp_;
  SourceManager& sources_;
  DiagnosticEngine& diagnostics_;

  const PredefinedMacros::Table* predefined_ = nullptr;
  std::unordered_map<std::string_view, Macro*> macros_;
  std::deque<Macro> macro_pool_;  // stable: a macro stays alive while an expansion uses it
  std::array<uint64_t, 16> filter_{};

  std::vector<std::unique_ptr<IncludeFrame>> includes_;
  std::vector<std::unique_ptr<IncludeFrame>> abandoned_;
  std::vector<Token> out_;
  std::vector<Cond> conds_;
  std::vector<char> seen_;
  std::vector<char> once_;
  std::vector<std::string_view> guard_of_;
  // Whether a file's path is known resolved (this run resolved it, or load() did for the main
  // file): the names its quoted #includes spell are then looked up below its folder as it is.
  std::vector<char> path_resolved_;
  Loc end_loc_;

  size_t expansion_depth_ = 0;
  size_t budget_ = pp_detail::kMaxExpandedTokens;
  bool budget_spent_ = false;
  bool depth_reported_ = false;
  size_t argument_nesting_ = 0;
  std::vector<std::vector<PPTok>> spare_;
  std::vector<Token> line_;
  std::vector<PPTok> expr_in_;
};

}  // namespace xshade::hlsl
