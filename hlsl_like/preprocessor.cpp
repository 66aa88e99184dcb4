#include "hlsl_like/preprocessor.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <system_error>
#include <unordered_map>
#include <utility>

#include "base/paths.h"
#include "hlsl_like/lexer.h"

// How expansion works: the clang scheme of a stack of token buffers ("frames"), one per macro
// expansion being read. While a macro's frame is on the stack the macro is disabled; an identifier
// that names a disabled macro when it is read is painted (`no_expand`) and never expanded again,
// which is what C's hide sets amount to. Frames are popped only when a read goes past their end,
// so the last token of an expansion is still read with its macro disabled. Arguments are
// pre-expanded in a nested context whose base is the argument's token list; that nesting is the
// only recursion, and it is bounded by kMaxExpansionDepth together with the frames.

namespace xshade::hlsl {
namespace {

// Work done by expansion (tokens made) before the preprocessor stops expanding: a few lines of
// doubling macros must not hang the compiler or fill memory.
constexpr size_t kMaxExpandedTokens = size_t(1) << 20;
// Parentheses and ?: nesting in a #if expression.
constexpr size_t kMaxExpressionDepth = 128;
// Macro calls nested in the arguments of macro calls: each level is one recursion of argument
// pre-expansion (about 1 KiB of stack, several under AddressSanitizer), so this stays well below
// kMaxExpansionDepth.
constexpr size_t kMaxArgumentNesting = 64;

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
  bool in_if = false;          // a #if line: the operand of a `defined` from a macro is kept
  uint8_t defined_state = 0;   // 1 after `defined`, 2 after `defined (`
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
  IncludeFrame(std::string_view text, uint32_t index, DiagnosticEngine& diagnostics,
               std::deque<std::string>* store, size_t conds, size_t output, size_t pragmas)
      : lexer(text, index, diagnostics, store), file(index), cond_base(conds), output_mark(output),
        pragma_mark(pragmas) {}
  Lexer lexer;
  uint32_t file;
  size_t cond_base;    // conditionals open when the file was entered
  size_t output_mark;  // output tokens and pragmas made before the file was entered
  size_t pragma_mark;
  bool finished = false;
  Guard guard = Guard::Start;
  size_t guard_cond = 0;
  std::string_view guard_macro;
};

struct Value {
  uint64_t v = 0;
  bool is_unsigned = false;
};

std::string clip(std::string_view text) {
  if (text.size() <= 80) return std::string(text);
  return std::string(text.substr(0, 80)) + "...";
}

bool is_punct1(const Token& token, char c) {
  return token.kind == TokenKind::Punct && token.text.size() == 1 && token.text[0] == c;
}

Token make_token(TokenKind kind, std::string_view text, Loc loc) {
  Token token;
  token.kind = kind;
  token.text = text;
  token.loc = loc;
  return token;
}

}  // namespace

struct PredefinedMacros::Table {
  std::deque<std::string> text;  // what the macros' names and tokens point into
  std::deque<Macro> macros;
  std::unordered_map<std::string_view, const Macro*> by_name;
  std::array<uint64_t, 16> filter{};  // as Preprocessor::Impl::filter_
};

struct Preprocessor::Impl {
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
  // Macros.
  static size_t filter_bit(std::string_view name) {
    return (name.size() * 131 + static_cast<unsigned char>(name.front()) * 7 +
            static_cast<unsigned char>(name.back())) & 1023;
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
    macros_.emplace(adopted->name, adopted);
    return adopted;
  }
  bool is_defined(std::string_view name) {
    return find(name) != nullptr || name == "__FILE__" || name == "__LINE__";
  }
  void add_macro(Macro macro);
  void warn_self(Macro& macro, Loc loc);
  std::string_view store(std::string text) {
    pp_.text_store_.push_back(std::move(text));
    return pp_.text_store_.back();
  }

  // Reading and expanding.
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

  // Files and directives.
  bool next_file_token(PPTok& out, bool stop_at_file_end);
  bool special_file_token(IncludeFrame& frame, const Token& token, bool stop_at_file_end, bool& ended);
  static void note_token(IncludeFrame& frame) {
    if (frame.guard == Guard::Start || frame.guard == Guard::Closed) frame.guard = Guard::None;
  }
  void enter_file(uint32_t file);
  void finish_file(IncludeFrame& frame);
  void directive(IncludeFrame& frame);
  void do_define(Lexer& lex, Loc directive_loc);
  void do_undef(Lexer& lex, const Token& name);
  void do_include(IncludeFrame& frame, const Token& name);
  void include_file(IncludeFrame& frame, const Token& name, std::string_view spelled, bool angled, Loc where);
  // The folders a compile was given: the include directories and the main file's folder. An
  // include may not resolve outside them (`#include "../../etc/passwd"` is an error, not a read).
  std::vector<std::filesystem::path> given_folders_;
  bool inside_given_folders(const std::filesystem::path& file) const;
  void abandon_files_from(size_t first);
  void do_if(IncludeFrame& frame, const Token& name, bool guard_start);
  void do_pragma(IncludeFrame& frame, const Token& name);
  void skip_group(IncludeFrame& frame, bool to_endif_only);
  void pop_cond(IncludeFrame& frame);
  void else_seen(IncludeFrame& frame);
  bool eval_line(Lexer& lex, const Token& name);
  void skip_line(Lexer& lex) {
    while (!lex.line_ended()) lex.next();
  }
  void extra_tokens(Lexer& lex, std::string_view directive_name) {
    if (lex.line_ended()) return;
    const Token token = lex.next();
    diagnostics_.warning(token.loc, "extra tokens at end of #" + std::string(directive_name) + " directive");
    skip_line(lex);
  }
  void ensure_file_tables() {
    const size_t count = sources_.file_count();
    if (seen_.size() < count) {
      seen_.resize(count, 0);
      once_.resize(count, 0);
      guard_of_.resize(count);
    }
  }
  std::string short_name(uint32_t file) const {
    return std::filesystem::path(sources_.name(file)).filename().string();
  }

  class ExprParser;

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
  Loc end_loc_;

  size_t expansion_depth_ = 0;
  size_t budget_ = kMaxExpandedTokens;
  bool budget_spent_ = false;
  bool depth_reported_ = false;
  size_t argument_nesting_ = 0;
  std::vector<std::vector<PPTok>> spare_;
  std::vector<Token> line_;
  std::vector<PPTok> expr_in_;
};

// ---------------------------------------------------------------------------------------------
// #if expressions: C's integer arithmetic on 64 bits, signed unless a u suffix or a too large
// literal makes a value unsigned. Precedence climbing for the binary operators; the only
// recursion is for parentheses and ?:, bounded by kMaxExpressionDepth.

class Preprocessor::Impl::ExprParser {
 public:
  ExprParser(Preprocessor::Impl& impl, DiagnosticEngine& diagnostics, const std::vector<PPTok>& tokens, Loc end)
      : impl_(impl), diagnostics_(diagnostics), t_(tokens), end_loc_(end) {}

  bool evaluate() {
    const Value value = comma(true);
    if (!failed_ && i_ < t_.size()) {
      const Token& token = t_[i_].tok;
      fail(token.loc, is_punct1(token, ')') ? std::string("unexpected ')' in expression")
                                             : "unexpected '" + clip(token.text) + "' in expression");
    }
    return !failed_ && value.v != 0;
  }

