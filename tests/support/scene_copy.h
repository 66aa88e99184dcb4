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

// " --cache 'ROOT/cache' --scenes 'ROOT/scenes' --golden 'ROOT/golden' --shaders 'ROOT/shaders'":
// the options that make a verb use the copy (and a cache of its own).
std::string copied_scene_options(const std::filesystem::path& root);

// Replaces the first `from` in `file` with `to`; a test fails when `file` does not hold `from`.
void replace_in_file(const std::filesystem::path& file, const std::string& from, const std::string& to);

// Writes GOLDEN/MANIFEST.toml with one entry for `scene`, hashing GOLDEN/SCENE.png as bless does:
// for a golden a test made by hand (no golden is used without its entry and hash).
void write_manifest_for(const std::filesystem::path& golden, const std::string& scene);

// The whole file, or empty when it cannot be read.
std::string read_text(const std::filesystem::path& path);

}  // namespace xshade::tests
