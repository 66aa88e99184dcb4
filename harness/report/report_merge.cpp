#include "harness/report/report_merge.h"

#include <algorithm>
#include <map>

#include "base/file_io.h"
#include "base/paths.h"
#include "harness/gate/scene_check.h"
#include "harness/image/image_io.h"
#include "harness/report/results_json.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

Result<FoundReport> read_report(const fs::path& folder) {
  const fs::path file = folder / "results.json";
  auto text = read_input_file(file, kMaxResultsBytes, "the report's results");
  if (!text) return fail(text.error());
  auto results = results_from_json(*text, file.string());
  if (!results) return fail(results.error());
  return FoundReport{folder, std::move(*results)};
}

// Where each kept result came from, so that its files are copied from the right folder.
struct SceneMerge {
  SceneResult scene;
  std::vector<size_t> lane_report;  // beside scene.lanes
  std::vector<size_t> pair_report;  // beside scene.cross_lane
};

// Keeps `candidate` in place of `kept` when its verdict is worse.
template <class T>
void keep_worst(std::vector<T>& kept, std::vector<size_t>& sources, const T& candidate, size_t report,
                const auto& same) {
  const auto found = std::find_if(kept.begin(), kept.end(), [&](const T& each) { return same(each, candidate); });
  if (found == kept.end()) {
    kept.push_back(candidate);
    sources.push_back(report);
  } else if (worst(found->verdict, candidate.verdict) != found->verdict) {
    *found = candidate;
    sources[size_t(found - kept.begin())] = report;
  }
}

class FileMapper {
 public:
  FileMapper(const std::vector<FoundReport>& reports, MergedReport& merged) : reports_(reports), merged_(merged) {}

  // The merged report's path for `path` of report `r`; empty (with a warning) when there is no
  // such file in that report's folder.
  std::string map(size_t r, const std::string& path) {
    if (path.empty()) return path;
    const fs::path folder = reports_[r].folder;
    const fs::path from = folder / path;
    if (!path_is_inside(from, folder)) {
      merged_.warnings.push_back((folder / "results.json").string() + " names " + path + ", which leads out of " +
                                 folder.string() + "; it is left out");
      return {};
    }
    std::error_code error;
    if (!fs::is_regular_file(from, error)) {
      merged_.warnings.push_back((folder / "results.json").string() + " names " + path + ", which is not there");
      return {};
    }
    std::string to = path;
    for (auto taken = taken_.find(to); taken != taken_.end() && taken->second != from; taken = taken_.find(to))
      to = "run-" + std::to_string(r + 1) + "/" + path;
    if (taken_.emplace(to, from).second) merged_.files.push_back({from, to});
    return to;
  }

 private:
  const std::vector<FoundReport>& reports_;
  MergedReport& merged_;
  std::map<std::string, fs::path> taken_;
};

}  // namespace

Result<std::vector<FoundReport>> find_reports(const std::vector<fs::path>& folders) {
  std::vector<FoundReport> found;
  for (const fs::path& folder : folders) {
    std::error_code error;
    if (fs::exists(folder / "results.json", error)) {
      auto report = read_report(folder);
      if (!report) return fail(report.error());
      found.push_back(std::move(*report));
      continue;
    }
    if (!fs::is_directory(folder, error))
      return fail(ErrorKind::Usage,
                  folder.string() + " is not a report folder (it has no results.json) nor a folder of them");
    std::vector<fs::path> inner;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
      if (entry.is_directory() && fs::exists(entry.path() / "results.json")) inner.push_back(entry.path());
    if (inner.empty())
      return fail(ErrorKind::Usage, folder.string() +
                                        " holds no results.json, and none of its folders does: it is not a report of "
                                        "xshade run nor a folder of them");
    std::sort(inner.begin(), inner.end());
    for (const fs::path& each : inner) {
      auto report = read_report(each);
      if (!report) return fail(report.error());
      found.push_back(std::move(*report));
    }
  }
  return found;
}