 private:
  void fail(Loc loc, std::string message) {
    if (failed_) return;
    failed_ = true;
    diagnostics_.error(loc, std::move(message));
  }
  bool at_punct(std::string_view p) const { return i_ < t_.size() && t_[i_].tok.is_punct(p); }

  Value comma(bool eval) {
    Value value = conditional(eval);
    while (!failed_ && at_punct(",")) {
      ++i_;
      value = conditional(eval);
    }
    return value;
  }

  Value conditional(bool eval) {
    Value c = binary(1, eval);
    if (failed_ || !at_punct("?")) return c;
    const Loc question = t_[i_].tok.loc;
    ++i_;
    if (++depth_ > kMaxExpressionDepth) {
      fail(question, "expression nested too deeply");
      return {};
    }
    const bool truth = c.v != 0;
    const Value a = comma(eval && truth);
    if (failed_) return {};
    if (!at_punct(":")) {
      fail(i_ < t_.size() ? t_[i_].tok.loc : end_loc_, "expected ':' in expression");
      return {};
    }
    ++i_;
    const Value b = conditional(eval && !truth);
    --depth_;
    Value result = truth ? a : b;
    result.is_unsigned = a.is_unsigned || b.is_unsigned;
    return result;
  }

  static int precedence(const Token& token) {
    if (token.kind != TokenKind::Punct) return 0;
    const std::string_view p = token.text;
    if (p == "*" || p == "/" || p == "%") return 10;
    if (p == "+" || p == "-") return 9;
    if (p == "<<" || p == ">>") return 8;
    if (p == "<" || p == ">" || p == "<=" || p == ">=") return 7;
    if (p == "==" || p == "!=") return 6;
    if (p == "&") return 5;
    if (p == "^") return 4;
    if (p == "|") return 3;
    if (p == "&&") return 2;
    if (p == "||") return 1;
    return 0;
  }

  Value binary(int min_precedence, bool eval) {
    Value lhs = unary(eval);
    for (;;) {
      if (failed_ || i_ >= t_.size()) return lhs;
      const int p = precedence(t_[i_].tok);
      if (p == 0 || p < min_precedence) return lhs;
      const Token& op = t_[i_].tok;
      ++i_;
      if (p == 2 || p == 1) {  // && and || evaluate their right side only when it matters
        const bool left = lhs.v != 0;
        const bool needed = p == 2 ? left : !left;
        const Value rhs = binary(p + 1, eval && needed);
        lhs = Value{(p == 2 ? (left && rhs.v != 0) : (left || rhs.v != 0)) ? 1u : 0u, false};
        continue;
      }
      const Value rhs = binary(p + 1, eval);
      lhs = apply(op, lhs, rhs, eval);
    }
  }

  Value apply(const Token& op, Value a, Value b, bool eval) {
    const std::string_view p = op.text;
    const bool u = a.is_unsigned || b.is_unsigned;
    const auto sa = static_cast<int64_t>(a.v);
    const auto sb = static_cast<int64_t>(b.v);
    auto boolean = [](bool x) { return Value{x ? 1u : 0u, false}; };
    if (p == "*") return {a.v * b.v, u};
    if (p == "+") return {a.v + b.v, u};
    if (p == "-") return {a.v - b.v, u};
    if (p == "/" || p == "%") {
      if (b.v == 0) {
        if (eval) fail(op.loc, "division by zero in preprocessor expression");
        return {0, u};
      }
      if (u) return {p == "/" ? a.v / b.v : a.v % b.v, true};
      if (sa == std::numeric_limits<int64_t>::min() && sb == -1) return {p == "/" ? a.v : 0, false};
      return {static_cast<uint64_t>(p == "/" ? sa / sb : sa % sb), false};
    }
    if (p == "<<" || p == ">>") {
      const bool negative_count = !b.is_unsigned && sb < 0;
      const bool too_far = negative_count || b.v >= 64;
      if (p == "<<") return {too_far ? 0 : a.v << b.v, a.is_unsigned};
      if (too_far) return {(!a.is_unsigned && sa < 0) ? ~uint64_t(0) : 0, a.is_unsigned};
      if (a.is_unsigned) return {a.v >> b.v, true};
      return {static_cast<uint64_t>(sa >> b.v), false};
    }
    if (p == "<") return boolean(u ? a.v < b.v : sa < sb);
    if (p == ">") return boolean(u ? a.v > b.v : sa > sb);
    if (p == "<=") return boolean(u ? a.v <= b.v : sa <= sb);
    if (p == ">=") return boolean(u ? a.v >= b.v : sa >= sb);
    if (p == "==") return boolean(a.v == b.v);
    if (p == "!=") return boolean(a.v != b.v);
    if (p == "&") return {a.v & b.v, u};
    if (p == "^") return {a.v ^ b.v, u};
    return {a.v | b.v, u};  // "|"
  }

  Value unary(bool eval) {
    // Prefix operators are gathered first and applied afterwards, so that a long chain of them
    // costs no recursion.
    const size_t first = i_;
    while (i_ < t_.size()) {
      const Token& token = t_[i_].tok;
      if (!(is_punct1(token, '+') || is_punct1(token, '-') || is_punct1(token, '!') || is_punct1(token, '~'))) break;
      ++i_;
    }
    const size_t last = i_;
    Value value = primary(eval);
    for (size_t k = last; k-- > first;) {
      switch (t_[k].tok.text[0]) {
        case '-': value.v = 0 - value.v; break;
        case '!': value = Value{value.v == 0 ? 1u : 0u, false}; break;
        case '~': value.v = ~value.v; break;
        default: break;
      }
    }
    return value;
  }

  Value primary(bool eval) {
    if (failed_) return {};
    if (i_ >= t_.size()) {
      fail(end_loc_, "expected value in expression");
      return {};
    }
    const Token& token = t_[i_].tok;
    switch (token.kind) {
      case TokenKind::IntLiteral:
        ++i_;
        return integer(token);
      case TokenKind::Identifier:
        ++i_;
        if (token.text == "defined") return defined(token);
        return {};  // an identifier that is not a macro counts as 0
      case TokenKind::FloatLiteral:
        fail(token.loc, "floating-point literal in preprocessor expression");
        return {};
      default:
        break;
    }
    if (is_punct1(token, '(')) {
      ++i_;
      if (++depth_ > kMaxExpressionDepth) {
        fail(token.loc, "expression nested too deeply");
        return {};
      }
      const Value value = comma(eval);
      --depth_;
      if (failed_) return {};
      if (!at_punct(")")) {
        fail(token.loc, "missing ')' in expression");
        return {};
      }
      ++i_;
      return value;
    }
    fail(token.loc, "expected value in expression, found '" + clip(token.text) + "'");
    return {};
  }

  // `defined` that only appeared through macro expansion.
  Value defined(const Token& keyword) {
    const bool paren = at_punct("(");
    if (paren) ++i_;
    if (i_ >= t_.size() || t_[i_].tok.kind != TokenKind::Identifier) {
      fail(i_ < t_.size() ? t_[i_].tok.loc : keyword.loc, "macro name missing after 'defined'");
      return {};
    }
    const bool result = impl_.is_defined(t_[i_].tok.text);
    ++i_;
    if (paren) {
      if (!at_punct(")")) {
        fail(keyword.loc, "missing ')' after 'defined'");
        return {};
      }
      ++i_;
    }
    return {result ? 1u : 0u, false};
  }

