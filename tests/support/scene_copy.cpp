#include "tests/support/scene_copy.h"

#include <gtest/gtest.h>

#include "harness/render/shader_cache.h"

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

std::string copied_scene_options(const fs::path& root) {
  return " --cache '" + (root / "cache").string() + "' --scenes '" + (root / "scenes").string() + "' --golden '" +
         (root / "golden").string() + "' --shaders '" + (root / "shaders").string() + "'";
}

void replace_in_file(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = read_text(file);
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " is not in " << file;
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

void write_manifest_for(const fs::path& golden, const std::string& scene) {
  std::ofstream(golden / "MANIFEST.toml", std::ios::trunc)
      << "[[golden]]\nscene = \"" << scene << "\"\nreason = \"made by a test\"\nblessed_by = \"test\"\n"
      << "date = \"2024-05-01T12:34:56Z\"\nhash = \"" << harness::content_hash(read_text(golden / (scene + ".png")))
      << "\"\n";
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace xshade::tests
