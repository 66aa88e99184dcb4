// The conditional stack (#if, #ifdef, #ifndef, #elif, #else, #endif and the skipping of groups
// not emitted) and the directives that only report or record: #pragma, #line, #error, #warning.
#include <string>
#include <string_view>
#include <utility>

#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {

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

void Preprocessor::Impl::do_else(IncludeFrame& frame, const Token& name) {
  Lexer& lex = frame.lexer;
  const std::string_view d = name.text;
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
}

void Preprocessor::Impl::do_endif(IncludeFrame& frame, const Token& name) {
  Lexer& lex = frame.lexer;
  if (conds_.size() <= frame.cond_base) {
    diagnostics_.error(name.loc, "#endif without #if");
    skip_line(lex);
    return;
  }
  extra_tokens(lex, name.text);
  pop_cond(frame);
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
  pragma.in_program = frame.in_program;
  while (!lex.line_ended()) pragma.args.push_back(lex.next());
  pp_.pragmas_.push_back(std::move(pragma));
}

void Preprocessor::Impl::do_message(Lexer& lex, const Token& name) {
  const std::string_view d = name.text;
  const std::string_view message = lex.rest_of_line();
  std::string text = message.empty() ? "#" + std::string(d) : std::string(message);
  if (d == "error") {
    diagnostics_.error(name.loc, std::move(text));
  } else {
    diagnostics_.warning(name.loc, std::move(text));
  }
}

// #line N ["name"]: the line after it is line N (of "name"), as C's preprocessor and DXC count
// them; messages from there on say so (SourceManager::resolve).
void Preprocessor::Impl::do_line(Lexer& lex, const Token& name) {
  const Token number = lex.line_ended() ? name : lex.next();
  uint32_t line = 0;
  bool digits = number.kind == TokenKind::IntLiteral && !number.text.empty();
  for (char c : number.text) {
    digits = digits && c >= '0' && c <= '9' && line <= 214748364u;
    if (digits) line = line * 10 + uint32_t(c - '0');
  }
  if (!digits || line == 0 || line > 2147483647u) {
    diagnostics_.error(number.loc,
                       "#line takes a line number from 1 to 2147483647 in decimal digits, then optionally "
                       "a file name in quotes");
    skip_line(lex);
    return;
  }
  std::string file_name;
  if (!lex.line_ended()) {
    const Token spelled = lex.next();
    if (spelled.kind != TokenKind::StringLiteral || spelled.text.size() < 2) {
      diagnostics_.error(spelled.loc, "#line's file name is a string in quotes");
      skip_line(lex);
      return;
    }
    file_name = std::string(spelled.text.substr(1, spelled.text.size() - 2));
  }
  extra_tokens(lex, "line");
  sources_.add_line_mapping(name.loc.file, name.loc.line + 1, line, std::move(file_name));
}

}  // namespace xshade::hlsl
