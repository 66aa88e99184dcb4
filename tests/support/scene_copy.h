// A fixed scene copied into a temporary folder for a test that changes it: the scene file, its
// golden as bless wrote it (the PNG, the float image where there is one, the manifest) and the
// shader library, laid out as a user's project would have them.
#pragma once

#include <filesystem>
#include <string>

namespace xshade::tests {

// Writes ROOT/scenes/SCENE.toml, ROOT/golden/{SCENE.png, SCENE.exr, MANIFEST.toml} and
// ROOT/shaders/ from xshade's source tree `source`; ROOT is emptied first.
void copy_fixed_scene(const std::filesystem::path& source, const std::filesystem::path& root, const std::string& scene);

// The whole file, or empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

}  // namespace xshade::tests
