// Where `run` and `bless` find scenes and the shader cache.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "hlsl_like/diagnostic.h"

namespace xshade::cli {

// The scene files named: each a scene name in `scenes_dir` or a path to a .toml file; none
// means every scene in `scenes_dir`, by name.
Result<std::vector<std::filesystem::path>> scene_files(const std::vector<std::string>& scenes,
                                                       const std::filesystem::path& scenes_dir);

// `given`, else $XSHADE_CACHE_DIR, else $XDG_CACHE_HOME/xshade, else ~/.cache/xshade.
std::filesystem::path shader_cache_dir(const std::filesystem::path& given);

}  // namespace xshade::cli
