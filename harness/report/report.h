// The run's reports, written into the report folder beside the images the run put there:
// index.html and one <scene>.html per scene (report_html.h), junit.xml (junit_report.h) and
// results.json (results_json.h).
#pragma once

#include <filesystem>
#include <vector>

#include "base/result.h"
#include "harness/gate/run_results.h"
#include "harness/report/viewer_data.h"

namespace xshade::harness {

// Creates `report_dir` if needed. Each file is written to a temporary file beside it and renamed
// into place, so an interrupted run leaves either the previous report or the new one, never half
// of a file. index.html is written after the pages: when it is there, the pages it links to are
// too. Then the pages and images an earlier run into the same folder wrote and this one did not
// are removed (the folder's .xshade-report-files lists what each run wrote; nothing else is).
//
// `viewers`, when given, holds each scene's viewer data (viewer_data.h) in the order of
// results.scenes, made as the run went; otherwise it is made here from the report folder. With
// `viewers`, `written_already` marks the scenes whose page and pixel scripts the folder holds as
// they are from an earlier write (xshade watch writes again only the scenes a save reached); the
// index, junit.xml and results.json are always written whole.
Result<void> write_reports(const RunResults& results, const std::filesystem::path& report_dir,
                           const std::vector<ViewerPage>* viewers = nullptr,
                           const std::vector<bool>* written_already = nullptr);

}  // namespace xshade::harness
