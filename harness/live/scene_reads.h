// Which files each scene reads, and so which scenes a saved file reaches: `xshade watch` renders
// again only those.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/gate/scene_check.h"

namespace xshade::harness {

// Every file a checked scene read: the scene file, the project file (when one is used), the
// meshes, textures, buffers and environment image it names, the shader sources and includes its
// plan and its lanes' compiles read (CheckedScene::files_read), and with `goldens` each lane's
// golden images (GoldenStore::files_for, those in a folder that exists: a bless makes them). A
// scene that did not load read its file alone (and the project file): it is rendered again when
// that changes. Each path absolute and normal (file_watcher.h's normal_file_path).
std::set<std::filesystem::path> scene_reads(const std::filesystem::path& scene_file, const CheckedScene& checked,
                                            const std::filesystem::path& project_file,
                                            const GoldenStore* goldens = nullptr);

// The files of each scene, by scene file, as the last render of each found them.
class SceneReadIndex {
 public:
  void set(const std::filesystem::path& scene_file, std::set<std::filesystem::path> reads);
  // A scene no longer watched: its files reach nothing and are not watched for it.
  void forget(const std::filesystem::path& scene_file);
  // The scenes that read any of `changed`, in the order of `scene_files`.
  std::vector<std::filesystem::path> reached(const std::set<std::filesystem::path>& changed,
                                             const std::vector<std::filesystem::path>& scene_files) const;
  // Every file any scene reads.
  std::set<std::filesystem::path> all_files() const;

 private:
  std::map<std::filesystem::path, std::set<std::filesystem::path>> reads_;  // by normal scene file
};

}  // namespace xshade::harness
