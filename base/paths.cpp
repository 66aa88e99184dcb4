#include "base/paths.h"

#include <system_error>

namespace xshade {

std::optional<std::filesystem::path> resolved_path(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
  if (error) return std::nullopt;
  return resolved;
}

std::optional<std::filesystem::path> existing_resolved_path(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  if (error) return std::nullopt;
  fs::path resolved = fs::canonical(absolute, error);
  if (error) return std::nullopt;
  return resolved;
}

bool resolved_path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  // The common case on the strings, as lexically_relative would decide it: the file's path is the
  // folder's, a separator and names none of which is empty or starts with a dot (no `.` or `..`).
  // Anything else is left to lexically_relative, which parses both paths into components.
  const std::string& f = file.native();
  const std::string& d = folder.native();
  if (!d.empty() && d.back() != '/' && f.size() > d.size() + 1 && f.compare(0, d.size(), d) == 0 &&
      f[d.size()] == '/') {
    bool plain = true;
    for (size_t i = d.size() + 1; i < f.size() && plain; ++i)
      if (f[i - 1] == '/') plain = f[i] != '/' && f[i] != '.';
    if (plain && f.back() != '/') return true;
  }
  const std::filesystem::path relative = file.lexically_relative(folder);
  return !relative.empty() && relative != "." && *relative.begin() != "..";
}

bool path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  const std::optional<std::filesystem::path> real = resolved_path(file);
  if (!real) return false;
  const std::optional<std::filesystem::path> root = resolved_path(folder);
  return root && resolved_path_is_inside(*real, *root);
}

}  // namespace xshade
