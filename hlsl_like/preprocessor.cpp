// The preprocessor's public entry and its token loop: tokens come from the files (with each
// directive handed to its subsystem here) and, where they name a macro, through expansion.
// preprocessor_internal.h lists which file holds which subsystem.
#include "hlsl_like/preprocessor.h"

#include <string>
#include <utility>
#include <vector>

#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {

using pp_detail::clip;
using pp_detail::make_token;

Preprocessor::Preprocessor(SourceManager& sources, DiagnosticEngine& diagnostics, PreprocessorOptions options)
    : sources_(sources), diagnostics_(diagnostics), options_(std::move(options)) {}

std::vector<Token> Preprocessor::run(uint32_t main_file) {
  pragmas_.clear();
  files_.clear();
  redefined_predefined_.clear();
  Impl impl(*this);
  return impl.run(main_file);
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
  if (const auto folder = sources_.path(main_file).parent_path(); !folder.empty()) {
    given_folders_.push_back(folder);
    main_folder_resolved_ = sources_.path_resolved_on_load(main_file);
  }
  enter_file(main_file);
  path_resolved_[main_file] = sources_.path_resolved_on_load(main_file);
  Context ctx;
  PPTok token;
  bool ended = false;
  while (!ended) {
    // The common case first, in a loop of its own: tokens straight from a file that name no macro.
    if (ctx.frames.empty() && !ctx.has_pushback && !ctx.carry_space && !ctx.carry_line_start) {
      for (;;) {
        IncludeFrame& frame = *includes_.back();
        const Token next = frame.lexer.next();
        if (next.kind == TokenKind::Hash || next.kind == TokenKind::EndOfFile) {
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
        break;
      }
      if (ended) break;
    }
    if (!expand_next(ctx, token, false)) break;
    out_.push_back(token.tok);
  }
  unwind(ctx);
  end.loc = end_loc_;
  out_.push_back(end);
  return std::move(out_);
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
  // A directive is content for the include guard as any token is: only a first #ifndef may
  // start the guard, which do_if sets up again from `guard_start`.
  const bool guard_start = frame.guard == Guard::Start;
  note_token(frame);
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
  } else if (d == "include" || d == "include_with_pragmas") {
    do_include(frame, name);
  } else if (d == "if" || d == "ifdef" || d == "ifndef") {
    do_if(frame, name, guard_start);
  } else if (d == "elif" || d == "else") {
    do_else(frame, name);
  } else if (d == "endif") {
    do_endif(frame, name);
  } else if (d == "error" || d == "warning") {
    do_message(lex, name);
  } else if (d == "pragma") {
    do_pragma(frame, name);
  } else if (d == "line") {
    do_line(lex, name);
  } else {
    diagnostics_.error(name.loc, "unknown directive '#" + clip(d) + "'");
    skip_line(lex);
  }
}

}  // namespace xshade::hlsl
