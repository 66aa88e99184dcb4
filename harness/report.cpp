#include "harness/report.h"

#include <fstream>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "harness/junit_report.h"
#include "harness/report_html.h"
#include "harness/results_json.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

Result<void> write_atomically(const fs::path& path, std::string_view text) {
  // Beside the target, so that the rename stays within one file system and is atomic.
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (file) file.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (file) file.close();
    if (!file) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      return fail("cannot write the report file " + temporary.string());
    }
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return fail("cannot write the report file " + path.string() + ": " + error.message());
  }
  return {};
}

}  // namespace

Result<void> write_reports(const RunResults& results, const fs::path& report_dir) {
  std::error_code error;
  fs::create_directories(report_dir, error);
  if (error) return fail("cannot create the report folder " + report_dir.string() + ": " + error.message());

  const std::vector<std::string> pages = scene_page_names(results);
  for (size_t i = 0; i < results.scenes.size(); ++i) {
    if (auto written = write_atomically(report_dir / pages[i], scene_html(results.scenes[i])); !written) return written;
  }
  if (auto written = write_atomically(report_dir / "junit.xml", junit_xml(results)); !written) return written;
  if (auto written = write_atomically(report_dir / "results.json", results_json(results)); !written) return written;
  return write_atomically(report_dir / "index.html", index_html(results));
}

}  // namespace xshade::harness