  Value integer(const Token& token) {
    const std::string_view text = token.text;
    size_t k = 0;
    unsigned base = 10;
    if (text.size() > 1 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
      base = 16;
      k = 2;
    } else if (text.size() > 1 && text[0] == '0') {
      base = 8;
    }
    uint64_t v = 0;
    bool overflow = false;
    for (; k < text.size(); ++k) {
      const char c = text[k];
      unsigned d;
      if (c >= '0' && c <= '9') {
        d = unsigned(c - '0');
      } else if (base == 16 && c >= 'a' && c <= 'f') {
        d = unsigned(c - 'a' + 10);
      } else if (base == 16 && c >= 'A' && c <= 'F') {
        d = unsigned(c - 'A' + 10);
      } else {
        break;
      }
      if (d >= base) {
        fail(token.loc, "invalid digit '" + std::string(1, c) + "' in octal literal");
        return {};
      }
      if (v > (std::numeric_limits<uint64_t>::max() - d) / base) overflow = true;
      v = v * base + d;
    }
    bool is_unsigned = false;
    for (; k < text.size(); ++k)
      if (text[k] == 'u' || text[k] == 'U') is_unsigned = true;
    if (overflow) {
      fail(token.loc, "integer literal is too large");
      return {};
    }
    if (v > uint64_t(std::numeric_limits<int64_t>::max())) is_unsigned = true;
    return {v, is_unsigned};
  }

  Preprocessor::Impl& impl_;
  DiagnosticEngine& diagnostics_;
  const std::vector<PPTok>& t_;
  Loc end_loc_;
  size_t i_ = 0;
  size_t depth_ = 0;
  bool failed_ = false;
};

// ---------------------------------------------------------------------------------------------

Preprocessor::Preprocessor(SourceManager& sources, DiagnosticEngine& diagnostics, PreprocessorOptions options)
    : sources_(sources), diagnostics_(diagnostics), options_(std::move(options)) {}

std::optional<std::filesystem::path> find_include(std::string_view name, const std::filesystem::path& including_file,
                                                  bool angled, const std::vector<std::filesystem::path>& include_dirs,
                                                  std::vector<std::filesystem::path>* searched) {
  namespace fs = std::filesystem;
  // Shaders written on Windows may spell "sub\\file.hlsl".
  std::string portable(name);
  for (char& c : portable)
    if (c == '\\') c = '/';
  const fs::path relative{portable};
  auto exists = [](const fs::path& candidate) {
    std::error_code error;
    return fs::is_regular_file(candidate, error);
  };
  if (relative.is_absolute()) return exists(relative) ? std::optional<fs::path>(relative) : std::nullopt;
  std::vector<fs::path> folders;
  if (!angled && !including_file.empty()) folders.push_back(including_file.parent_path());
  folders.insert(folders.end(), include_dirs.begin(), include_dirs.end());
  for (const fs::path& folder : folders) {
    if (searched) searched->push_back(folder);
    if (exists(folder / relative)) return folder / relative;
  }
  return std::nullopt;
}

std::vector<Token> Preprocessor::run(uint32_t main_file) {
  pragmas_.clear();
  files_.clear();
  Impl impl(*this);
  return impl.run(main_file);
}

PredefinedMacros::PredefinedMacros(std::unique_ptr<Table> table) : table_(std::move(table)) {}
PredefinedMacros::~PredefinedMacros() = default;

Result<std::shared_ptr<const PredefinedMacros>> PredefinedMacros::read(const std::vector<MacroDefinition>& definitions) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  Preprocessor reader(sources, diagnostics, {});
  auto table = std::make_unique<Table>();
  {
    Preprocessor::Impl impl(reader);
    impl.define(definitions);
    for (const Diagnostic& diagnostic : diagnostics.diagnostics())
      if (diagnostic.severity == Severity::Error) return fail("predefined macros: " + diagnostic.message);
    impl.export_macros(*table);
  }
  table->text = std::move(reader.text_store_);  // a deque moves without moving its strings
  return std::shared_ptr<const PredefinedMacros>(new PredefinedMacros(std::move(table)));
}

void Preprocessor::Impl::export_macros(PredefinedMacros::Table& table) {
  for (const auto& [name, macro] : macros_)
    if (macro) table.by_name.emplace(name, macro);
  table.macros = std::move(macro_pool_);  // the macros keep their addresses
  table.filter = filter_;
  macros_.clear();
}

void Preprocessor::Impl::define(const std::vector<MacroDefinition>& definitions) {
  for (const MacroDefinition& definition : definitions) {
    // The name may carry a parameter list ("F(x)"); either way it is read as a #define line.
    const std::string& name = definition.name;
    bool valid = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_');
    size_t k = 0;
    while (k < name.size() && (std::isalnum(static_cast<unsigned char>(name[k])) || name[k] == '_')) ++k;
    if (k < name.size() && !(name[k] == '(' && name.back() == ')' && name.find('\n') == std::string::npos))
      valid = false;
    if (!valid) {
      diagnostics_.error({}, "invalid macro name '" + clip(name) + "' in the options");
      continue;
    }
    std::string text = "#define " + name + " " + definition.value;
    for (char& c : text)
      if (c == '\n' || c == '\r') c = ' ';
    const std::string_view stored = store(std::move(text));
    Lexer lexer(stored, 0, diagnostics_, &pp_.text_store_);
    lexer.next();  // #
    lexer.next();  // define
    do_define(lexer, Loc{});
  }
}

bool Preprocessor::Impl::inside_given_folders(const std::filesystem::path& file) const {
  return std::any_of(given_folders_.begin(), given_folders_.end(),
                     [&](const std::filesystem::path& folder) { return path_is_inside(file, folder); });
}

std::vector<Token> Preprocessor::Impl::run(uint32_t main_file) {
  define(pp_.options_.defines);
  Token end = make_token(TokenKind::EndOfFile, {}, {});
  end.at_line_start = true;
  if (main_file == 0 || main_file >= sources_.file_count()) {
    diagnostics_.error({}, "no such source file");
    return {end};
  }
  out_.clear();
  given_folders_ = pp_.options_.include_dirs;
  if (const auto folder = sources_.path(main_file).parent_path(); !folder.empty()) given_folders_.push_back(folder);
  enter_file(main_file);
  out_.reserve(sources_.text(main_file).size() / 3 + 16);
  Context ctx;
  PPTok token;
  for (;;) {
    // The common case first: a token straight from a file that names no macro.
    if (ctx.frames.empty() && !ctx.has_pushback && !ctx.carry_space && !ctx.carry_line_start) {
      IncludeFrame& frame = *includes_.back();
      const Token next = frame.lexer.next();
      if (next.kind == TokenKind::Hash || next.kind == TokenKind::EndOfFile) {
        bool ended;
        if (special_file_token(frame, next, false, ended)) {
          if (ended) break;
          continue;
        }
      }
      note_token(frame);
      if (next.kind != TokenKind::Identifier || !maybe_macro(next.text)) {
        out_.push_back(next);
        continue;
      }
      ctx.pushback = PPTok{next, false, false};
      ctx.has_pushback = true;
    }
    if (!expand_next(ctx, token, false)) break;
    out_.push_back(token.tok);
  }
  unwind(ctx);
  end.loc = end_loc_;
  out_.push_back(end);
  return std::move(out_);
}

// ---------------------------------------------------------------------------------------------
// Expansion

