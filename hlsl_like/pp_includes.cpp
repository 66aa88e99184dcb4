// #include: where a name resolves (the including file's folder, then the include directories),
// the folders an include may not leave, the stack of files being read with its limits (depth and
// cycles), #pragma once and include guards remembered per file.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <sys/stat.h>

#include "base/paths.h"
#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {

using pp_detail::clip;
using pp_detail::find_include_path;
using pp_detail::is_punct1;

namespace {

// Whether `path` names a regular file (through links), as std::filesystem::is_regular_file, from
// a string: an #include looks in a folder or two for every name, and a path object parses itself
// into components, each of them allocated.
bool is_regular_file(const std::string& path) {
  struct stat status {};
  return ::stat(path.c_str(), &status) == 0 && S_ISREG(status.st_mode);
}

// `folder / name` as std::filesystem::path spells it on POSIX: a separator unless the folder is
// empty or ends in one.
void join(std::string_view folder, std::string_view name, std::string& out) {
  out.assign(folder);
  if (!folder.empty() && folder.back() != '/') out += '/';
  out += name;
}

}  // namespace

bool pp_detail::find_include_path(std::string_view name, const std::string* including_folder,
                                  const std::vector<std::filesystem::path>& include_dirs, std::string& found,
                                  std::vector<std::filesystem::path>* searched, size_t* include_dir) {
  if (include_dir) *include_dir = include_dirs.size();
  // Shaders written on Windows may spell "sub\\file.hlsl".
  std::string portable(name);
  for (char& c : portable)
    if (c == '\\') c = '/';
  if (!portable.empty() && portable.front() == '/') {
    found = std::move(portable);
    return is_regular_file(found);
  }
  if (including_folder) {
    if (searched) searched->emplace_back(*including_folder);
    join(*including_folder, portable, found);
    if (is_regular_file(found)) return true;
  }
  for (size_t i = 0; i < include_dirs.size(); ++i) {
    if (searched) searched->push_back(include_dirs[i]);
    join(include_dirs[i].native(), portable, found);
    if (is_regular_file(found)) {
      if (include_dir) *include_dir = i;
      return true;
    }
  }
  return false;
}

std::optional<std::filesystem::path> find_include(std::string_view name, const std::filesystem::path& including_file,
                                                  bool angled, const std::vector<std::filesystem::path>& include_dirs,
                                                  std::vector<std::filesystem::path>* searched) {
  const bool local = !angled && !including_file.empty();
  const std::string folder = local ? including_file.parent_path().native() : std::string();
  std::string found;
  if (!find_include_path(name, local ? &folder : nullptr, include_dirs, found, searched, nullptr)) return std::nullopt;
  return std::filesystem::path(std::move(found));
}

void Preprocessor::Impl::resolve_given_folders() {
  if (folders_resolved_) return;
  folders_resolved_ = true;
  resolved_folders_.reserve(given_folders_.size());
  for (const std::filesystem::path& folder : given_folders_) resolved_folders_.push_back(resolved_path(folder));
}

std::optional<std::filesystem::path> Preprocessor::Impl::resolved_under(size_t folder, std::string_view relative) {
  resolve_given_folders();
  if (folder >= resolved_folders_.size() || !resolved_folders_[folder]) return std::nullopt;
  std::string path = resolved_folders_[folder]->native();
  while (!relative.empty()) {
    const size_t slash = relative.find('/');
    const std::string_view name = relative.substr(0, slash);
    if (name.empty() || name == "." || name == "..") return std::nullopt;
    if (path.empty() || path.back() != '/') path += '/';
    path += name;
    struct stat status {};
    if (::lstat(path.c_str(), &status) != 0 || S_ISLNK(status.st_mode)) return std::nullopt;
    relative = slash == std::string_view::npos ? std::string_view() : relative.substr(slash + 1);
  }
  return std::filesystem::path(std::move(path));
}

bool Preprocessor::Impl::inside_given_folders(const std::filesystem::path& resolved_file) {
  resolve_given_folders();
  return std::any_of(resolved_folders_.begin(), resolved_folders_.end(),
                     [&](const std::optional<std::filesystem::path>& folder) {
                       return folder && resolved_path_is_inside(resolved_file, *folder);
                     });
}

void Preprocessor::Impl::enter_file(uint32_t file) {
  ensure_file_tables();
  // Room for the file's tokens ahead, from its size (shaders as written have a token for every
  // six to ten characters; three leaves room for dense code), so that the output is not moved
  // again as each included file is read.
  const size_t expected = out_.size() + sources_.text(file).size() / 3 + 16;
  if (out_.capacity() < expected) out_.reserve(std::max(expected, out_.capacity() * 2));
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
  if (!frame.folder_known) {
    frame.folder_known = true;
    if (!sources_.path(frame.file).empty()) frame.folder = sources_.path(frame.file).parent_path().native();
  }
  const bool local = !angled && !sources_.path(frame.file).empty();
  std::string& found = found_include_;
  size_t include_dir = 0;
  if (!find_include_path(spelled, local ? &frame.folder : nullptr, pp_.options_.include_dirs, found, nullptr,
                         &include_dir)) {
    std::vector<fs::path> searched;
    find_include_path(spelled, local ? &frame.folder : nullptr, pp_.options_.include_dirs, found, &searched, nullptr);
    std::string message = "cannot find include file '" + clip(spelled) + "'";
    if (fs::path(std::string(spelled)).is_absolute()) {
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
  uint32_t index = 0;
  for (const auto& [path, file] : loaded_includes_)
    if (path == found) {
      index = file;
      break;
    }
  if (index == 0) {
    // A file found in an include directory is resolved from the directory's resolved path when
    // no name after it is a link (or . or ..): a check of each of those names, where resolving
    // the whole path reads every component of it as a link. Anything else is resolved whole.
    std::optional<fs::path> resolved;
    if (include_dir < pp_.options_.include_dirs.size())
      resolved = resolved_under(include_dir, std::string_view(found).substr(found.size() - spelled.size()));
    if (!resolved) resolved = resolved_path(found);
    if (!resolved || !inside_given_folders(*resolved)) {
      std::string folders;
      for (const fs::path& folder : given_folders_) folders += (folders.empty() ? "" : ", ") + folder.string();
      diagnostics_.error(where, "include file '" + clip(spelled) + "' is outside the folders this shader was given (" +
                                    folders + "); an include may not leave them");
      return;
    }
    Result<uint32_t> loaded = sources_.load_canonical(*resolved, found);
    if (!loaded) {
      diagnostics_.error(where, loaded.error().message);
      return;
    }
    index = *loaded;
    loaded_includes_.emplace_back(found, index);
  }
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

}  // namespace xshade::hlsl
