// What the gating tests' files share: xshade's source tree, whose fixed scenes and goldens they
// run, and the fixed scene they copy and change (it has a texture, a golden PNG and a float image).
#pragma once

#include <filesystem>

namespace xshade::tests {

inline const std::filesystem::path kSource = XSHADE_SOURCE_DIR;
inline constexpr const char* kCopiedScene = "toon_shadow_texture";

}  // namespace xshade::tests