void Preprocessor::Impl::add_macro(Macro macro) {
  if (Macro* old = find(macro.name)) {
    bool same = old->function_like == macro.function_like && old->variadic == macro.variadic &&
                old->params == macro.params && old->body.size() == macro.body.size();
    for (size_t i = 0; same && i < macro.body.size(); ++i) {
      const Token& a = old->body[i].tok;
      const Token& b = macro.body[i].tok;
      same = a.kind == b.kind && a.text == b.text && (i == 0 || a.space_before == b.space_before);
    }
    if (same) return;  // the first definition stays, for the location of later notes
    diagnostics_.warning(macro.loc, "macro '" + clip(macro.name) + "' redefined");
    if (old->loc.file != 0) diagnostics_.note(old->loc, "previous definition is here");
  }
  const size_t bit = filter_bit(macro.name);
  filter_[bit >> 6] |= uint64_t(1) << (bit & 63);
  macro_pool_.push_back(std::move(macro));
  Macro* stored = &macro_pool_.back();
  macros_[stored->name] = stored;
}

void Preprocessor::Impl::warn_self(Macro& macro, Loc loc) {
  if (macro.warned_self) return;
  macro.warned_self = true;
  diagnostics_.warning(loc, "macro '" + clip(macro.name) + "' refers to itself; it is not expanded again");
}

bool Preprocessor::Impl::charge(size_t tokens, Loc loc) {
  if (budget_spent_) return false;
  if (tokens + 1 <= budget_) {
    budget_ -= tokens + 1;
    return true;
  }
  budget_spent_ = true;
  diagnostics_.error(loc, "macro expansion is too large (more than " + std::to_string(kMaxExpandedTokens) +
                              " tokens); macros are no longer expanded");
  return false;
}

void Preprocessor::Impl::pop_frame(Context& ctx) {
  Frame& frame = ctx.frames.back();
  if (frame.macro) frame.macro->disabled = false;
  recycle(std::move(frame.tokens));
  ctx.frames.pop_back();
  --expansion_depth_;
}

void Preprocessor::Impl::unwind(Context& ctx) {
  while (!ctx.frames.empty()) pop_frame(ctx);
  ctx.has_pushback = false;
}

bool Preprocessor::Impl::raw_next(Context& ctx, PPTok& out, bool stop_at_file_end) {
  if (ctx.has_pushback) {
    ctx.has_pushback = false;
    out = ctx.pushback;
    return true;
  }
  while (!ctx.frames.empty()) {
    Frame& frame = ctx.frames.back();
    if (frame.pos < frame.tokens.size()) {
      out = frame.tokens[frame.pos++];
      return true;
    }
    pop_frame(ctx);
  }
  if (ctx.list) {
    if (ctx.list_pos >= ctx.list_end) return false;
    out = (*ctx.list)[ctx.list_pos++];
    return true;
  }
  return next_file_token(out, stop_at_file_end);
}

bool Preprocessor::Impl::expand_next(Context& ctx, PPTok& out, bool stop_at_file_end) {
  for (;;) {
    if (!raw_next(ctx, out, stop_at_file_end)) return false;
    const bool keep = ctx.in_if && defined_operand(ctx, out.tok);
    if (!keep && out.tok.kind == TokenKind::Identifier && !out.no_expand && maybe_macro(out.tok.text) &&
        try_expand(ctx, out))
      continue;
    if (ctx.carry_space || ctx.carry_line_start) {
      out.tok.space_before = out.tok.space_before || ctx.carry_space;
      out.tok.at_line_start = out.tok.at_line_start || ctx.carry_line_start;
      ctx.carry_space = ctx.carry_line_start = false;
    }
    return true;
  }
}

// In a #if line, `defined X` and `defined(X)` that came out of a macro: neither `defined` nor X
// is expanded, as GCC and Clang do.
bool Preprocessor::Impl::defined_operand(Context& ctx, const Token& token) {
  if (token.kind == TokenKind::Identifier) {
    if (ctx.defined_state != 0) {
      ctx.defined_state = 0;
      return true;
    }
    if (token.text == "defined") {
      ctx.defined_state = 1;
      return true;
    }
    return false;
  }
  ctx.defined_state = ctx.defined_state == 1 && is_punct1(token, '(') ? 2 : 0;
  return false;
}

// `token` names a macro (or a builtin) perhaps. Returns true when it was consumed: its expansion
// is now the top frame, or it vanished; false when it stands for itself (possibly painted).
bool Preprocessor::Impl::try_expand(Context& ctx, PPTok& token) {
  const Token name = token.tok;
  Macro* macro = find(name.text);
  if (!macro) {
    if (name.text == "__LINE__") {
      token.tok.kind = TokenKind::IntLiteral;
      token.tok.text = store(std::to_string(name.loc.line));
    } else if (name.text == "__FILE__") {
      std::string text = "\"";
      if (name.loc.file != 0)
        for (char c : sources_.name(name.loc.file)) {
          if (c == '"' || c == '\\') text += '\\';
          text += c;
        }
      text += '"';
      token.tok.kind = TokenKind::StringLiteral;
      token.tok.text = store(std::move(text));
    }
    return false;
  }
  if (macro->disabled) {
    token.no_expand = true;
    warn_self(*macro, name.loc);
    return false;
  }
  if (budget_spent_) return false;
  if (expansion_depth_ >= Preprocessor::kMaxExpansionDepth) {
    if (!depth_reported_) {
      depth_reported_ = true;
      diagnostics_.error(name.loc, "macro expansion nested too deeply (more than " +
                                       std::to_string(Preprocessor::kMaxExpansionDepth) + " levels)");
    }
    token.no_expand = true;
    return false;
  }

  std::vector<PPTok> buffer = take_buffer();
  if (macro->function_like) {
    PPTok next;
    if (!raw_next(ctx, next, true)) {
      recycle(std::move(buffer));
      return false;
    }
    if (!is_punct1(next.tok, '(')) {
      // Not a call: the name stands for itself and the token read ahead comes next.
      ctx.pushback = next;
      ctx.has_pushback = true;
      recycle(std::move(buffer));
      return false;
    }
    Args args;
    if (!collect_args(ctx, *macro, name, args)) {
      recycle(std::move(buffer));
      return true;
    }
    substitute(*macro, name, &args, buffer);
  } else {
    substitute(*macro, name, nullptr, buffer);
  }
  if (!charge(buffer.size(), name.loc)) {
    // Too much work: what was made so far is dropped, the name stays.
    recycle(std::move(buffer));
    return false;
  }
  if (buffer.empty()) {
    ctx.carry_space = ctx.carry_space || name.space_before;
    ctx.carry_line_start = ctx.carry_line_start || name.at_line_start;
    recycle(std::move(buffer));
    return true;
  }
  ctx.frames.push_back(Frame{std::move(buffer), 0, macro});
  macro->disabled = true;
  ++expansion_depth_;
  return true;
}

