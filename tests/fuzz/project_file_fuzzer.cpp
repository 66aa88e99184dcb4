// libFuzzer target: any bytes as a project file (xshade.toml). The reader must report, never
// crash, hang or read out of bounds, and every folder it accepts must be inside the project.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "base/paths.h"
#include "harness/scene/project_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // A folder that exists, so that "scenes" and "shaders" can name real folders (its own, ".").
  static const std::filesystem::path root = [] {
    auto folder = std::filesystem::temp_directory_path() / "xshade_project_fuzz";
    std::filesystem::create_directories(folder / "scenes");
    return folder;
  }();
  auto project = xshade::harness::parse_project_file(text, root / "xshade.toml");
  if (!project) {
    (void)project.error().to_string();
    return 0;
  }
  auto inside = [&](const std::filesystem::path& folder) {
    return folder == project->root || xshade::path_is_inside(folder, project->root);
  };
  if (project->scenes && !inside(*project->scenes)) std::abort();
  if (project->golden && !inside(*project->golden)) std::abort();
  for (const auto& folder : project->shaders)
    if (!inside(folder)) std::abort();
  return 0;
}
