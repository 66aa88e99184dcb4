#include "harness/report/report.h"

#include <set>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "base/file_io.h"
#include "base/paths.h"
#include "harness/report/junit_report.h"
#include "harness/report/report_html.h"
#include "harness/report/results_json.h"
#include "harness/report/viewer_data.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// The list of what a run wrote, so that the next run into the same folder removes its pages and
// images that it does not write again, and nothing it did not write.
constexpr const char* kWrittenList = ".xshade-report-files";

std::vector<std::string> files_of(const RunResults& results, const std::vector<std::string>& pages) {
  std::vector<std::string> files = pages;
  for (const char* file :
       {"junit.xml", "results.json", "index.html", kViewerScriptFile, kViewerStyleFile, kWrittenList})
    files.push_back(file);
  for (const SceneResult& scene : results.scenes) {
    for (const LaneResult& lane : scene.lanes)
      for (const std::string* path : {&lane.image, &lane.image_exr, &lane.golden, &lane.golden_exr, &lane.diff,
                                      &lane.metric_map, &lane.non_finite_mask})
        if (!path->empty()) files.push_back(*path);
    for (const CrossLaneResult& pair : scene.cross_lane)
      if (!pair.diff.empty()) files.push_back(pair.diff);
  }
  return files;
}

// Removes what the earlier run listed and this one did not write (a scene since renamed, an
// image a passing lane no longer has), and the folders that leaves empty. A listed path that
// leads out of the folder is ignored: the list is data in a folder others can write.
void remove_stale(const fs::path& report_dir, const std::vector<std::string>& now) {
  auto earlier = read_file(report_dir / kWrittenList);
  if (!earlier) return;
  const std::set<std::string> keep(now.begin(), now.end());
  std::istringstream lines(*earlier);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || keep.count(line)) continue;
    std::error_code ignored;
    const fs::path path = report_dir / line;
    if (!path_is_inside(path, report_dir)) continue;
    if (fs::is_regular_file(fs::symlink_status(path, ignored))) fs::remove(path, ignored);
    for (fs::path folder = path.parent_path();
         folder != report_dir && folder.string().size() > report_dir.string().size(); folder = folder.parent_path())
      if (!fs::remove(folder, ignored)) break;  // only an empty folder is removed
  }
}

}  // namespace

Result<void> write_reports(const RunResults& results, const fs::path& report_dir,
                           const std::vector<ViewerPage>* viewers, const std::vector<bool>* written_already) {
  std::error_code error;
  fs::create_directories(report_dir, error);
  if (error)
    return fail(ErrorKind::Backend, "cannot create the report folder " + report_dir.string() + ": " + error.message());

  for (const auto& [file, text] :
       {std::pair{kViewerScriptFile, viewer_script()}, std::pair{kViewerStyleFile, viewer_style()}})
    if (auto written = write_file_atomically(report_dir / file, text); !written) return written;
  const std::vector<std::string> pages = scene_page_names(results);
  std::vector<std::string> pixel_scripts;
  std::set<std::string> scripted;  // the images whose pixels/KEY.js this write made
  for (size_t i = 0; i < results.scenes.size(); ++i) {
    const ViewerPage viewer =
        viewers && i < viewers->size() ? (*viewers)[i] : viewer_page(results.scenes[i], report_dir, {}, &scripted);
    const bool in_place = viewers && written_already && i < written_already->size() && (*written_already)[i];
    for (const ViewerPage::PixelScript& pixels : viewer.pixels) {
      if (pixels.script.empty()) continue;
      const std::string script = pixel_script_path(pixels.image);
      if (in_place) {
        pixel_scripts.push_back(script);
        continue;
      }
      fs::create_directories((report_dir / script).parent_path(), error);
      if (auto written = write_file_atomically(report_dir / script, pixels.script); !written) return written;
      pixel_scripts.push_back(script);
    }
    if (in_place) continue;
    if (auto written = write_file_atomically(report_dir / pages[i], scene_html(results.scenes[i], viewer)); !written)
      return written;
  }
  if (auto written = write_file_atomically(report_dir / "junit.xml", junit_xml(results)); !written) return written;
  if (auto written = write_file_atomically(report_dir / "results.json", results_json(results)); !written)
    return written;
  if (auto written = write_file_atomically(report_dir / "index.html", index_html(results)); !written) return written;
  std::vector<std::string> files = files_of(results, pages);
  files.insert(files.end(), pixel_scripts.begin(), pixel_scripts.end());
  remove_stale(report_dir, files);
  std::string list;
  for (const std::string& file : files) list += file + "\n";
  return write_file_atomically(report_dir / kWrittenList, list);
}

}  // namespace xshade::harness