bool Preprocessor::Impl::collect_args(Context& ctx, const Macro& macro, const Token& name, Args& args) {
  const size_t params = macro.params.size();
  args.starts.push_back(0);
  size_t depth = 0;
  for (;;) {
    PPTok token;
    if (!raw_next(ctx, token, true)) {
      diagnostics_.error(name.loc, "unterminated call of macro '" + clip(macro.name) + "'");
      return false;
    }
    const Token& t = token.tok;
    if (t.kind == TokenKind::Punct && t.text.size() == 1) {
      const char c = t.text[0];
      if (c == '(') {
        ++depth;
      } else if (c == ')') {
        if (depth == 0) break;
        --depth;
      } else if (c == ',' && depth == 0 && !(macro.variadic && args.starts.size() >= params)) {
        args.starts.push_back(args.tokens.size());
        continue;
      }
    } else if (t.kind == TokenKind::Identifier && !token.no_expand) {
      if (Macro* other = find(t.text); other && other->disabled) {
        token.no_expand = true;
        warn_self(*other, t.loc);
      }
    }
    args.tokens.push_back(token);
  }
  args.starts.push_back(args.tokens.size());
  // Arguments read from a list are copies of tokens already made: nested calls would otherwise
  // copy their tokens once per level.
  if (ctx.list && !charge(args.tokens.size(), name.loc)) return false;
  size_t given = args.starts.size() - 1;
  if (params == 0 && given == 1 && args.tokens.empty()) given = 0;
  if (macro.variadic && given + 1 == params) {
    args.starts.push_back(args.tokens.size());  // an empty __VA_ARGS__
    ++given;
  }
  if (given != params) {
    const size_t needed = macro.variadic ? params - 1 : params;
    diagnostics_.error(name.loc, "macro '" + clip(macro.name) + "' takes " + (macro.variadic ? "at least " : "") +
                                     std::to_string(needed) + (needed == 1 ? " argument, " : " arguments, ") +
                                     std::to_string(given) + " given");
    return false;
  }
  return true;
}

void Preprocessor::Impl::expand_list(const std::vector<PPTok>& list, size_t begin, size_t end,
                                     std::vector<PPTok>& out, bool in_if) {
  bool any = false;
  for (size_t i = begin; i < end && !any; ++i) {
    const PPTok& t = list[i];
    any = t.tok.kind == TokenKind::Identifier && !t.no_expand && maybe_macro(t.tok.text);
  }
  const bool too_deep = expansion_depth_ >= Preprocessor::kMaxExpansionDepth;
  if (!any || budget_spent_ || too_deep || argument_nesting_ >= kMaxArgumentNesting) {
    if (any && !budget_spent_ && !depth_reported_) {
      depth_reported_ = true;
      diagnostics_.error(list[begin].tok.loc,
                         too_deep ? "macro expansion nested too deeply (more than " +
                                        std::to_string(Preprocessor::kMaxExpansionDepth) + " levels)"
                                  : "macro calls nested too deeply in arguments (more than " +
                                        std::to_string(kMaxArgumentNesting) + " levels)");
    }
    out.insert(out.end(), list.begin() + std::ptrdiff_t(begin), list.begin() + std::ptrdiff_t(end));
    return;
  }
  Context sub;
  sub.list = &list;
  sub.list_pos = begin;
  sub.list_end = end;
  sub.in_if = in_if;
  ++expansion_depth_;
  ++argument_nesting_;
  PPTok token;
  while (expand_next(sub, token, true)) out.push_back(token);
  unwind(sub);
  --argument_nesting_;
  --expansion_depth_;
}

PPTok Preprocessor::Impl::stringize(const Args& args, int param, Loc loc) {
  const size_t begin = args.starts[size_t(param)];
  const size_t end = args.starts[size_t(param) + 1];
  // Texts can double at each level of nesting (a stringized string escapes its quotes again),
  // so their length is charged too.
  size_t estimate = 2;
  for (size_t i = begin; i < end; ++i) estimate += args.tokens[i].tok.text.size() * 2 + 1;
  PPTok result;
  if (!charge(end - begin + estimate / 8, loc)) {
    result.tok = make_token(TokenKind::StringLiteral, "\"\"", loc);
    return result;
  }
  std::string text = "\"";
  for (size_t i = begin; i < end; ++i) {
    const Token& t = args.tokens[i].tok;
    if (i > begin && (t.space_before || t.at_line_start)) text += ' ';
    if (t.kind == TokenKind::StringLiteral) {
      for (char c : t.text) {
        if (c == '"' || c == '\\') text += '\\';
        text += c;
      }
    } else {
      text += t.text;
    }
  }
  text += '"';
  result.tok = make_token(TokenKind::StringLiteral, store(std::move(text)), loc);
  return result;
}

void Preprocessor::Impl::paste(std::vector<PPTok>& out, const PPTok& rhs, Loc loc) {
  PPTok& lhs = out.back();
  if (rhs.placemarker) return;
  if (lhs.placemarker) {
    const bool space = lhs.tok.space_before;
    lhs = rhs;
    lhs.tok.space_before = space;
    return;
  }
  if (!charge((lhs.tok.text.size() + rhs.tok.text.size()) / 8, loc)) return;
  std::string text;
  text.reserve(lhs.tok.text.size() + rhs.tok.text.size());
  text += lhs.tok.text;
  text += rhs.tok.text;
  // Valid when the text lexes as exactly one token, without complaint.
  DiagnosticEngine quiet(sources_);
  Lexer lexer(text, 0, quiet);
  const Token first = lexer.next();
  const Token second = lexer.next();
  if (quiet.diagnostics().empty() && first.kind != TokenKind::EndOfFile && second.kind == TokenKind::EndOfFile &&
      first.text.size() == text.size()) {
    lhs.tok.kind = first.kind;
    lhs.tok.text = store(std::move(text));
    lhs.tok.loc = loc;
    lhs.no_expand = false;
    return;
  }
  diagnostics_.error(loc, "pasting \"" + clip(lhs.tok.text) + "\" and \"" + clip(rhs.tok.text) +
                              "\" does not give a valid token");
  PPTok second_token = rhs;
  second_token.tok.loc = loc;
  out.push_back(second_token);
}

void Preprocessor::Impl::substitute(const Macro& macro, const Token& name, const Args* args,
                                    std::vector<PPTok>& out) {
  const std::vector<BodyToken>& body = macro.body;
  const size_t n = body.size();
  std::vector<std::vector<PPTok>> expanded;
  std::vector<char> have_expanded;
  bool placemarkers = false;
  auto raw_arg = [&](int param, bool space_before) {
    const size_t begin = args->starts[size_t(param)];
    const size_t end = args->starts[size_t(param) + 1];
    if (begin == end) {
      PPTok mark;
      mark.placemarker = true;
      mark.tok.loc = name.loc;
      mark.tok.space_before = space_before;
      out.push_back(mark);
      placemarkers = true;
      return;
    }
    const size_t first = out.size();
    out.insert(out.end(), args->tokens.begin() + std::ptrdiff_t(begin), args->tokens.begin() + std::ptrdiff_t(end));
    out[first].tok.space_before = space_before;
    out[first].tok.at_line_start = false;
  };
  for (size_t i = 0; i < n; ++i) {
    const BodyToken& b = body[i];
    const bool stringizing =
        macro.function_like && b.tok.kind == TokenKind::Hash && i + 1 < n && body[i + 1].param >= 0;
    if (stringizing) {
      PPTok s = stringize(*args, body[i + 1].param, name.loc);
      s.tok.space_before = b.tok.space_before;
      out.push_back(s);
      ++i;
      continue;
    }
    if (b.tok.kind == TokenKind::HashHash && i + 1 < n && !out.empty()) {
      const BodyToken& r = body[i + 1];
      if (macro.function_like && r.tok.kind == TokenKind::Hash && i + 2 < n && body[i + 2].param >= 0) {
        paste(out, stringize(*args, body[i + 2].param, name.loc), name.loc);
        i += 2;
        continue;
      }
      if (r.param >= 0) {
        const size_t begin = args->starts[size_t(r.param)];
        const size_t end = args->starts[size_t(r.param) + 1];
        if (begin < end) {
          paste(out, args->tokens[begin], name.loc);
          out.insert(out.end(), args->tokens.begin() + std::ptrdiff_t(begin + 1),
                     args->tokens.begin() + std::ptrdiff_t(end));
        }
        ++i;
        continue;
      }
      PPTok rhs;
      rhs.tok = r.tok;
      rhs.tok.loc = name.loc;
      paste(out, rhs, name.loc);
      ++i;
      continue;
    }
    if (b.param >= 0) {
      if (i + 1 < n && body[i + 1].tok.kind == TokenKind::HashHash) {
        raw_arg(b.param, b.tok.space_before);
        continue;
      }
      const size_t p = size_t(b.param);
      if (expanded.empty()) {
        expanded.resize(macro.params.size());
        have_expanded.resize(macro.params.size(), 0);
      }
      if (!have_expanded[p]) {
        have_expanded[p] = 1;
        expand_list(args->tokens, args->starts[p], args->starts[p + 1], expanded[p]);
        if (!charge(expanded[p].size(), name.loc)) expanded[p].clear();
      }
      if (!expanded[p].empty()) {
        const size_t first = out.size();
        out.insert(out.end(), expanded[p].begin(), expanded[p].end());
        out[first].tok.space_before = b.tok.space_before;
        out[first].tok.at_line_start = false;
      }
      continue;
    }
    PPTok copy;
    copy.tok = b.tok;
    copy.tok.loc = name.loc;
    copy.tok.at_line_start = false;
    out.push_back(copy);
  }
  if (placemarkers) {
    size_t kept = 0;
    for (size_t i = 0; i < out.size(); ++i)
      if (!out[i].placemarker) out[kept++] = out[i];
    out.resize(kept);
  }
  if (!out.empty()) {
    out.front().tok.at_line_start = name.at_line_start;
    out.front().tok.space_before = name.space_before;
  }
}

