#include "accuracy/accuracy_report.h"

#include <fmt/core.h>

#include <cmath>

#include "accuracy/pareto_chart.h"
#include "base/markup.h"
#include "harness/report/report_text.h"

namespace xshade::accuracy {
namespace {

std::string ms(double value) { return fmt::format("{:.2f}", value); }

std::vector<const StudyResult*> results_of(const AccuracyRun& run, const std::string& study) {
  std::vector<const StudyResult*> results;
  for (const StudyResult& result : run.results)
    if (result.study == study) results.push_back(&result);
  return results;
}

struct Row {
  std::string configuration, lane, max, mean, rmse, rmse8, psnr, beyond, time, compile;
};

std::vector<Row> rows_of(const Study& study, const AccuracyRun& run) {
  std::vector<Row> rows;
  for (size_t c = 0; c < study.configurations.size(); ++c)
    for (const StudyResult* result : results_of(run, study.id))
      for (const ConfigurationResult& measured : result->configurations)
        if (measured.label == study.configurations[c].label) {
          const auto& e = measured.error;
          rows.push_back(
              {measured.label, std::string(harness::lane_name(result->lane)), fmt::format("{:.4g}", e.max_difference),
               fmt::format("{:.3g}", e.mean), fmt::format("{:.3g}", e.rmse),
               fmt::format("{:.3g}", chart_error(measured)), harness::describe_psnr(e.psnr),
               fmt::format("{:.2f}%", 100.0 * measured.failing_fraction),
               fmt::format("{} ({}-{})", ms(measured.time.median_ms), ms(measured.time.q1_ms), ms(measured.time.q3_ms)),
               ms(measured.compile_ms)});
        }
  return rows;
}

std::string convergence_line(const StudyResult& result, const Study& study) {
  const std::optional<Convergence> c = convergence(result);
  if (!c || !study.reference_check) return {};
  return fmt::format("{}: {} against the reference: RMSE {:.3g} sRGB steps; the smallest error it judges: {:.3g}: {}",
                     harness::lane_name(result.lane), study.reference_check->label, c->check_error, c->smallest_error,
                     c->converged ? "converged" : "NOT converged");
}

}  // namespace

// In 8-bit sRGB steps, as a viewer sees the image: linear errors are dominated by a few
// highlights far above 1, which the display clips. PSNR = 20 log10(255 / RMSE) on those images.
double chart_error(const ConfigurationResult& result) {
  return std::isinf(result.error.psnr) ? 0.0 : 255.0 * std::pow(10.0, -result.error.psnr / 20.0);
}

std::optional<Convergence> convergence(const StudyResult& result) {
  if (!result.reference_check) return std::nullopt;
  Convergence c;
  c.check_error = chart_error(*result.reference_check);
  c.smallest_error = INFINITY;
  for (const ConfigurationResult& measured : result.configurations)
    if (chart_error(measured) > 0.0) c.smallest_error = std::min(c.smallest_error, chart_error(measured));
  c.converged = c.check_error < c.smallest_error;
  return c;
}

std::string study_chart_svg(const Study& study, const AccuracyRun& run) {
  std::vector<ChartSeries> series;
  for (const StudyResult* result : results_of(run, study.id)) {
    ChartSeries lane{std::string(harness::lane_name(result->lane)), {}};
    for (const ConfigurationResult& measured : result->configurations)
      lane.points.push_back({measured.label, measured.time.median_ms, (measured.time.q3_ms - measured.time.q1_ms) / 2.0,
                             chart_error(measured)});
    series.push_back(std::move(lane));
  }
  ChartOptions options;
  options.title = fmt::format("{}: {} (scene {})", study.id, study.knob, study.scene);
  options.x_label = study.timed_passes == "scene"
                        ? "scene pass time, median over frames (ms)"
                        : "time of the " + study.timed_passes.substr(0, study.timed_passes.size() - 1) +
                              " passes, median over frames (ms)";
  options.y_label = "RMSE against " + study.reference.label + " (8-bit sRGB steps)";
  return pareto_chart_svg(series, options);
}

std::string accuracy_csv(const AccuracyRun& run) {
  std::string csv =
      "study,configuration,lane,max_difference,mean_difference,rmse,psnr_db,beyond_tolerance,median_ms,q1_ms,q3_ms,"
      "repetitions,compile_ms\n";
  for (const StudyResult& result : run.results)
    for (const ConfigurationResult& m : result.configurations)
      csv += fmt::format("{},\"{}\",{},{:.6g},{:.6g},{:.6g},{:.3f},{:.6f},{:.4f},{:.4f},{:.4f},{},{:.3f}\n",
                         result.study, m.label, harness::lane_name(result.lane), m.error.max_difference, m.error.mean,
                         m.error.rmse, m.error.psnr, m.failing_fraction, m.time.median_ms, m.time.q1_ms, m.time.q3_ms,
                         m.time.repetitions, m.compile_ms);
  return csv;
}

std::string accuracy_markdown(const AccuracyRun& run, const std::string& chart_dir) {
  std::string md = harness::generated_markdown_head("What accuracy costs", run.command_line, run.drivers);
  md += fmt::format(
      "\nFor each knob of SHADERS.md section 6, a scene is rendered on each lane in every configuration and in a "
      "reference configuration. Error: against the reference on the same lane, in linear values (max, mean "
      "absolute, RMSE: dominated by the few highlights far above 1), and on the 8-bit sRGB images a viewer sees "
      "(RMSE in steps, which the charts plot, and PSNR), and the share of pixels beyond the scene's tolerance. "
      "Time: of the passes the knob changes, wall time of each pass run to completion (glFinish or a fence), "
      "median and interquartile range over {} rounds x {} frames: the configurations take turns, round after "
      "round, each turn after {} untimed warm-up frame, so that a slow spell of the machine falls on all of them; "
      "every configuration is measured in the same run on the same machine. Compile: every variant "
      "of the configuration, from source, no cache. These are CPU drivers: time is llvmpipe's, on a shared "
      "machine; read differences smaller than the interquartile ranges as noise. fp16 emulation rounds in extra "
      "instructions, so on these drivers half costs time; on a GPU with fp16 arithmetic it saves time.\n",
      run.options.rounds, run.options.frames_per_round, run.options.warmup_frames);
  for (const Study& study : run.studies) {
    const std::vector<const StudyResult*> results = results_of(run, study.id);
    if (results.empty()) continue;
    md += fmt::format("\n## {}: {}\n\nScene `{}`. Reference: {}; {}\n\n", study.id, study.knob, study.scene,
                      study.reference.label, study.why_reference);
    md += fmt::format("![{}]({}/{}.svg)\n\n", study.id, chart_dir, study.id);
    if (!study.findings.empty()) md += study.findings + "\n\n";
    for (const StudyResult* result : results) {
      if (std::string line = convergence_line(*result, study); !line.empty()) md += "- " + line + "\n";
      for (const std::string& skipped : result->skipped)
        md += fmt::format("- {}: not run: {}\n", harness::lane_name(result->lane), skipped);
    }
    md +=
        "\n| configuration | lane | max | mean | RMSE | RMSE, sRGB steps | PSNR | beyond tolerance | time ms, median "
        "(IQR) | "
        "compile ms |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows_of(study, run))
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.configuration, r.lane, r.max, r.mean,
                        r.rmse, r.rmse8, r.psnr, r.beyond, r.time, r.compile);
  }
  return md;
}

