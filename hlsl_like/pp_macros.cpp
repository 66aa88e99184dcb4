// Macros: #define and #undef, the definitions from the options and the predefined table, and
// expansion with its stringizing (#), pasting (##) and the builtins __FILE__ and __LINE__.
//
// How expansion works: the clang scheme of a stack of token buffers ("frames"), one per macro
// expansion being read. While a macro's frame is on the stack the macro is disabled; an identifier
// that names a disabled macro when it is read is painted (`no_expand`) and never expanded again,
// which is what C's hide sets amount to. Frames are popped only when a read goes past their end,
// so the last token of an expansion is still read with its macro disabled. Arguments are
// pre-expanded in a nested context whose base is the argument's token list; that nesting is the
// only recursion, and it is bounded by kMaxExpansionDepth together with the frames.
#include <cctype>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {
namespace {

// Macro calls nested in the arguments of macro calls: each level is one recursion of argument
// pre-expansion (about 1 KiB of stack, several under AddressSanitizer), so this stays well below
// kMaxExpansionDepth.
constexpr size_t kMaxArgumentNesting = 64;

}  // namespace

using pp_detail::BodyToken;
using pp_detail::clip;
using pp_detail::Frame;
using pp_detail::is_punct1;
using pp_detail::kMaxExpandedTokens;
using pp_detail::make_token;
using pp_detail::PPTok;

// ---------------------------------------------------------------------------------------------
// Definitions

PredefinedMacros::PredefinedMacros(std::unique_ptr<Table> table) : table_(std::move(table)) {}
PredefinedMacros::~PredefinedMacros() = default;

Result<std::shared_ptr<const PredefinedMacros>> PredefinedMacros::read(
    const std::vector<MacroDefinition>& definitions) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  Preprocessor reader(sources, diagnostics, {});
  auto table = std::make_unique<Table>();
  {
    Preprocessor::Impl impl(reader);
    impl.define(definitions);
    for (const Diagnostic& diagnostic : diagnostics.diagnostics())
      if (diagnostic.severity == Severity::Error)
        return fail(ErrorKind::Internal, "predefined macros: " + diagnostic.message);
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
    pp_.redefined_predefined_.emplace(name.text);
    macros_[name.text] = nullptr;  // hides the predefined macro from find()
  } else {
    macros_.erase(name.text);
  }
  extra_tokens(lex, "undef");
}

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
    // The predefined table (the prelude) stands in for what Unity's include files define; a
    // source that includes those files redefines its macros as they please, silently.
    if (old->predefined) pp_.redefined_predefined_.emplace(macro.name);
    if (!old->predefined) {
      diagnostics_.warning(macro.loc, "macro '" + clip(macro.name) + "' redefined");
      if (old->loc.file != 0) diagnostics_.note(old->loc, "previous definition is here");
    }
  }
  const size_t bit = filter_bit(macro.name);
  filter_[bit >> 6] |= uint64_t(1) << (bit & 63);
  macro_pool_.push_back(std::move(macro));
  Macro* stored = &macro_pool_.back();
  macros_[stored->name] = stored;
}

// ---------------------------------------------------------------------------------------------
// Expansion

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

void Preprocessor::Impl::expand_list(const std::vector<PPTok>& list, size_t begin, size_t end, std::vector<PPTok>& out,
                                     bool in_if) {
  bool any = false;
  for (size_t i = begin; i < end && !any; ++i) {
    const PPTok& t = list[i];
    any = t.tok.kind == TokenKind::Identifier && !t.no_expand && maybe_macro(t.tok.text);
  }
  const bool too_deep = expansion_depth_ >= Preprocessor::kMaxExpansionDepth;
  if (!any || budget_spent_ || too_deep || argument_nesting_ >= kMaxArgumentNesting) {
    if (any && !budget_spent_ && !depth_reported_) {
      depth_reported_ = true;
      diagnostics_.error(list[begin].tok.loc, too_deep
                                                  ? "macro expansion nested too deeply (more than " +
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
  diagnostics_.error(
      loc, "pasting \"" + clip(lhs.tok.text) + "\" and \"" + clip(rhs.tok.text) + "\" does not give a valid token");
  PPTok second_token = rhs;
  second_token.tok.loc = loc;
  out.push_back(second_token);
}

void Preprocessor::Impl::substitute(const Macro& macro, const Token& name, const Args* args, std::vector<PPTok>& out) {
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

}  // namespace xshade::hlsl
