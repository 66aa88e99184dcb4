#include "cli/folders.h"

#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "base/file_io.h"
#include "base/paths.h"
#include "base/spelling.h"
#include "harness/render/driver_cache.h"
#include "harness/render/lanes.h"
#include "harness/scene/project_file.h"

namespace xshade::cli {

namespace fs = std::filesystem;

const OwnFolders& own_folders() {
  static const OwnFolders folders = [] {
    std::error_code error;
    const fs::path binary = fs::read_symlink("/proc/self/exe", error);
    if (!error) {
      // XSHADE_DATA_FROM_BINARY is the install's share/xshade relative to its bin folder.
      const fs::path data = (binary.parent_path() / XSHADE_DATA_FROM_BINARY).lexically_normal();
      if (fs::is_directory(data / "shaders", error))
        return OwnFolders{data / "shaders", data / "scenes", data / "golden", data / "probes", true};
    }
    const fs::path source = XSHADE_SOURCE_DIR;
    return OwnFolders{source / "shaders", source / "scenes", source / "golden", source / "stability/probes", false};
  }();
  return folders;
}

Result<SceneFolders> resolve_folders(const FolderOptions& given, const fs::path& working_folder, GoldenUse golden) {
  std::optional<harness::ProjectFile> project;
  if (!given.no_project) {
    std::optional<fs::path> file = given.project;
    if (file->empty()) {
      auto found = harness::find_project_file(working_folder);
      if (!found) return fail(found.error());
      file = *found;
    }
    if (file) {
      auto loaded = harness::load_project_file(*file);
      if (!loaded) return fail(loaded.error());
      project = std::move(*loaded);
    }
  }
  const OwnFolders& own = own_folders();
  std::vector<fs::path> shaders = !given.shaders.empty() ? given.shaders
                                  : project              ? project->shaders
                                                         : std::vector<fs::path>{};
  for (const fs::path& folder : shaders) {
    std::error_code error;
    if (!fs::is_directory(folder, error))
      return fail(ErrorKind::Usage,
                  "the shader folder " + folder.string() + " (" +
                      (given.shaders.empty() ? "the project file's shaders" : std::string("--shaders")) +
                      ") is not a folder");
  }
  shaders.push_back(own.shaders);
  SceneFolders folders{
      {}, {}, harness::ShaderSearchPath(std::move(shaders)), project ? project->path : fs::path(), false};

  const bool own_scenes = given.scenes.empty() && !(project && project->scenes);
  folders.scenes = !given.scenes.empty() ? given.scenes : own_scenes ? own.scenes : *project->scenes;

  if (!given.golden.empty()) {
    folders.golden = given.golden;
  } else if (project && project->golden) {
    folders.golden = *project->golden;
  } else if (own_scenes) {
    folders.golden = own.golden;
    folders.own_golden = true;
  } else if (golden != GoldenUse::None) {
    return fail(ErrorKind::Usage, "the scenes in " + folders.scenes.string() +
                                      " are not xshade's own, so their goldens cannot be either: give --golden DIR" +
                                      (project ? " or golden = \"...\" in " + project->path.string() : std::string()));
  }
  std::error_code error;
  if (golden == GoldenUse::Read && !fs::is_directory(folders.golden, error))
    return fail(ErrorKind::Usage, "the golden folder " + folders.golden.string() + " (" +
                                      (!given.golden.empty() ? std::string("--golden") : "the project file's golden") +
                                      ") does not exist: name the folder that holds MANIFEST.toml, or create the "
                                      "goldens with xshade bless");
  return folders;
}

// The .toml files in `folder`, sorted.
static std::vector<fs::path> scenes_in(const fs::path& folder, std::error_code& error) {
  std::vector<fs::path> files;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
    if (it->path().extension() == ".toml") files.push_back(it->path());
  std::sort(files.begin(), files.end());
  return files;
}

// A scene file found in the scenes folder is held to it like every path a scene names: a
// symbolic link there that points out of the folder would have xshade read (and render, and
// report) a file the folder's owner never put in it.
static Result<void> check_inside(const fs::path& file, const fs::path& folder) {
  if (path_is_inside(file, folder)) return {};
  std::error_code error;
  const fs::path target = fs::weakly_canonical(file, error);
  return fail(ErrorKind::UserInput,
              "the scene file " + file.string() + " is a symbolic link that points outside the scenes folder " +
                  folder.string() + (error ? std::string() : " (to " + target.string() + ")") +
                  "; a scene file must be inside its folder",
              SourceLocation{file.string(), 0, 0});
}

Result<std::vector<fs::path>> scene_files(const std::vector<std::string>& scenes, const SceneFolders& folders) {
  std::vector<fs::path> files;
  if (scenes.empty()) {
    std::error_code error;
    files = scenes_in(folders.scenes, error);
    if (error)
      return fail(ErrorKind::Usage,
                  "cannot read the scenes folder " + folders.scenes.string() + ": " + error.message());
    if (files.empty()) return fail(ErrorKind::Usage, "no scenes (*.toml) in " + folders.scenes.string());
    for (const fs::path& file : files)
      if (Result<void> inside = check_inside(file, folders.scenes); !inside) return fail(inside.error());
    return files;
  }
  for (const std::string& scene : scenes) {
    const fs::path as_given(scene);
    if (as_given.extension() == ".toml") {
      if (folders.own_golden && !path_is_inside(as_given, folders.scenes))
        return fail(ErrorKind::Usage, "'" + scene + "' is not one of xshade's own scenes (" + folders.scenes.string() +
                                          "), so its golden cannot be xshade's either: give --golden DIR");
      files.push_back(as_given);
      continue;
    }
    if (scene.empty() || as_given.has_parent_path() || scene == "." || scene == "..")
      return fail(ErrorKind::Usage, "'" + scene + "' is not a scene name: a name is a file name in " +
                                        folders.scenes.string() +
                                        " without .toml; give a path ending in .toml for a file elsewhere");
    const fs::path file = folders.scenes / (scene + ".toml");
    std::error_code error;
    if (!fs::exists(file, error)) {
      std::vector<std::string> known;
      for (const fs::path& other : scenes_in(folders.scenes, error)) known.push_back(other.stem().string());
      std::string message = "no scene '" + scene + "' in " + folders.scenes.string();
      if (auto near = nearest(scene, known)) message += "; did you mean '" + *near + "'?";
      if (harness::parse_lane(scene)) message += " (lanes are chosen with --lane " + scene + ", or --lane gl,vk)";
      return fail(ErrorKind::Usage, message);
    }
    if (Result<void> inside = check_inside(file, folders.scenes); !inside) return fail(inside.error());
    files.push_back(file);
  }
  return files;
}

std::vector<fs::path> include_folders(const std::vector<fs::path>& given) {
  std::vector<fs::path> folders = given;
  folders.push_back(own_folders().shaders);
  return folders;
}

fs::path shader_cache_dir(const fs::path& given) {
  if (!given.empty()) return given;
  if (const char* dir = std::getenv("XSHADE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir && *dir) return fs::path(dir) / "xshade";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "xshade";
  return fs::temp_directory_path() / ("xshade-cache-" + std::to_string(::geteuid()));
}

fs::path private_cache_dir(const fs::path& folder, std::string_view verb) {
  if (folder.empty()) return folder;
  if (auto made = make_private_folder(folder); !made) {
    fmt::print(stderr, "xshade {}: warning: not using the compile cache: {}\n", verb, made.error().message);
    return {};
  }
  // Mesa writes its shader cache's index through a shared memory map: on a full disk that is a
  // SIGBUS in every driver, and in a folder it cannot write, every run compiles as if cold and
  // slower. xshade's own entries are written with checked writes, and stay on.
  std::string why_not;
  struct statvfs space {};
  if (::access(folder.c_str(), W_OK) != 0)
    why_not = folder.string() + " cannot be written (" + std::strerror(errno) + ")";
  else if (::statvfs(folder.c_str(), &space) == 0 &&
           uint64_t(space.f_bavail) * space.f_frsize < kMinDriverCacheFreeBytes)
    why_not = fmt::format("the disk of {} has {} KiB free, less than the {} MiB it needs", folder.string(),
                          uint64_t(space.f_bavail) * space.f_frsize / 1024, kMinDriverCacheFreeBytes >> 20);
  if (!why_not.empty()) {
    fmt::print(stderr, "xshade {}: warning: the drivers' shader cache is off for this run: {}\n", verb, why_not);
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);  // the workers inherit it
  } else if (const std::optional<std::string> damage =
                 harness::check_driver_cache(harness::driver_cache_folder(folder))) {
    fmt::print(stderr, "xshade {}: warning: {}\n", verb, *damage);
  }
  return folder;
}

}  // namespace xshade::cli