MergedReport merge_reports(const std::vector<FoundReport>& reports) {
  MergedReport merged;
  std::map<std::string, SceneMerge> scenes;  // by name: the order a run lists them in
  for (size_t r = 0; r < reports.size(); ++r) {
    const RunResults& run = reports[r].results;
    merged.results.merged_from.push_back({reports[r].folder.string(), run.started, run.seconds, run.command});
    merged.results.seconds += run.seconds;
    if (!run.started.empty() && (merged.results.started.empty() || run.started < merged.results.started))
      merged.results.started = run.started;
    for (const SceneResult& scene : run.scenes) {
      auto [entry, first] = scenes.try_emplace(scene.scene);
      SceneResult& into = entry->second.scene;
      if (first) {
        into = scene;
        into.lanes.clear();
        into.cross_lane.clear();
      }
      into.verdict = worst(into.verdict, scene.verdict);
      if (into.message.empty()) into.message = scene.message;
      if (into.description.empty()) into.description = scene.description;
      if (into.plan.empty()) into.plan = scene.plan;
      for (const std::string& warning : scene.warnings)
        if (std::find(into.warnings.begin(), into.warnings.end(), warning) == into.warnings.end())
          into.warnings.push_back(warning);
      for (const LaneResult& lane : scene.lanes)
        keep_worst(into.lanes, entry->second.lane_report, lane, r,
                   [](const LaneResult& a, const LaneResult& b) { return a.lane == b.lane; });
      for (const CrossLaneResult& pair : scene.cross_lane)
        keep_worst(into.cross_lane, entry->second.pair_report, pair, r,
                   [](const CrossLaneResult& a, const CrossLaneResult& b) {
                     return a.first_lane == b.first_lane && a.second_lane == b.second_lane;
                   });
    }
  }

  FileMapper files(reports, merged);
  for (auto& [name, scene] : scenes) {
    for (size_t i = 0; i < scene.scene.lanes.size(); ++i) {
      LaneResult& lane = scene.scene.lanes[i];
      for (std::string* path :
           {&lane.image, &lane.image_exr, &lane.golden, &lane.golden_exr, &lane.diff, &lane.non_finite_mask})
        *path = files.map(scene.lane_report[i], *path);
    }
    for (size_t i = 0; i < scene.scene.cross_lane.size(); ++i)
      scene.scene.cross_lane[i].diff = files.map(scene.pair_report[i], scene.scene.cross_lane[i].diff);
    merged.results.scenes.push_back(std::move(scene.scene));
  }
  return merged;
}

std::vector<std::string> compare_lanes_across_reports(RunResults& results, const fs::path& folder) {
  std::vector<std::string> warnings;
  for (SceneResult& scene : results.scenes) {
    if (!scene.cross_lane.empty()) continue;
    std::map<Lane, FloatImage> images;
    // A lane that rendered (it passed or failed against its golden) and whose image cannot be read
    // leaves checks that should be made: each is an error, never a check that is not there.
    std::vector<Lane> unreadable, rendered;
    for (const LaneResult& lane : scene.lanes) {
      const std::optional<Lane> id = parse_lane(lane.lane);
      if (!id || (lane.verdict != Verdict::Pass && lane.verdict != Verdict::Fail)) continue;
      rendered.push_back(*id);
      auto image = lane.image_exr.empty()
                       ? Result<FloatImage>(fail(ErrorKind::UserInput, "the report names no float image of it"))
                       : read_image(folder / lane.image_exr);
      if (image) {
        images.emplace(*id, std::move(*image));
        continue;
      }
      unreadable.push_back(*id);
      warnings.push_back(image.error().message + "; " + scene.scene + " on " + lane.lane +
                         " is not held against the other lanes, and each check it misses is an error");
    }
    scene.cross_lane =
        cross_lane_results(images, scene.compare, [&](const FloatImage& heat_map, const std::string& file) {
          const std::string relative = scene.scene + "/" + file;
          std::error_code ignored;
          fs::create_directories((folder / relative).parent_path(), ignored);
          return write_png(heat_map, folder / relative, PngCompression::Fast) ? relative : std::string();
        });
    std::sort(rendered.begin(), rendered.end());
    for (size_t a = 0; a < rendered.size(); ++a)
      for (size_t b = a + 1; b < rendered.size(); ++b) {
        const bool missing = std::count(unreadable.begin(), unreadable.end(), rendered[a]) ||
                             std::count(unreadable.begin(), unreadable.end(), rendered[b]);
        if (!missing) continue;
        CrossLaneResult error;
        error.first_lane = std::string(lane_name(rendered[a]));
        error.second_lane = std::string(lane_name(rendered[b]));
        error.verdict = Verdict::Error;
        scene.cross_lane.push_back(std::move(error));
      }
    // In lane order, as a run lists its pairs.
    const auto order = [](const CrossLaneResult& pair) {
      return std::pair{parse_lane(pair.first_lane).value_or(Lane::Gl), parse_lane(pair.second_lane).value_or(Lane::Gl)};
    };
    std::stable_sort(scene.cross_lane.begin(), scene.cross_lane.end(),
                     [&](const CrossLaneResult& a, const CrossLaneResult& b) { return order(a) < order(b); });
    for (const CrossLaneResult& pair : scene.cross_lane) scene.verdict = worst(scene.verdict, pair.verdict);
  }
  return warnings;
}

}  // namespace xshade::harness
