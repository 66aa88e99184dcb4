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

bool resolved_path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder) {
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
