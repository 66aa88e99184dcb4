// What the verbs that check scenes and write a report (run and watch) share.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/folders.h"

#include "harness/gate/scene_check.h"
#include "harness/report/viewer_data.h"

namespace xshade::cli {

// What a verb that checks scenes works on: the lanes asked for, the folders and the scene files.
struct SceneRunInputs {
  std::vector<harness::Lane> lanes;
  SceneFolders folders;
  std::vector<std::filesystem::path> files;
};
// The lanes, folders and scene files named on the command line, resolved; an error is the
// command line's or its files' (exit 2).
Result<SceneRunInputs> resolve_scene_run(const LaneSelection& selection, const FolderOptions& folders,
                                         const std::vector<std::string>& scenes, GoldenUse golden);

// The time now as ISO 8601 UTC, "2026-12-07T04:28:24Z", for a run's record.
std::string utc_now();

// A scene's lanes' longer messages (a compile's diagnostics with their carets) on stderr, under
// `verb`; lanes that failed alike say so instead of repeating it. The progress line shows only
// a lane's first line.
void print_lane_details(const std::string& verb, const harness::SceneResult& scene);

// The scene page's viewer data, from the renders in hand (not read back from the report).
harness::ViewerPage viewer_page_of(const harness::CheckedScene& checked, const std::filesystem::path& report_dir);

}  // namespace xshade::cli
