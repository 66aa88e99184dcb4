// Where the verbs find scenes, their goldens, shaders and the shader cache: the folders given on
// the command line, else those of the project file (harness/project_file.h), else xshade's own.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "harness/render/shader_search_path.h"

namespace xshade::cli {

// xshade's own data: its shader library, its fixed scenes and their goldens, the stability
// suite's probe shaders. In <prefix>/share/xshade beside an installed binary, else (a build) in
// the source tree the binary was built from.
struct OwnFolders {
  std::filesystem::path shaders;
  std::filesystem::path scenes;
  std::filesystem::path golden;
  std::filesystem::path probes;
  bool installed = false;
};
const OwnFolders& own_folders();

// The folder options of `run` and `bless`; empty means not given.
struct FolderOptions {
  std::filesystem::path scenes;
  std::filesystem::path golden;
  std::vector<std::filesystem::path> shaders;  // searched in order, before xshade's library
  std::filesystem::path project;               // the project file; empty: xshade.toml found from the working folder
  bool no_project = false;                     // use no project file
};

struct SceneFolders {
  std::filesystem::path scenes;
  std::filesystem::path golden;        // empty only when it was not needed and not given
  harness::ShaderSearchPath shaders;   // the user's folders, then xshade's library
  std::filesystem::path project_file;  // empty when none was used
  bool own_golden = false;             // the goldens are xshade's own (so the scenes must be too)
};

// What a verb does with the golden folder: nothing (info, run --plan), read it (run), or write
// it (bless, which creates it).
enum class GoldenUse { None, Read, Write };

// Resolves each folder: the command line's, else the project file's, else xshade's own; a
// broken project file is an error, and so is a shader folder that does not exist. The goldens
// of a user's scenes must be the user's too: when the scenes are not xshade's own and no golden
// folder is given, that is an error unless `golden` is None (blessing would otherwise write into
// xshade's own goldens), and then `golden` stays empty. A golden folder to read must exist: a
// misspelt one must not pass every scene as "no golden".
Result<SceneFolders> resolve_folders(const FolderOptions& given, const std::filesystem::path& working_folder,
                                     GoldenUse golden);

// The scene files named: each a scene name in `folders.scenes` (a file name without .toml) or a
// path to a .toml file; none means every scene in the folder, by name. A name that is not a plain
// file name is an error (`../../etc/passwd` names no scene). A .toml path outside xshade's own
// scenes cannot use xshade's own goldens.
Result<std::vector<std::filesystem::path>> scene_files(const std::vector<std::string>& scenes,
                                                       const SceneFolders& folders);

// The include folders of a compile: those given, then xshade's shader library, so that a user's
// shader can include "include/brdf.hlsl" wherever xshade is installed.
std::vector<std::filesystem::path> include_folders(const std::vector<std::filesystem::path>& given);

// `given`, else $XSHADE_CACHE_DIR, else $XDG_CACHE_HOME/xshade, else ~/.cache/xshade, else (no
// HOME) a folder of this user's in the temporary folder, xshade-cache-UID.
std::filesystem::path shader_cache_dir(const std::filesystem::path& given);

// `folder` made private (base/file_io.h's make_private_folder); empty, with a warning on stderr
// naming `verb`, when it cannot be: xshade believes what its cache holds, so it uses no cache
// another user can write.
// The drivers' own shader cache inside it is turned off for the process and its workers, with a
// warning, when the folder cannot be written or its disk has less than kMinDriverCacheFreeBytes
// free (Mesa maps its index file into memory, and a write to a map on a full disk is a SIGBUS);
// where it is on, one whose entries changed since the last run recorded them is set aside with a
// warning (harness/render/driver_cache.h), and the caller records them after its run.
std::filesystem::path private_cache_dir(const std::filesystem::path& folder, std::string_view verb);
// Mesa's index is under 2 MiB and every fixed scene's entries together a few MiB more: 64 MiB
// leaves room for a project's.
inline constexpr uint64_t kMinDriverCacheFreeBytes = uint64_t(64) << 20;

}  // namespace xshade::cli
