// #include: where a name resolves (the including file's folder, then the include directories),
// the folders an include may not leave, the stack of files being read with its limits (depth and
// cycles), #pragma once and include guards remembered per file.
#include <algorithm>
#include <cerrno>
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

// What looking a name up below a folder's resolved path told.
enum class BelowFolder { Missing, Found, Unsure };

// `relative` (/-separated) below `resolved_folder`, the resolved path of a folder that exists, an
// lstat a name. When every name is a plain one (not empty, `.` or `..`) and none is a link, the
// folder's path with the names after it is the file's resolved path (left in `path`, its size in
// `size`), and whether the file is a regular one is what a stat of the path as spelled would
// tell: Found or Missing. Anything else is Unsure, for that stat and a resolution of the whole
// path to decide. `plain_folders`: the folders this compile found no link, not asked again.
BelowFolder look_below(std::string_view resolved_folder, std::string_view relative, std::string& path, size_t& size,
                       std::vector<std::string>& plain_folders) {
  path.assign(resolved_folder);
  for (;;) {
    const size_t slash = relative.find('/');
    const std::string_view name = relative.substr(0, slash);
    if (name.empty() || name == "." || name == "..") return BelowFolder::Unsure;
    if (path.empty() || path.back() != '/') path += '/';
    path += name;
    const bool last = slash == std::string_view::npos;
    if (!last && std::find(plain_folders.begin(), plain_folders.end(), path) != plain_folders.end()) {
      relative = relative.substr(slash + 1);
      continue;
    }
    struct stat status {};
    if (::lstat(path.c_str(), &status) != 0)
      return errno == ENOENT || errno == ENOTDIR ? BelowFolder::Missing : BelowFolder::Unsure;
    if (S_ISLNK(status.st_mode)) return BelowFolder::Unsure;
    if (last) {
      size = size_t(status.st_size);
      return S_ISREG(status.st_mode) ? BelowFolder::Found : BelowFolder::Missing;
    }
    if (S_ISDIR(status.st_mode)) plain_folders.push_back(path);
    relative = relative.substr(slash + 1);
  }
}

}  // namespace

bool pp_detail::find_include_path(std::string_view name, const std::string* including_folder,
                                  const std::vector<std::filesystem::path>& include_dirs, std::string& found,
                                  std::vector<std::filesystem::path>* searched) {
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
    if (is_regular_file(found)) return true;
  }
  return false;
}

std::optional<std::filesystem::path> find_include(std::string_view name, const std::filesystem::path& including_file,
                                                  bool angled, const std::vector<std::filesystem::path>& include_dirs,
                                                  std::vector<std::filesystem::path>* searched) {
  const bool local = !angled && !including_file.empty();
  const std::string folder = local ? including_file.parent_path().native() : std::string();
  std::string found;
  if (!find_include_path(name, local ? &folder : nullptr, include_dirs, found, searched)) return std::nullopt;
  return std::filesystem::path(std::move(found));
}

void Preprocessor::Impl::resolve_given_folders() {
  if (folders_resolved_) return;
  folders_resolved_ = true;
  resolved_folders_.reserve(given_folders_.size());
  for (size_t i = 0; i < given_folders_.size(); ++i) {
    const std::filesystem::path& folder = given_folders_[i];
    ResolvedFolder& resolved = resolved_folders_.emplace_back();
    if (main_folder_resolved_ && i + 1 == given_folders_.size()) {
      resolved.path = folder;
      resolved.exists = true;
      continue;
    }
    resolved.path = existing_resolved_path(folder);
    resolved.exists = resolved.path.has_value();
    if (!resolved.exists) resolved.path = resolved_path(folder);
  }
}

bool Preprocessor::Impl::inside_given_folders(const std::filesystem::path& resolved_file) {
  resolve_given_folders();
  return std::any_of(resolved_folders_.begin(), resolved_folders_.end(), [&](const ResolvedFolder& folder) {
    return folder.path && resolved_path_is_inside(resolved_file, *folder.path);
  });
}