// ---------------------------------------------------------------------------------------------
// Files

void Preprocessor::Impl::enter_file(uint32_t file) {
  ensure_file_tables();
  if (!seen_[file]) {
    seen_[file] = 1;
    pp_.files_.push_back(file);
  }
  includes_.push_back(std::make_unique<IncludeFrame>(sources_.text(file), file, diagnostics_, &pp_.text_store_,
                                                     conds_.size(), out_.size(), pp_.pragmas_.size()));
}

void Preprocessor::Impl::finish_file(IncludeFrame& frame) {
  frame.finished = true;
  for (size_t i = frame.cond_base; i < conds_.size(); ++i)
    diagnostics_.error(conds_[i].loc, "unterminated #" + std::string(conds_[i].directive));
  conds_.resize(frame.cond_base);
  if (frame.guard == Guard::Closed && !frame.guard_macro.empty()) guard_of_[frame.file] = frame.guard_macro;
}

// A '#' or the end of a file: handles a directive or the end and returns true, or returns false
// for a '#' that is an ordinary token. `ended` says that reading must stop here.
bool Preprocessor::Impl::special_file_token(IncludeFrame& frame, const Token& token, bool stop_at_file_end,
                                            bool& ended) {
  ended = false;
  if (token.kind == TokenKind::Hash) {
    if (!token.at_line_start) return false;
    directive(frame);
    return true;
  }
  if (!frame.finished) finish_file(frame);
  if (includes_.size() == 1) {
    end_loc_ = token.loc;
    ended = true;
  } else if (stop_at_file_end) {
    ended = true;
  } else {
    includes_.pop_back();
  }
  return true;
}

bool Preprocessor::Impl::next_file_token(PPTok& out, bool stop_at_file_end) {
  for (;;) {
    IncludeFrame& frame = *includes_.back();
    Token token = frame.lexer.next();
    if (token.kind == TokenKind::Hash || token.kind == TokenKind::EndOfFile) {
      bool ended;
      if (special_file_token(frame, token, stop_at_file_end, ended)) {
        if (ended) return false;
        continue;
      }
    }
    note_token(frame);
    out.tok = token;
    out.no_expand = false;
    out.placemarker = false;
    return true;
  }
}

void Preprocessor::Impl::directive(IncludeFrame& frame) {
  Lexer& lex = frame.lexer;
  if (lex.line_ended()) return;  // a lone '#'
  const Token name = lex.next();
  const bool guard_start = frame.guard == Guard::Start;
  if (frame.guard == Guard::Start || frame.guard == Guard::Closed) frame.guard = Guard::None;
  if (name.kind != TokenKind::Identifier) {
    diagnostics_.error(name.loc, "unknown directive '#" + clip(name.text) + "'");
    skip_line(lex);
    return;
  }
  const std::string_view d = name.text;
  if (d == "define") {
    do_define(lex, name.loc);
  } else if (d == "undef") {
    do_undef(lex, name);
  } else if (d == "include") {
    do_include(frame, name);
  } else if (d == "if" || d == "ifdef" || d == "ifndef") {
    do_if(frame, name, guard_start);
  } else if (d == "elif" || d == "else") {
    if (conds_.size() <= frame.cond_base) {
      diagnostics_.error(name.loc, "#" + std::string(d) + " without #if");
      skip_line(lex);
      return;
    }
    Cond& cond = conds_.back();
    if (cond.seen_else) diagnostics_.error(name.loc, "#" + std::string(d) + " after #else");
    else_seen(frame);
    if (d == "else") {
      cond.seen_else = true;
      extra_tokens(lex, d);
    }
    // The group that was being emitted ends here; the rest of the chain is skipped.
    skip_group(frame, false);
  } else if (d == "endif") {
    if (conds_.size() <= frame.cond_base) {
      diagnostics_.error(name.loc, "#endif without #if");
      skip_line(lex);
      return;
    }
    extra_tokens(lex, d);
    pop_cond(frame);
  } else if (d == "error" || d == "warning") {
    const std::string_view message = lex.rest_of_line();
    std::string text = message.empty() ? "#" + std::string(d) : std::string(message);
    if (d == "error") {
      diagnostics_.error(name.loc, std::move(text));
    } else {
      diagnostics_.warning(name.loc, std::move(text));
    }
  } else if (d == "pragma") {
    do_pragma(frame, name);
  } else if (d == "line") {
    diagnostics_.warning(name.loc, "#line is not supported; the directive is ignored");
    skip_line(lex);
  } else {
    diagnostics_.error(name.loc, "unknown directive '#" + clip(d) + "'");
    skip_line(lex);
  }
}

