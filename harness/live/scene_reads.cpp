#include "harness/live/scene_reads.h"

#include <algorithm>

#include "harness/live/file_watcher.h"

namespace xshade::harness {

namespace fs = std::filesystem;

namespace {

void add_texture(std::set<fs::path>& reads, const TextureRef& texture) {
  if (!texture.file.empty()) reads.insert(normal_file_path(texture.file));
  for (const fs::path& face : texture.faces) reads.insert(normal_file_path(face));
}

}  // namespace

std::set<fs::path> scene_reads(const fs::path& scene_file, const CheckedScene& checked, const fs::path& project_file,
                               const GoldenStore* goldens) {
  std::set<fs::path> reads = {normal_file_path(scene_file)};
  if (!project_file.empty()) reads.insert(normal_file_path(project_file));
  for (const fs::path& file : checked.files_read) reads.insert(normal_file_path(file));
  if (goldens)
    for (const LaneResult& lane : checked.result.lanes)
      for (const fs::path& file : goldens->files_for(checked.result.scene, lane.lane)) {
        std::error_code error;
        if (fs::is_directory(file.parent_path(), error)) reads.insert(normal_file_path(file));
      }
  if (!checked.scene) return reads;
  const Scene& scene = *checked.scene;
  if (!scene.environment.file.empty()) reads.insert(normal_file_path(scene.environment.file));
  for (const SceneObject& object : scene.objects) {
    if (!object.mesh.file.empty()) reads.insert(normal_file_path(object.mesh.file));
    for (const auto& [name, texture] : object.textures) add_texture(reads, texture);
    for (const auto& [name, buffer] : object.buffers)
      if (!buffer.file.empty()) reads.insert(normal_file_path(buffer.file));
  }
  for (const PostEffect& effect : scene.post)
    for (const auto& [name, texture] : effect.textures) add_texture(reads, texture);
  return reads;
}

void SceneReadIndex::set(const fs::path& scene_file, std::set<fs::path> reads) {
  reads_[normal_file_path(scene_file)] = std::move(reads);
}

void SceneReadIndex::forget(const fs::path& scene_file) { reads_.erase(normal_file_path(scene_file)); }

std::vector<fs::path> SceneReadIndex::reached(const std::set<fs::path>& changed,
                                              const std::vector<fs::path>& scene_files) const {
  std::vector<fs::path> scenes;
  for (const fs::path& scene : scene_files) {
    const fs::path normal = normal_file_path(scene);
    const auto known = reads_.find(normal);
    // A scene never rendered is reached by its own file alone.
    const bool reads_one = known == reads_.end()
                               ? changed.count(normal) > 0
                               : std::any_of(changed.begin(), changed.end(),
                                             [&](const fs::path& file) { return known->second.count(file) > 0; });
    if (reads_one) scenes.push_back(scene);
  }
  return scenes;
}

std::set<fs::path> SceneReadIndex::all_files() const {
  std::set<fs::path> files;
  for (const auto& [scene, reads] : reads_) files.insert(reads.begin(), reads.end());
  return files;
}

}  // namespace xshade::harness