std::string accuracy_html(const AccuracyRun& run, const std::string& chart_dir) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>xshade accuracy</title>\n"
      "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
      "padding:2px 6px;text-align:right}td:first-child,td:nth-child(2){text-align:left}</style>\n</head>\n<body>\n"
      "<h1>What accuracy costs</h1>\n";
  html += "<p>" + escape_text(run.command_line) + "</p>\n<ul>\n";
  for (const auto& [lane, driver] : run.drivers)
    html += fmt::format("<li>{}: {}</li>\n", escape_text(harness::lane_name(lane)),
                        escape_text(driver.renderer + ", " + driver.api_version));
  html += "</ul>\n";
  for (const Study& study : run.studies) {
    if (results_of(run, study.id).empty()) continue;
    html += fmt::format("<h2>{}: {}</h2>\n<p>Scene {}. Reference: {}; {}</p>\n", escape_text(study.id),
                        escape_text(study.knob), escape_text(study.scene), escape_text(study.reference.label),
                        escape_text(study.why_reference));
    html += fmt::format("<img src=\"{}/{}.svg\" alt=\"{}\">\n<p>{}</p>\n<ul>\n", url_path(chart_dir),
                        url_path(study.id), escape_attribute(study.id), escape_text(study.findings));
    for (const StudyResult* result : results_of(run, study.id))
      if (std::string line = convergence_line(*result, study); !line.empty())
        html += "<li>" + escape_text(line) + "</li>\n";
    html +=
        "</ul>\n<table>\n<tr><th>configuration</th><th>lane</th><th>max</th><th>mean</th><th>RMSE</th>"
        "<th>RMSE, sRGB steps</th><th>PSNR</th><th>beyond tolerance</th><th>time ms, median (IQR)</th><th>compile "
        "ms</th></tr>\n";
    for (const Row& r : rows_of(study, run))
      html += fmt::format(
          "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</"
          "td><td>{}</td></tr>\n",
          escape_text(r.configuration), escape_text(r.lane), r.max, r.mean, r.rmse, r.rmse8, r.psnr, r.beyond, r.time,
          r.compile);
    html += "</table>\n";
  }
  return html + "</body>\n</html>\n";
}

}  // namespace xshade::accuracy