bool Preprocessor::Impl::locate_include(const IncludeFrame& frame, bool local, std::string_view spelled,
                                        IncludeTarget& target) {
  // Shaders written on Windows may spell "sub\\file.hlsl".
  std::string& portable = portable_name_;
  portable.assign(spelled);
  std::replace(portable.begin(), portable.end(), '\\', '/');
  std::string& found = target.found;
  const auto loaded = [&] {
    for (const auto& [path, file] : loaded_includes_)
      if (path == found) {
        target.file = file;
        return true;
      }
    return false;
  };
  if (!portable.empty() && portable.front() == '/') {
    found = portable;
    return loaded() || is_regular_file(found);
  }
  resolve_given_folders();
  std::string& below = resolved_include_;
  const auto look_in = [&](std::string_view folder, const std::string* resolved_folder) {
    join(folder, portable, found);
    if (loaded()) return true;
    if (resolved_folder) {
      size_t size = 0;
      switch (look_below(*resolved_folder, portable, below, size, plain_folders_)) {
        case BelowFolder::Found:
          target.resolved = std::filesystem::path(below);
          target.size = size;
          return true;
        case BelowFolder::Missing: return false;
        case BelowFolder::Unsure: break;
      }
    }
    return is_regular_file(found);
  };
  // The order of find_include_path: the including file's folder, then the include directories.
  if (local && look_in(frame.folder, path_resolved_[frame.file] ? &frame.folder : nullptr)) return true;
  const std::vector<std::filesystem::path>& include_dirs = pp_.options_.include_dirs;
  for (size_t i = 0; i < include_dirs.size(); ++i) {
    const ResolvedFolder& folder = resolved_folders_[i];
    if (look_in(include_dirs[i].native(), folder.exists ? &folder.path->native() : nullptr)) return true;
  }
  return false;
}

uint32_t Preprocessor::Impl::load_include(IncludeFrame& frame, bool local, std::string_view spelled, Loc where) {
  namespace fs = std::filesystem;
  IncludeTarget target{found_include_, 0, std::nullopt, std::nullopt};
  if (!locate_include(frame, local, spelled, target)) {
    std::vector<fs::path> searched;
    find_include_path(spelled, local ? &frame.folder : nullptr, pp_.options_.include_dirs, found_include_, &searched);
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
    return 0;
  }
  if (target.file != 0) return target.file;
  const std::string& found = target.found;
  // The search found a regular file there: it is resolved whole, without asking first whether it
  // exists. Should it have gone since, it is resolved as far as it exists, and does not open.
  std::optional<fs::path> resolved = std::move(target.resolved);
  if (!resolved) resolved = existing_resolved_path(found);
  const bool resolved_whole = resolved.has_value();
  if (!resolved) resolved = resolved_path(found);
  if (!resolved || !inside_given_folders(*resolved)) {
    std::string folders;
    for (const fs::path& folder : given_folders_) folders += (folders.empty() ? "" : ", ") + folder.string();
    diagnostics_.error(where, "include file '" + clip(spelled) + "' is outside the folders this shader was given (" +
                                  folders + "); an include may not leave them");
    return 0;
  }
  Result<uint32_t> loaded = sources_.load_canonical(*resolved, found, target.size);
  if (!loaded) {
    diagnostics_.error(where, loaded.error().message);
    return 0;
  }
  loaded_includes_.emplace_back(found, *loaded);
  ensure_file_tables();
  if (resolved_whole) path_resolved_[*loaded] = 1;
  return *loaded;
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
  const std::string directive = "#" + std::string(name.text);
  if (lex.line_ended()) {
    diagnostics_.error(name.loc, "expected \"file\" or <file> after " + directive);
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
    extra_tokens(lex, name.text);
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
      diagnostics_.error(file.loc, "expected \"file\" or <file> after " + directive);
      return;
    }
  }
  if (spelled.empty()) {
    diagnostics_.error(file.loc, "empty file name in " + directive);
    return;
  }
  include_file(frame, name, spelled, angled, file.loc);
}

void Preprocessor::Impl::include_file(IncludeFrame& frame, const Token& name, std::string_view spelled, bool angled,
                                      Loc where) {
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
  const std::string_view folder = local ? std::string_view(frame.folder) : std::string_view();
  uint32_t index = 0;
  for (const IncludeLookup& lookup : include_lookups_)
    if (lookup.local == local && lookup.folder == folder && lookup.spelled == spelled) {
      index = lookup.file;
      break;
    }
  if (index == 0) {
    index = load_include(frame, local, spelled, where);
    if (index == 0) return;
    include_lookups_.push_back({local, std::string(folder), std::string(spelled), index});
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
  // Unity applies an included file's pragmas only along an unbroken chain of
  // #include_with_pragmas from the program (its manual's "pragma directives" limitations).
  includes_.back()->in_program = frame.in_program && name.text == "include_with_pragmas";
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
