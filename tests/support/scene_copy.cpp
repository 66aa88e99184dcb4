#include "tests/support/scene_copy.h"

#include <fstream>
#include <sstream>

namespace xshade::tests {

namespace fs = std::filesystem;

void copy_fixed_scene(const fs::path& source, const fs::path& root, const std::string& scene) {
  fs::remove_all(root);
  fs::create_directories(root / "scenes");
  fs::create_directories(root / "golden");
  fs::copy_file(source / "scenes" / (scene + ".toml"), root / "scenes" / (scene + ".toml"));
  for (const char* extension : {".png", ".exr"})
    if (fs::exists(source / "golden" / (scene + extension)))
      fs::copy_file(source / "golden" / (scene + extension), root / "golden" / (scene + extension));
  fs::copy_file(source / "golden" / "MANIFEST.toml", root / "golden" / "MANIFEST.toml");
  fs::copy(source / "shaders", root / "shaders", fs::copy_options::recursive);
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace xshade::tests
