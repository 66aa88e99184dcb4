#include "harness/cli/scene_files.h"

#include <algorithm>
#include <cstdlib>

namespace xshade::cli {

namespace fs = std::filesystem;

Result<std::vector<fs::path>> scene_files(const std::vector<std::string>& scenes, const fs::path& scenes_dir) {
  std::vector<fs::path> files;
  if (scenes.empty()) {
    std::error_code error;
    for (fs::directory_iterator it(scenes_dir, error), end; !error && it != end; it.increment(error))
      if (it->path().extension() == ".toml") files.push_back(it->path());
    if (error) return fail("cannot read the scenes folder " + scenes_dir.string() + ": " + error.message());
    std::sort(files.begin(), files.end());
    if (files.empty()) return fail("no scenes (*.toml) in " + scenes_dir.string());
    return files;
  }
  for (const std::string& scene : scenes) {
    const fs::path as_given(scene);
    files.push_back(as_given.extension() == ".toml" ? as_given : scenes_dir / (scene + ".toml"));
  }
  return files;
}

fs::path shader_cache_dir(const fs::path& given) {
  if (!given.empty()) return given;
  if (const char* dir = std::getenv("XSHADE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir && *dir) return fs::path(dir) / "xshade";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "xshade";
  return fs::temp_directory_path() / "xshade-cache";
}

}  // namespace xshade::cli
