#include "cli/scene_runs.h"

#include <fmt/core.h>

#include <ctime>
#include <map>

#include "cli/lane_selection.h"

namespace xshade::cli {

Result<SceneRunInputs> resolve_scene_run(const LaneSelection& selection, const FolderOptions& folders,
                                         const std::vector<std::string>& scenes, GoldenUse golden) {
  auto lanes = resolve_lanes(selection);
  if (!lanes) return fail(lanes.error());
  auto resolved = resolve_folders(folders, std::filesystem::current_path(), golden);
  if (!resolved) return fail(resolved.error());
  auto files = scene_files(scenes, *resolved);
  if (!files) return fail(files.error());
  return SceneRunInputs{std::move(*lanes), std::move(*resolved), std::move(*files)};
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void print_lane_details(const std::string& verb, const harness::SceneResult& scene) {
  std::map<std::string, std::string> first_lane_with;
  for (const harness::LaneResult& lane : scene.lanes) {
    if (lane.message.find('\n') == std::string::npos) continue;
    auto [seen, first] = first_lane_with.emplace(lane.message, lane.lane);
    if (first)
      fmt::print(stderr, "xshade {}: {} on {}: {}\n", verb, scene.scene, lane.lane, lane.message);
    else
      fmt::print(stderr, "xshade {}: {} on {}: as on {}\n", verb, scene.scene, lane.lane, seen->second);
  }
}

harness::ViewerPage viewer_page_of(const harness::CheckedScene& checked, const std::filesystem::path& report_dir) {
  std::map<std::string, const harness::FloatImage*> renders;
  for (const harness::LaneResult& lane : checked.result.lanes)
    if (auto id = harness::parse_lane(lane.lane); id && checked.images.count(*id))
      renders[lane.image_exr] = &checked.images.at(*id);
  return harness::viewer_page(checked.result, report_dir, renders);
}

}  // namespace xshade::cli
