#include "harness/render/shader_search_path.h"

#include <algorithm>
#include <set>
#include <system_error>

#include "base/paths.h"

namespace xshade::harness {

namespace fs = std::filesystem;

ShaderSearchPath::ShaderSearchPath(fs::path library) : folders_{std::move(library)} {}

ShaderSearchPath::ShaderSearchPath(std::vector<fs::path> folders) : folders_(std::move(folders)) {}

Result<fs::path> ShaderSearchPath::find(const std::string& library_path, std::vector<fs::path>* looked_in) const {
  const fs::path relative(library_path);
  const fs::path normal = relative.lexically_normal();
  if (relative.is_absolute() || relative.has_root_name() || normal.empty() || *normal.begin() == "..")
    return fail(ErrorKind::UserInput,
                "'" + library_path + "' is not a path inside the shader folders (" + describe() + ")");
  for (const fs::path& folder : folders_) {
    const fs::path candidate = (folder / normal).lexically_normal();
    if (looked_in) looked_in->push_back(candidate);
    std::error_code ignored;
    if (!fs::is_regular_file(candidate, ignored)) continue;
    if (!path_is_inside(candidate, folder))
      return fail(ErrorKind::UserInput,
                  "'" + library_path + "' in " + folder.string() +
                      " is a link that leads out of that folder; a shader must lie inside the folders it was given");
    return candidate;
  }
  return fail(ErrorKind::UserInput, "'" + library_path + "' is in none of the shader folders (" + describe() + ")");
}

std::vector<std::string> ShaderSearchPath::files(const std::string& kind) const {
  std::set<std::string> found;
  for (const fs::path& folder : folders_) {
    std::error_code error;
    for (fs::directory_iterator it(folder / kind, error), end; !error && it != end; it.increment(error))
      if (it->path().extension() == ".hlsl" || it->path().extension() == ".shader")
        found.insert(kind + "/" + it->path().filename().string());
  }
  return {found.begin(), found.end()};
}

std::string ShaderSearchPath::describe() const {
  std::string text;
  for (const fs::path& folder : folders_) text += (text.empty() ? "" : ", ") + folder.string();
  return text;
}

}  // namespace xshade::harness
