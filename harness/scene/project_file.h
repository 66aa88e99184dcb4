// The project file: `xshade.toml` at the root of a user's repository says where that repository
// keeps its scenes, their goldens and its own shaders, so that `xshade run` and `xshade bless`
// there need no folder options (docs/getting_started.md).
//
//   scenes = "xshade/scenes"     # the scene files (*.toml)
//   golden = "xshade/golden"     # their golden images and MANIFEST.toml
//   shaders = ["shaders"]        # searched in order before xshade's own shader library
//
// Paths are relative to the project file's folder and may not leave it (`..` and symbolic links
// resolved): a checkout's project file cannot point xshade at files outside the checkout.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace xshade::harness {

struct ProjectFile {
  std::filesystem::path path;                   // the file, absolute
  std::filesystem::path root;                   // its folder: every path below is inside it
  std::optional<std::filesystem::path> scenes;  // absolute; nullopt when the file does not say
  std::optional<std::filesystem::path> golden;
  std::vector<std::filesystem::path> shaders;
};

inline constexpr std::string_view kProjectFileName = "xshade.toml";

// Reads and checks a project file; every problem is reported as file:line:col (like a scene's).
// `scenes` and each of `shaders` must be existing folders; `golden` may not exist yet (blessing
// creates it) but must not be a file.
Result<ProjectFile> load_project_file(const std::filesystem::path& file);
// The same for text in memory; `file` names it and anchors its paths.
Result<ProjectFile> parse_project_file(std::string_view text, const std::filesystem::path& file);

// A project file is a few lines; this bounds what a mistaken or hostile one makes xshade read.
inline constexpr size_t kMaxProjectFileBytes = size_t(1) << 20;

// The project file that governs `start`: xshade.toml in it or the nearest folder above it,
// looking no higher than the root of the repository `start` is in (the first folder with a .git)
// or the file system's root. nullopt when there is none; an error when an xshade.toml on the way
// is not a file (a directory, a FIFO, a link to nothing), which is never passed over.
Result<std::optional<std::filesystem::path>> find_project_file(const std::filesystem::path& start);

}  // namespace xshade::harness
