// Path containment: the rule that holds every path a user's file names to its folder.
#pragma once

#include <filesystem>

namespace xshade {

// Whether `file` lies inside `folder` once `..` and symbolic links are resolved in both (a link
// inside the folder that points out of it is outside). Every path a user's file names, an
// #include or a scene's texture, is held to its folders with this before anything reads it.
bool path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder);

}  // namespace xshade
