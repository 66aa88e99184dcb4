#include "hlsl_like/source_manager.h"

#include <sys/stat.h>

#include <optional>
#include <system_error>
#include <utility>

#include "base/file_io.h"
#include "base/paths.h"

namespace xshade::hlsl {

SourceManager::SourceManager() { files_.push_back(std::make_unique<File>()); }  // index 0: none

uint32_t SourceManager::add(std::string name, std::string text) {
  auto file = std::make_unique<File>();
  file->name = std::move(name);
  file->text = std::move(text);
  files_.push_back(std::move(file));
  return uint32_t(files_.size() - 1);
}

Result<uint32_t> SourceManager::load(const std::filesystem::path& path) {
  // A file that can be read exists: resolved whole, which weakly_canonical would also do after
  // first asking whether it exists. Only a path that does not resolve is made canonical as far
  // as it exists (and then most likely does not open).
  std::optional<std::filesystem::path> resolved = existing_resolved_path(path);
  const bool resolved_whole = resolved.has_value();
  std::filesystem::path canonical;
  if (resolved_whole) {
    canonical = std::move(*resolved);
  } else {
    std::error_code error;
    canonical = std::filesystem::weakly_canonical(path, error);
    if (error) canonical = path;
  }
  Result<uint32_t> loaded = load_canonical(canonical, path.string());
  if (loaded && resolved_whole) files_[*loaded]->resolved_on_load = true;
  return loaded;
}

Result<uint32_t> SourceManager::load_canonical(const std::filesystem::path& canonical, std::string name,
                                               std::optional<size_t> known_size) {
  for (uint32_t i = 1; i < files_.size(); ++i)
    if (!files_[i]->path.empty() && files_[i]->path == canonical) return i;
  // The size first, so that a file no shader is as large as (a log, a sparse file of gigabytes)
  // is refused unread; an #include has been stat'ed already.
  if (!known_size) {
    struct stat status {};
    if (::stat(canonical.c_str(), &status) == 0 && S_ISREG(status.st_mode)) known_size = size_t(status.st_size);
  }
  if (known_size && *known_size > kMaxSourceFileBytes)
    return fail(ErrorKind::UserInput, "'" + name + "' is " + std::to_string(*known_size) +
                                          " bytes; a shader source may have at most " +
                                          std::to_string(kMaxSourceFileBytes >> 20) + " MiB");
  ReadFailure failure = ReadFailure::CannotOpen;
  std::optional<std::string> text =
      known_size ? read_regular_file(canonical, *known_size, &failure) : read_file(canonical, &failure);
  if (!text) {
    if (failure == ReadFailure::IsDirectory) return fail(ErrorKind::UserInput, "'" + name + "' is a directory");
    if (failure == ReadFailure::NotAFile)
      return fail(ErrorKind::UserInput, "'" + name + "' is " + not_a_file(canonical) + ", not a file");
    return fail(ErrorKind::UserInput,
                (failure == ReadFailure::CannotOpen ? "cannot open '" : "cannot read '") + name + "'");
  }
  uint32_t index = add(std::move(name), std::move(*text));
  files_[index]->path = canonical;
  return index;
}
std::string_view SourceManager::line_text(uint32_t file, uint32_t line) const {
  if (file == 0 || file >= files_.size() || line == 0) return {};
  const File& f = *files_[file];
  if (f.line_starts.empty()) {
    f.line_starts.push_back(0);
    for (uint32_t i = 0; i < f.text.size(); ++i)
      if (f.text[i] == '\n') f.line_starts.push_back(i + 1);
  }
  if (line > f.line_starts.size()) return {};
  const uint32_t start = f.line_starts[line - 1];
  uint32_t end = line < f.line_starts.size() ? f.line_starts[line] - 1 : uint32_t(f.text.size());
  if (end > start && f.text[end - 1] == '\r') --end;
  return std::string_view(f.text).substr(start, end - start);
}

SourceLocation SourceManager::resolve(Loc loc) const {
  if (loc.file == 0 || loc.file >= files_.size()) return {};
  const File& f = *files_[loc.file];
  std::string name = f.name;
  uint32_t line = loc.line;
  for (const File::LineMapping& mapping : f.line_mappings) {
    if (mapping.from_line > loc.line) break;
    line = mapping.line + (loc.line - mapping.from_line);
    if (!mapping.name.empty()) name = mapping.name;
  }
  return {std::move(name), line, loc.column};
}

void SourceManager::add_line_mapping(uint32_t file, uint32_t from_line, uint32_t line, std::string name) {
  if (file == 0 || file >= files_.size()) return;
  auto& mappings = files_[file]->line_mappings;
  // A file is read once, top to bottom: each #line comes after the ones before it.
  if (!mappings.empty() && mappings.back().from_line >= from_line) return;
  mappings.push_back({from_line, line, std::move(name)});
}

}  // namespace xshade::hlsl
