#include "harness/report/report.h"

#include <string_view>
#include <system_error>
#include <vector>

#include "base/file_io.h"
#include "harness/report/junit_report.h"
#include "harness/report/report_html.h"
#include "harness/report/results_json.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;


}  // namespace

Result<void> write_reports(const RunResults& results, const fs::path& report_dir) {
  std::error_code error;
  fs::create_directories(report_dir, error);
  if (error) return fail("cannot create the report folder " + report_dir.string() + ": " + error.message());

  const std::vector<std::string> pages = scene_page_names(results);
  for (size_t i = 0; i < results.scenes.size(); ++i) {
    if (auto written = write_file_atomically(report_dir / pages[i], scene_html(results.scenes[i])); !written) return written;
  }
  if (auto written = write_file_atomically(report_dir / "junit.xml", junit_xml(results)); !written) return written;
  if (auto written = write_file_atomically(report_dir / "results.json", results_json(results)); !written) return written;
  return write_file_atomically(report_dir / "index.html", index_html(results));
}

}  // namespace xshade::harness