void Preprocessor::Impl::do_define(Lexer& lex, Loc directive_loc) {
  if (lex.line_ended()) {
    diagnostics_.error(directive_loc, "macro name missing in #define");
    return;
  }
  const Token name = lex.next();
  if (name.kind != TokenKind::Identifier) {
    diagnostics_.error(name.loc, "macro name must be an identifier");
    skip_line(lex);
    return;
  }
  if (name.text == "defined") {
    diagnostics_.error(name.loc, "'defined' cannot be used as a macro name");
    skip_line(lex);
    return;
  }
  Macro macro;
  macro.name = name.text;
  macro.loc = name.loc;
  std::vector<BodyToken>& body = macro.body;
  if (!lex.line_ended()) {
    Token first = lex.next();
    if (is_punct1(first, '(') && !first.space_before) {
      macro.function_like = true;
      // Parameters: (), (a), (a, b), (a, ...), (...)
      bool expect_name = false;  // after a comma
      for (;;) {
        if (lex.line_ended()) {
          diagnostics_.error(first.loc, "missing ')' in macro parameter list");
          return;
        }
        const Token p = lex.next();
        if (is_punct1(p, ')') && !expect_name && macro.params.empty()) break;
        if (is_punct1(p, '.')) {
          bool dots = true;
          for (int k = 0; k < 2 && dots; ++k) dots = !lex.line_ended() && is_punct1(lex.next(), '.');
          if (!dots) {
            diagnostics_.error(p.loc, "expected parameter name in macro parameter list");
            skip_line(lex);
            return;
          }
          macro.variadic = true;
          macro.params.push_back("__VA_ARGS__");
          if (lex.line_ended() || !is_punct1(lex.next(), ')')) {
            diagnostics_.error(p.loc, "'...' must be the last macro parameter");
            skip_line(lex);
            return;
          }
          break;
        }
        if (p.kind != TokenKind::Identifier) {
          diagnostics_.error(p.loc, "expected parameter name in macro parameter list, found '" + clip(p.text) + "'");
          skip_line(lex);
          return;
        }
        if (p.text == "__VA_ARGS__") {
          diagnostics_.error(p.loc, "'__VA_ARGS__' can only name the parameters of a variadic macro");
          skip_line(lex);
          return;
        }
        for (std::string_view existing : macro.params)
          if (existing == p.text) {
            diagnostics_.error(p.loc, "duplicate macro parameter '" + clip(p.text) + "'");
            skip_line(lex);
            return;
          }
        macro.params.push_back(p.text);
        if (lex.line_ended()) {
          diagnostics_.error(first.loc, "missing ')' in macro parameter list");
          return;
        }
        const Token separator = lex.next();
        if (is_punct1(separator, ')')) break;
        if (!is_punct1(separator, ',')) {
          diagnostics_.error(separator.loc, "expected ',' or ')' in macro parameter list");
          skip_line(lex);
          return;
        }
        expect_name = true;
      }
    } else {
      body.push_back(BodyToken{first, -1});
    }
    while (!lex.line_ended()) body.push_back(BodyToken{lex.next(), -1});
  }
  for (size_t i = 0; i < body.size(); ++i) {
    BodyToken& b = body[i];
    if (macro.function_like && b.tok.kind == TokenKind::Identifier)
      for (size_t k = 0; k < macro.params.size(); ++k)
        if (macro.params[k] == b.tok.text) b.param = int(k);
  }
  if (!body.empty()) {
    if (body.front().tok.kind == TokenKind::HashHash || body.back().tok.kind == TokenKind::HashHash) {
      const Loc at = body.front().tok.kind == TokenKind::HashHash ? body.front().tok.loc : body.back().tok.loc;
      diagnostics_.error(at, "'##' cannot appear at either end of a macro expansion");
      return;
    }
    if (macro.function_like)
      for (size_t i = 0; i < body.size(); ++i)
        if (body[i].tok.kind == TokenKind::Hash && (i + 1 >= body.size() || body[i + 1].param < 0)) {
          diagnostics_.error(body[i].tok.loc, "'#' is not followed by a macro parameter");
          return;
        }
  }
  add_macro(std::move(macro));
}

void Preprocessor::Impl::do_undef(Lexer& lex, const Token& directive_name) {
  if (lex.line_ended()) {
    diagnostics_.error(directive_name.loc, "macro name missing in #undef");
    return;
  }
  const Token name = lex.next();
  if (name.kind != TokenKind::Identifier) {
    diagnostics_.error(name.loc, "macro name must be an identifier");
    skip_line(lex);
    return;
  }
  if (predefined_ && predefined_->by_name.count(name.text)) {
    macros_[name.text] = nullptr;  // hides the predefined macro from find()
  } else {
    macros_.erase(name.text);
  }
  extra_tokens(lex, "undef");
}

void Preprocessor::Impl::do_include(IncludeFrame& frame, const Token& name) {
  Lexer& lex = frame.lexer;
  if (lex.line_ended()) {
    diagnostics_.error(name.loc, "expected \"file\" or <file> after #include");
    return;
  }
  const Token file = lex.next_header_name();
  std::string_view spelled;
  bool angled = false;
  if (file.kind == TokenKind::StringLiteral || file.kind == TokenKind::AngledHeader) {
    const char close = file.kind == TokenKind::StringLiteral ? '"' : '>';
    if (file.text.size() < 2 || file.text.back() != close) {  // unterminated: already reported
      skip_line(lex);
      return;
    }
    spelled = file.text.substr(1, file.text.size() - 2);
    angled = file.kind == TokenKind::AngledHeader;
    extra_tokens(lex, "include");
  } else {
    // #include MACRO: the line is expanded and must give "file" or <file>.
    expr_in_.clear();
    PPTok first;
    first.tok = file;
    expr_in_.push_back(first);
    while (!lex.line_ended()) {
      PPTok t;
      t.tok = lex.next();
      expr_in_.push_back(t);
    }
    std::vector<PPTok> expanded;
    expand_list(expr_in_, 0, expr_in_.size(), expanded);
    bool ok = false;
    if (!expanded.empty() && expanded[0].tok.kind == TokenKind::StringLiteral && expanded[0].tok.text.size() >= 2 &&
        expanded[0].tok.text.back() == '"') {
      spelled = expanded[0].tok.text.substr(1, expanded[0].tok.text.size() - 2);
      ok = true;
    } else if (!expanded.empty() && is_punct1(expanded[0].tok, '<')) {
      std::string text;
      for (size_t i = 1; i < expanded.size(); ++i) {
        const Token& t = expanded[i].tok;
        if (is_punct1(t, '>')) {
          spelled = store(std::move(text));
          angled = true;
          ok = true;
          break;
        }
        if (i > 1 && t.space_before) text += ' ';
        text += t.text;
      }
    }
    if (!ok) {
      diagnostics_.error(file.loc, "expected \"file\" or <file> after #include");
      return;
    }
  }
  if (spelled.empty()) {
    diagnostics_.error(file.loc, "empty file name in #include");
    return;
  }
  include_file(frame, name, spelled, angled, file.loc);
}

void Preprocessor::Impl::include_file(IncludeFrame& frame, const Token& name, std::string_view spelled, bool angled,
                                      Loc where) {
  namespace fs = std::filesystem;
  if (includes_.size() >= Preprocessor::kMaxIncludeDepth) {
    diagnostics_.error(name.loc, "#include nested too deeply (more than " +
                                     std::to_string(Preprocessor::kMaxIncludeDepth) + " levels)");
    return;
  }
  const fs::path relative{std::string(spelled)};
  std::vector<fs::path> searched;
  const std::optional<fs::path> found =
      find_include(spelled, sources_.path(frame.file), angled, pp_.options_.include_dirs, &searched);
  if (!found) {
    std::string message = "cannot find include file '" + clip(spelled) + "'";
    if (relative.is_absolute()) {
      // Nothing was searched: the path was taken as it is.
    } else if (searched.empty()) {
      message += " (no directories to search)";
    } else {
      message += " (searched: ";
      for (size_t i = 0; i < searched.size(); ++i) {
        if (i) message += ", ";
        message += searched[i].string();
      }
      message += ")";
    }
    diagnostics_.error(where, std::move(message));
    return;
  }
  if (!inside_given_folders(*found)) {
    std::string folders;
    for (const fs::path& folder : given_folders_) folders += (folders.empty() ? "" : ", ") + folder.string();
    diagnostics_.error(where, "include file '" + clip(spelled) + "' is outside the folders this shader was given (" +
                                  folders + "); an include may not leave them");
    return;
  }
  Result<uint32_t> loaded = sources_.load(*found);
  if (!loaded) {
    diagnostics_.error(where, loaded.error().message);
    return;
  }
  const uint32_t index = *loaded;
  ensure_file_tables();
  if (!seen_[index]) {
    seen_[index] = 1;
    pp_.files_.push_back(index);
  }
  if (once_[index]) return;
  if (!guard_of_[index].empty() && is_defined(guard_of_[index])) return;
  size_t last = includes_.size();
  size_t occurrences = 0;
  for (size_t i = 0; i < includes_.size(); ++i)
    if (includes_[i]->file == index) {
      ++occurrences;
      last = i;
    }
  if (occurrences >= 2) {
    std::string chain;
    for (size_t i = last; i < includes_.size(); ++i) chain += short_name(includes_[i]->file) + " -> ";
    chain += short_name(index) + " -> ...";
    diagnostics_.error(name.loc, "#include cycle: " + chain);
    abandon_files_from(last);
    return;
  }
  enter_file(index);
}

