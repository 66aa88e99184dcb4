// Path containment: the rule that holds every path a user's file names to its folder.
#pragma once

#include <filesystem>
#include <optional>

namespace xshade {

// Whether `file` lies inside `folder` once `..` and symbolic links are resolved in both (a link
// inside the folder that points out of it is outside). Every path a user's file names, an
// #include or a scene's texture, is held to its folders with this before anything reads it.
bool path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder);

// The two halves of path_is_inside, for a caller that holds many paths to the same folders:
// each folder and each file is resolved once (resolving asks the file system about every
// component of the path) and the containment itself is then lexical.
//
// `path` made absolute with `..` and symbolic links resolved (the part that does not exist yet
// is kept as written); nothing when the file system cannot tell.
std::optional<std::filesystem::path> resolved_path(const std::filesystem::path& path);
// resolved_path for a path that exists, the same path when it does; nothing when it does not.
// resolved_path first asks whether the whole path exists (to know how much of it to resolve),
// which a caller that knows the path exists, or is content with nothing otherwise, need not ask.
std::optional<std::filesystem::path> existing_resolved_path(const std::filesystem::path& path);
// path_is_inside for a file and a folder resolved_path gave.
bool resolved_path_is_inside(const std::filesystem::path& file, const std::filesystem::path& folder);

}  // namespace xshade
