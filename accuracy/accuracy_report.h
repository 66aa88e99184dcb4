// What `xshade accuracy` writes: per study a table (Markdown, CSV) and a Pareto chart (SVG),
// an HTML page with both, and docs/accuracy.md.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "accuracy/measure.h"
#include "harness/backend/backend.h"

namespace xshade::accuracy {

struct AccuracyRun {
  std::vector<Study> studies;
  std::vector<StudyResult> results;  // study by study, lane by lane
  std::vector<std::pair<harness::Lane, harness::DriverInfo>> drivers;
  std::string command_line;
  MeasureOptions options;
};

// The error the charts plot and the tables sort by.
double chart_error(const ConfigurationResult& result);

// Does the reference converge: its check differs from it by less than the smallest non-zero
// error among the configurations it judges (on the same lane)? Empty when there is no check.
struct Convergence {
  double check_error = 0.0;
  double smallest_error = 0.0;
  bool converged = true;
};
std::optional<Convergence> convergence(const StudyResult& result);

std::string study_chart_svg(const Study& study, const AccuracyRun& run);
std::string accuracy_csv(const AccuracyRun& run);
// `chart_dir` is where the charts are, relative to the Markdown or HTML file.
std::string accuracy_markdown(const AccuracyRun& run, const std::string& chart_dir);
std::string accuracy_html(const AccuracyRun& run, const std::string& chart_dir);

}  // namespace xshade::accuracy
