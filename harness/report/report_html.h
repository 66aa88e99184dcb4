// The run as static HTML: an index of every scene and lane, and one page per scene with its
// images side by side. Self-contained (inline CSS, no script, nothing fetched), so that the report
// folder can be opened from disk or served as it is by any CI artifact viewer.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "harness/gate/run_results.h"
#include "harness/report/viewer_data.h"

namespace xshade::harness {

// The file name of each scene's page, in the order of results.scenes: the scene name with
// anything but letters, digits, '.', '_' and '-' made '_', then ".html"; made unique (also
// ignoring case, for case-insensitive file systems) and never "index.html".
std::vector<std::string> scene_page_names(const RunResults& results);

// index.html: when, how long, the command and the counts; a table of scene x lane with the
// cross-lane verdicts, the scenes that did not pass first, each failing cell saying why.
std::string index_html(const RunResults& results);

// A scene's page: the image-diff viewer (golden, output and heat map of each group of lanes that
// rendered alike, viewer_data.h), each lane's layers, metrics, timings, driver, files and
// non-finite mask, the cross-lane comparisons and the plan. Image paths are the model's,
// relative to the report folder the page is written to, as are the viewer's pixel scripts
// (pixel_script_path).
std::string scene_html(const SceneResult& scene, const ViewerPage& viewer);

// The image-diff viewer (viewer/viewer.js and viewer.css, compiled in) that every scene page
// loads from beside itself: written once a report, not into each of its thousands of pages.
inline constexpr const char* kViewerScriptFile = "viewer.js";
inline constexpr const char* kViewerStyleFile = "viewer.css";
std::string_view viewer_script();
std::string_view viewer_style();

}  // namespace xshade::harness