// The files from includes_[first] up were read a second time only to reach a cycle: what they
// made is dropped, or each declaration in them would come twice and be reported as a
// redefinition of itself. Reading goes on in the file that included includes_[first].
void Preprocessor::Impl::abandon_files_from(size_t first) {
  const IncludeFrame& repeated = *includes_[first];
  out_.resize(std::min(out_.size(), repeated.output_mark));
  pp_.pragmas_.resize(std::min(pp_.pragmas_.size(), repeated.pragma_mark));
  conds_.resize(std::min(conds_.size(), repeated.cond_base));
  // The directive being handled still refers to the innermost frame, so frames are kept alive
  // until the run ends.
  for (size_t i = first; i < includes_.size(); ++i) abandoned_.push_back(std::move(includes_[i]));
  includes_.resize(first);
}

void Preprocessor::Impl::do_if(IncludeFrame& frame, const Token& name, bool guard_start) {
  Lexer& lex = frame.lexer;
  const std::string_view d = name.text;
  if (conds_.size() >= Preprocessor::kMaxConditionalDepth) {
    diagnostics_.error(name.loc, "#" + std::string(d) + " nested too deeply (more than " +
                                     std::to_string(Preprocessor::kMaxConditionalDepth) + " levels)");
    skip_group(frame, true);
    return;
  }
  bool value = false;
  std::string_view guard_name;
  if (d == "if") {
    value = eval_line(lex, name);
  } else if (lex.line_ended()) {
    diagnostics_.error(name.loc, "macro name missing in #" + std::string(d));
  } else {
    const Token macro = lex.next();
    if (macro.kind != TokenKind::Identifier) {
      diagnostics_.error(macro.loc, "macro name must be an identifier");
      skip_line(lex);
    } else {
      value = is_defined(macro.text) == (d == "ifdef");
      guard_name = macro.text;
      extra_tokens(lex, d);
    }
  }
  conds_.push_back(Cond{name.loc, d, value, false});
  if (guard_start && d == "ifndef" && !guard_name.empty()) {
    frame.guard = Guard::Inside;
    frame.guard_cond = conds_.size() - 1;
    frame.guard_macro = guard_name;
  }
  if (!value) skip_group(frame, false);
}

void Preprocessor::Impl::pop_cond(IncludeFrame& frame) {
  conds_.pop_back();
  if (frame.guard == Guard::Inside && conds_.size() == frame.guard_cond) frame.guard = Guard::Closed;
}

void Preprocessor::Impl::else_seen(IncludeFrame& frame) {
  if (frame.guard == Guard::Inside && conds_.size() == frame.guard_cond + 1) frame.guard = Guard::None;
}

// Skips a group that is not emitted. Nested conditionals are only counted. With
// `to_endif_only`, skips to the #endif that matches a conditional that was never pushed;
// otherwise #elif/#else of the innermost open conditional may start an emitted group.
void Preprocessor::Impl::skip_group(IncludeFrame& frame, bool to_endif_only) {
  Lexer& lex = frame.lexer;
  size_t depth = 0;
  for (;;) {
    const Token hash = lex.skip_to_directive();
    if (hash.kind == TokenKind::EndOfFile) return;
    if (lex.line_ended()) continue;
    const Token name = lex.next();
    if (name.kind != TokenKind::Identifier) continue;
    const std::string_view d = name.text;
    if (d == "if" || d == "ifdef" || d == "ifndef") {
      ++depth;
      continue;
    }
    if (d == "endif") {
      if (depth > 0) {
        --depth;
        continue;
      }
      extra_tokens(lex, d);
      if (!to_endif_only) pop_cond(frame);
      return;
    }
    if (depth > 0 || to_endif_only || (d != "else" && d != "elif")) continue;
    Cond& cond = conds_.back();
    if (cond.seen_else) diagnostics_.error(name.loc, "#" + std::string(d) + " after #else");
    else_seen(frame);
    if (d == "else") {
      cond.seen_else = true;
      if (!cond.taken) {
        cond.taken = true;
        extra_tokens(lex, d);
        return;
      }
    } else if (!cond.taken && eval_line(lex, name)) {
      cond.taken = true;
      return;
    }
  }
}

bool Preprocessor::Impl::eval_line(Lexer& lex, const Token& name) {
  line_.clear();
  while (!lex.line_ended()) line_.push_back(lex.next());
  if (line_.empty()) {
    diagnostics_.error(name.loc, "#" + std::string(name.text) + " with no expression");
    return false;
  }
  // `defined X` and `defined(X)` are answered before expansion, so that X is not expanded.
  static constexpr std::string_view kOne = "1";
  static constexpr std::string_view kZero = "0";
  expr_in_.clear();
  for (size_t i = 0; i < line_.size(); ++i) {
    PPTok token;
    token.tok = line_[i];
    if (token.tok.is_identifier("defined")) {
      size_t k = i + 1;
      const bool paren = k < line_.size() && is_punct1(line_[k], '(');
      if (paren) ++k;
      if (k >= line_.size() || line_[k].kind != TokenKind::Identifier) {
        diagnostics_.error(k < line_.size() ? line_[k].loc : token.tok.loc, "macro name missing after 'defined'");
        return false;
      }
      const bool defined = is_defined(line_[k].text);
      if (paren) {
        if (k + 1 >= line_.size() || !is_punct1(line_[k + 1], ')')) {
          diagnostics_.error(token.tok.loc, "missing ')' after 'defined'");
          return false;
        }
        ++k;
      }
      token.tok.kind = TokenKind::IntLiteral;
      token.tok.text = defined ? kOne : kZero;
      i = k;
    }
    expr_in_.push_back(token);
  }
  std::vector<PPTok> expanded;
  expand_list(expr_in_, 0, expr_in_.size(), expanded, true);
  ExprParser parser(*this, diagnostics_, expanded, line_.back().loc);
  return parser.evaluate();
}

void Preprocessor::Impl::do_pragma(IncludeFrame& frame, const Token& name) {
  Lexer& lex = frame.lexer;
  if (lex.line_ended()) {
    diagnostics_.warning(name.loc, "empty #pragma");
    return;
  }
  const Token first = lex.next();
  if (first.is_identifier("once")) {
    once_[frame.file] = 1;
    extra_tokens(lex, "pragma once");
    return;
  }
  Pragma pragma;
  pragma.name = first.text;
  pragma.loc = first.loc;
  while (!lex.line_ended()) pragma.args.push_back(lex.next());
  pp_.pragmas_.push_back(std::move(pragma));
}

}  // namespace xshade::hlsl
