#include "harness/report/report_html.h"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <numeric>
#include <set>

#include <fmt/format.h>

#include "base/markup.h"
#include "harness/report/report_text.h"
#include "viewer_assets.h"

namespace xshade::harness {
namespace {

// Colour says the verdict at a glance, and the verdict is always also written out, for readers
// who cannot tell the colours apart.
constexpr std::string_view kStyle = R"css(
:root { --pass: #1a7f37; --pass-bg: #dafbe1; --fail: #cf222e; --fail-bg: #ffebe9;
        --error: #9a6700; --error-bg: #fff8c5; --crash: #82071e; --crash-bg: #ffcecb;
        --skipped: #57606a; --skipped-bg: #eaeef2; --line: #d0d7de; --muted: #57606a; }
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", Helvetica, Arial, sans-serif;
       color: #1f2328; margin: 0 24px 48px; }
h1 { font-size: 22px; margin: 0 0 8px; } h2 { font-size: 18px; margin: 0 0 8px; }
h3 { font-size: 13px; margin: 0 0 4px; text-transform: uppercase; letter-spacing: .04em; color: var(--muted); }
a { color: #0969da; }
code, pre, .mono { font-family: ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; font-size: 12px; }
.swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid var(--line); }
pre { background: #f6f8fa; border: 1px solid var(--line); padding: 8px 12px; overflow: auto;
      white-space: pre-wrap; word-break: break-word; }
header { padding: 16px 20px; margin: 16px -24px 20px; border-bottom: 1px solid var(--line);
         border-left: 8px solid var(--skipped); background: #f6f8fa; }
header.v-pass { border-left-color: var(--pass); } header.v-fail { border-left-color: var(--fail); }
header.v-error { border-left-color: var(--error); } header.v-crash { border-left-color: var(--crash); }
nav { margin-top: 12px; }
dl.facts { display: grid; grid-template-columns: max-content auto; gap: 2px 12px; margin: 8px 0; }
dl.facts dt { color: var(--muted); } dl.facts dd { margin: 0; }
.badge { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 12px; font-weight: 700;
         vertical-align: middle; border: 1px solid currentColor; }
.verdict.v-pass, .badge.v-pass { color: var(--pass); background: var(--pass-bg); }
.verdict.v-fail, .badge.v-fail { color: var(--fail); background: var(--fail-bg); }
.verdict.v-error, .badge.v-error { color: var(--error); background: var(--error-bg); }
.verdict.v-crash, .badge.v-crash { color: var(--crash); background: var(--crash-bg); }
.verdict.v-skipped, .badge.v-skipped { color: var(--skipped); background: var(--skipped-bg); }
.verdict { font-weight: 700; }
.counts .badge { margin-right: 4px; }
table { border-collapse: collapse; margin: 0 0 12px; }
th, td { border: 1px solid var(--line); padding: 4px 8px; text-align: left; vertical-align: top; }
th { background: #f6f8fa; font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
table.index td.cell { padding: 0; min-width: 90px; max-width: 360px; }
table.index td.cell > a, table.index td.cell > span { display: block; padding: 4px 8px; color: inherit;
                                                      text-decoration: none; }
table.index td.cell > a:hover { text-decoration: underline; }
td.cell.v-pass { background: var(--pass-bg); } td.cell.v-fail { background: var(--fail-bg); }
td.cell.v-error { background: var(--error-bg); } td.cell.v-crash { background: var(--crash-bg); }
td.cell.v-skipped, td.cell.absent { background: var(--skipped-bg); color: var(--muted); }
tr.problem td.scene { border-left: 6px solid var(--fail); }
tr.problem.row-error td.scene { border-left-color: var(--error); }
tr.problem.row-crash td.scene { border-left-color: var(--crash); }
td.scene a { font-weight: 600; }
tr.separator td { background: #fff; border-left: none; border-right: none; padding: 14px 0 4px;
                  color: var(--muted); font-weight: 600; }
.detail { display: block; font-size: 12px; color: #1f2328; font-weight: normal; white-space: pre-wrap;
          word-break: break-word; }
.description { color: var(--muted); font-size: 12px; }
.pair { padding: 2px 0; }
section { margin: 0 0 28px; }
section.lane { border: 1px solid var(--line); border-left: 6px solid var(--skipped); padding: 12px 16px; }
section.lane.v-pass { border-left-color: var(--pass); } section.lane.v-fail { border-left-color: var(--fail); }
section.lane.v-error { border-left-color: var(--error); } section.lane.v-crash { border-left-color: var(--crash); }
p.why { font-weight: 600; margin: 0 0 10px; }
.images { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; margin: 0 0 12px; }
figure { margin: 0; }
figure img { display: block; image-rendering: pixelated; border: 1px solid var(--line);
             background: repeating-conic-gradient(#eee 0 25%, #fff 0 50%) 0 0 / 16px 16px; }
figcaption { font-size: 12px; color: var(--muted); margin-top: 2px; max-width: 320px; word-break: break-all; }
figcaption b { color: #1f2328; }
.placeholder { box-sizing: border-box; width: 192px; min-height: 128px; padding: 12px; border: 2px dashed var(--line);
               color: var(--muted); font-size: 12px; word-break: break-word; white-space: pre-wrap; }
.tables { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
.message { border-left: 4px solid var(--error); }
.warnings { border-left: 4px solid var(--skipped); }
.thumbs { display: flex; gap: 4px; margin-bottom: 2px; }
img.thumb { display: block; width: 64px; height: auto; max-height: 64px; object-fit: contain; image-rendering: auto;
            border: 1px solid var(--line); background: #fff; }
p.filter button { font: inherit; font-size: 12px; padding: 2px 10px; border: 1px solid var(--line); border-radius: 12px;
                  background: #fff; cursor: pointer; }
p.filter button[aria-pressed="true"] { background: #0969da; border-color: #0969da; color: #fff; }
table.index:not([data-show="all"]) tr.separator { display: none; }
table.index[data-show="problem"] tbody tr:not(.problem),
table.index[data-show="fail"] tbody tr:not(.row-fail), table.index[data-show="error"] tbody tr:not(.row-error),
table.index[data-show="crash"] tbody tr:not(.row-crash), table.index[data-show="pass"] tbody tr:not(.row-pass),
table.index[data-show="skipped"] tbody tr:not(.row-skipped) { display: none; }
p.files { font-size: 12px; color: var(--muted); margin: 0 0 8px; }
details.runs { margin: 12px 0; font-size: 12px; }
details.runs ul { margin: 4px 0; padding-left: 18px; }
.decides { color: var(--muted); font-size: 12px; }
)css";

std::string verdict_class(Verdict verdict) { return "v-" + std::string(verdict_name(verdict)); }

std::string verdict_word(Verdict verdict) {
  std::string word(verdict_name(verdict));
  for (char& c : word) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return word;
}

std::string verdict_span(Verdict verdict) {
  return fmt::format(R"(<span class="verdict {}">{}</span>)", verdict_class(verdict), verdict_word(verdict));
}

std::string badge(Verdict verdict) {
  return fmt::format(R"(<span class="badge {}">{}</span>)", verdict_class(verdict), verdict_word(verdict));
}

std::string page_start(std::string_view title) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n"
      "<style>{}</style>\n</head>\n<body>\n",
      escape_text(title), kStyle);
}

constexpr std::string_view kPageEnd = "</body>\n</html>\n";

// Letters, digits, '.', '_' and '-' as they are, anything else '_': safe as a file name and as a
// fragment identifier.
std::string safe_name(std::string_view name) {
  std::string out;
  for (const char c : name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    out += keep ? c : '_';
  }
  return out.empty() ? "scene" : out;
}

std::string lane_anchor(std::string_view lane) { return "lane-" + safe_name(lane); }

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string counts_html(const VerdictCounts& counts) {
  std::string out = fmt::format("{} — ", counts.total());
  const auto add = [&](Verdict verdict, size_t count, bool always) {
    if (count == 0 && !always) return;
    out += fmt::format(R"(<span class="badge {}">{} {}</span>)", verdict_class(verdict), count, verdict_name(verdict));
  };
  add(Verdict::Pass, counts.pass, true);
  add(Verdict::Fail, counts.fail, true);
  add(Verdict::Error, counts.error, true);
  add(Verdict::Crash, counts.crash, false);
  add(Verdict::Skipped, counts.skipped, false);
  return out;
}

// Every lane name of the run, in the order the scenes first name them: the index's columns.
std::vector<std::string> lane_columns(const RunResults& results) {
  std::vector<std::string> lanes;
  for (const SceneResult& scene : results.scenes)
    for (const LaneResult& lane : scene.lanes)
      if (std::find(lanes.begin(), lanes.end(), lane.lane) == lanes.end()) lanes.push_back(lane.lane);
  return lanes;
}

// What decides the scene's comparisons, in a few words: its metric and threshold, or the
// per-pixel layer's tolerance.
std::string deciding_comparison(const CompareSettings& compare) {
  if (compare.metric) {
    const MetricSettings& metric = *compare.metric;
    switch (metric.metric) {
      case Metric::Flip: return fmt::format("FLIP mean ≤ {:g}", metric.threshold);
      case Metric::Ssim: return fmt::format("SSIM mean ≥ {:g}", metric.threshold);
      case Metric::DeltaE:
        return fmt::format("ΔE00 above {:g}: average ≤ {:g}, pixels ≤ {:g}%", metric.pixel_threshold, metric.threshold,
                           100.0 * metric.incorrect_fraction);
    }
  }
  std::string text = fmt::format("per pixel ±{} sRGB {}", compare.channel_tolerance,
                                 compare.channel_tolerance == 1 ? "step" : "steps");
  if (compare.max_failing_fraction > 0.0) text += fmt::format(", {:g}% may fail", 100.0 * compare.max_failing_fraction);
  if (compare.position_radius > 0) text += fmt::format(", within {} px", compare.position_radius);
  return text;
}

void index_row(std::string& out, const SceneResult& scene, const std::string& page,
               const std::vector<std::string>& lanes) {
  auto to = std::back_inserter(out);
  const std::string href = escape_attribute(url_path(page));
  fmt::format_to(to, "<tr class=\"{}row-{}\">\n", is_problem(scene.verdict) ? "problem " : "",
                 verdict_name(scene.verdict));
  fmt::format_to(to, "<td class=\"scene\"><a href=\"{}\">{}</a>", href, escape_text(scene.scene));
  if (!scene.description.empty())
    fmt::format_to(to, "<span class=\"description detail\">{}</span>", escape_text(scene.description));
  fmt::format_to(to, "<span class=\"decides detail\">compared by {}</span>",
                 escape_text(deciding_comparison(scene.compare)));
  fmt::format_to(to, "</td>\n<td class=\"cell {0}\"><a href=\"{1}\">{2}</a></td>\n", verdict_class(scene.verdict), href,
                 verdict_span(scene.verdict));
  if (scene.lanes.empty() && !scene.message.empty()) {
    // The scene stopped before any lane ran: one cell across the lanes says why.
    fmt::format_to(
        to, "<td class=\"cell {}\" colspan=\"{}\"><a href=\"{}\"><span class=\"detail\">{}</span></a></td>\n",
        verdict_class(scene.verdict), std::max<size_t>(lanes.size(), 1), href, escape_text(first_line(scene.message)));
  } else {
    for (const std::string& name : lanes) {
      const auto lane =
          std::find_if(scene.lanes.begin(), scene.lanes.end(), [&](const LaneResult& l) { return l.lane == name; });
      if (lane == scene.lanes.end()) {
        out += "<td class=\"cell absent\"><span>—</span></td>\n";
        continue;
      }
      fmt::format_to(to, "<td class=\"cell {}\"><a href=\"{}#{}\">", verdict_class(lane->verdict), href,
                     lane_anchor(lane->lane));
      // The lane's image, and beside it the heat map where it did not pass, at a glance.
      if (!lane->image.empty() || (is_problem(lane->verdict) && !lane->diff.empty())) {
        out += "<span class=\"thumbs\">";
        for (const std::string* image : {&lane->image, is_problem(lane->verdict) ? &lane->diff : nullptr})
          if (image && !image->empty())
            fmt::format_to(to, "<img class=\"thumb\" src=\"{}\" alt=\"\" loading=\"lazy\">",
                           escape_attribute(url_path(*image)));
        out += "</span>";
      }
      out += verdict_span(lane->verdict);
      if (is_problem(lane->verdict))
        fmt::format_to(to, "<span class=\"detail\">{}</span>", escape_text(first_line(first_failure(*lane))));
      out += "</a></td>\n";
    }
    if (lanes.empty()) out += "<td class=\"cell absent\"><span>—</span></td>\n";
  }
  out += "<td class=\"cross\">";
  for (const CrossLaneResult& pair : scene.cross_lane) {
    fmt::format_to(to, "<div class=\"pair\"><a href=\"{}#cross-lane\">{}</a> {}", href, escape_text(pair_name(pair)),
                   verdict_span(pair.verdict));
    if (is_problem(pair.verdict))
      fmt::format_to(to, "<span class=\"detail\">{}</span>", escape_text(describe_metrics(pair.metrics)));
    out += "</div>";
  }
  if (scene.cross_lane.empty()) out += "<span class=\"description\">—</span>";
  out += "</td>\n</tr>\n";
}

// One image with a link to its full file, or a placeholder saying why there is none.
std::string figure(std::string_view caption, const std::string& path, std::string_view missing) {
  if (path.empty()) {
    return fmt::format("<figure><div class=\"placeholder\">{}</div><figcaption><b>{}</b></figcaption></figure>\n",
                       escape_text(missing), escape_text(caption));
  }
  const std::string url = escape_attribute(url_path(path));
  return fmt::format(
      "<figure><a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\"></a><figcaption><b>{2}</b><br>{3}</figcaption></figure>\n",
      url, escape_attribute(caption), escape_text(caption), escape_text(path));
}

std::string fact_row(std::string_view name, std::string_view value) {
  return fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", escape_text(name), escape_text(value));
}

// Where the lane's non-finite values were born (the tracing variant): per pass, each site with
// its pixels, its first pixel, its source line with a caret and the calls that led there, and
// the map of the pixels in each site's colour.
std::string trace_section(const NonfiniteTraceResult& trace) {
  std::string out = "<div class=\"trace\"><h3>Where the non-finite values were born</h3>\n";
  auto to = std::back_inserter(out);
  if (!trace.note.empty()) {
    fmt::format_to(to, "<p class=\"description\">not traced: {}</p>\n</div>\n", escape_text(trace.note));
    return out;
  }
  const double ratio = trace.plain_milliseconds > 0 ? trace.traced_milliseconds / trace.plain_milliseconds : 0.0;
  fmt::format_to(to,
                 "<p class=\"description\">The lane rendered again with the tracing variant: {:.0f} ms (the plain "
                 "render's passes {:.0f} ms, {:.1f}x); the traced image is {}.</p>\n",
                 trace.traced_milliseconds, trace.plain_milliseconds, ratio,
                 trace.identical ? "bit-identical to the plain one"
                                 : "NOT bit-identical to the plain one (" + trace.traced_image +
                                       "): a fault of the tracing variant");
  for (const PassOrigins& pass : trace.passes) {
    fmt::format_to(to, "<h4>{} {}</h4>\n", pass.output ? "Output pass" : "Earlier pass", escape_text(pass.pass));
    if (pass.origins.empty() && !pass.unattributed_pixels)
      out += "<p class=\"description\">no pixel is non-finite</p>\n";
    if (!pass.origins.empty()) {
      out +=
          "<table class=\"origins\">\n<tr><th></th><th>pixels</th><th>NaN</th><th>Inf</th><th>negative</th><th>first "
          "at</th><th>site</th></tr>\n";
      for (size_t i = 0; i < pass.origins.size(); ++i) {
        const NonfiniteOrigin& origin = pass.origins[i];
        const glm::vec4 color = origins_palette(i);
        const glsl::TraceSite& site = origin.site;
        std::string where = fmt::format("{}:{}:{}: {} in {}", site.file, site.line, site.column,
                                        glsl::describe_site(site), site.function);
        std::string source = site.source_line;
        if (!source.empty()) source += "\n" + std::string(site.column > 0 ? site.column - 1 : 0, ' ') + "^";
        for (const glsl::TraceCall& call : origin.calls)
          source += fmt::format("\ncalled from {} at {}:{}:{}", call.caller, call.file, call.line, call.column);
        if (origin.calls.size() == glsl::NonfiniteTrace::kRecordedCalls)
          source += "\n(calls further out are not recorded)";
        fmt::format_to(to,
                       "<tr><td><span class=\"swatch\" style=\"background: rgb({}, {}, {})\"></span></td><td>{}</td>"
                       "<td>{}</td><td>{}</td><td>{}</td><td>({}, {})</td><td>{}<pre>{}</pre></td></tr>\n",
                       int(color.r * 255), int(color.g * 255), int(color.b * 255), origin.pixels, origin.nan,
                       origin.inf, origin.negative, origin.first_x, origin.first_y, escape_text(where),
                       escape_text(source));
      }
      out += "</table>\n";
    }
    if (pass.unattributed_pixels)
      fmt::format_to(to,
                     "<p class=\"description\">{} pixels non-finite with no site recorded (drawn by no traced "
                     "program)</p>\n",
                     pass.unattributed_pixels);
    if (pass.recovered_pixels)
      fmt::format_to(to,
                     "<p class=\"description\">{} pixels had a NaN or infinity on the way that did not reach the "
                     "pass's output</p>\n",
                     pass.recovered_pixels);
    if (!pass.map.empty()) out += "<div class=\"images\">\n" + figure("origins by site", pass.map, "") + "</div>\n";
  }
  out += "</div>\n";
  return out;
}

// In the per-pixel layer's domain, 8-bit sRGB steps, as the table says; values above 1 in the
// float layer's, relative error.
std::string metrics_table(const ImageMetrics& metrics) {
  std::string out = "<table class=\"metrics\">\n";
  out += fact_row("domain", "8-bit sRGB steps, as the per-pixel layer compares");
  out += fact_row("worst", fmt::format("{} steps at ({}, {})", metrics.max_steps, metrics.worst_x, metrics.worst_y));
  if (metrics.first_failing)
    out +=
        fact_row("first failing", fmt::format("({}, {})", metrics.first_failing->first, metrics.first_failing->second));
  out += fact_row("mean", fmt::format("{:.4g} steps", metrics.mean_steps));
  out += fact_row("RMSE", fmt::format("{:.4g} steps", metrics.rmse_steps));
  out += fact_row("PSNR", describe_psnr(metrics.psnr));
  out +=
      fact_row("failing pixels", fmt::format("{} ({:.4g}%)", metrics.failing_pixels, metrics.failing_fraction * 100.0));
  if (metrics.hdr_values > 0)
    out += fact_row("above 1 (relative)",
                    fmt::format("worst {:.4g} at ({}, {}); {} failing pixels", metrics.float_max_relative,
                                metrics.float_x, metrics.float_y, metrics.float_failing_pixels));
  return out + "</table>\n";
}

void lane_section(std::string& out, const LaneResult& lane) {
  auto to = std::back_inserter(out);
  fmt::format_to(to, "<section class=\"lane {}\" id=\"{}\">\n<h2>{} {}</h2>\n", verdict_class(lane.verdict),
                 lane_anchor(lane.lane), escape_text(lane.lane), badge(lane.verdict));
  if (const std::string why = first_failure(lane); !why.empty())
    fmt::format_to(to, "<p class=\"why\">{}</p>\n", escape_text(first_line(why)));

  // The images themselves are in the viewer above; here, the files, and the mask of non-finite
  // values, which the viewer does not show.
  std::string files;
  const auto file_link = [&](std::string_view what, const std::string& path) {
    if (path.empty()) return;
    files += fmt::format("{}<a href=\"{}\">{}</a>", files.empty() ? "" : " · ", escape_attribute(url_path(path)),
                         escape_text(what));
  };
  file_link("image (PNG)", lane.image);
  file_link("float image (EXR)", lane.image_exr);
  file_link("golden (PNG)", lane.golden);
  file_link("golden (EXR)", lane.golden_exr);
  file_link("heat map", lane.diff);
  if (!files.empty()) fmt::format_to(to, "<p class=\"files\">Files: {}</p>\n", files);
  if (lane.image.empty()) out += "<p class=\"description\">not rendered</p>\n";
  if (lane.non_finite.total() > 0 || !lane.non_finite_mask.empty())
    out += "<div class=\"images\">\n" + figure("NaN / Inf / negative", lane.non_finite_mask, "no mask written") +
           "</div>\n";
  if (lane.trace) out += trace_section(*lane.trace);

  out += "<div class=\"tables\">\n<div><h3>Layers</h3>\n";
  if (lane.layers.empty()) {
    out += "<p class=\"description\">no layer ran</p>\n";
  } else {
    out += "<table class=\"layers\">\n<tr><th>layer</th><th>verdict</th><th>detail</th></tr>\n";
    for (const LayerResult& layer : lane.layers)
      fmt::format_to(to, "<tr><td>{}</td><td class=\"cell {}\">{}</td><td>{}</td></tr>\n", escape_text(layer.layer),
                     verdict_class(layer.verdict), verdict_span(layer.verdict), escape_text(layer.detail));
    out += "</table>\n";
  }
  out += "</div>\n<div><h3>Against the golden</h3>\n";
  out += lane.against_golden ? metrics_table(*lane.against_golden)
                             : std::string("<p class=\"description\">not compared</p>\n");
  out += "</div>\n<div><h3>Non-finite values</h3>\n<table>\n";
  out += fact_row("NaN", std::to_string(lane.non_finite.nan));
  out += fact_row("Inf", std::to_string(lane.non_finite.inf));
  out += fact_row("negative", std::to_string(lane.non_finite.negative));
  if (lane.non_finite.first)
    out += fact_row("first at", fmt::format("({}, {})", lane.non_finite.first->first, lane.non_finite.first->second));
  out += "</table>\n</div>\n<div><h3>Time</h3>\n<table>\n<tr><th>pass</th><th>ms</th></tr>\n";
  for (const PassTime& time : lane.timings)
    fmt::format_to(to, "<tr><td>{}</td><td class=\"num\">{:.2f}</td></tr>\n", escape_text(time.pass),
                   time.milliseconds);
  fmt::format_to(to, "<tr><th>total</th><td class=\"num\">{:.3f} s</td></tr>\n</table>\n</div>\n", lane.seconds);
  out += "<div><h3>Driver</h3>\n<table>\n";
  out += fact_row("api", lane.driver.api);
  out += fact_row("renderer", lane.driver.renderer);
  out += fact_row("api_version", lane.driver.api_version);
  out += fact_row("driver_version", lane.driver.driver_version);
  out += fact_row("llvm_version", lane.driver.llvm_version);
  out += "</table>\n</div>\n</div>\n";
  if (!lane.message.empty())
    fmt::format_to(to, "<h3>Message</h3>\n<pre class=\"message\">{}</pre>\n", escape_text(lane.message));
  out += "</section>\n";
}

void cross_lane_section(std::string& out, const SceneResult& scene) {
  auto to = std::back_inserter(out);
  out += "<section id=\"cross-lane\">\n<h2>Cross-lane agreement</h2>\n";
  if (scene.cross_lane.empty()) {
    out += "<p class=\"description\">no pair of lanes compared</p>\n</section>\n";
    return;
  }
  out +=
      "<table>\n<tr><th>pair</th><th>verdict</th><th>worst, sRGB steps</th><th>mean, steps</th><th>RMSE, steps</th>"
      "<th>PSNR</th><th>failing pixels</th></tr>\n";
  for (const CrossLaneResult& pair : scene.cross_lane) {
    const ImageMetrics& m = pair.metrics;
    if (pair.identical) {
      fmt::format_to(to, "<tr><td>{}</td><td class=\"cell {}\">{}</td><td colspan=\"5\">bit-identical</td></tr>\n",
                     escape_text(pair_name(pair)), verdict_class(pair.verdict), verdict_span(pair.verdict));
      continue;
    }
    fmt::format_to(to,
                   "<tr><td>{}</td><td class=\"cell {}\">{}</td>"
                   "<td class=\"num\">{} at ({}, {})</td><td class=\"num\">{:.4g}</td><td class=\"num\">{:.4g}</td>"
                   "<td class=\"num\">{}</td><td class=\"num\">{} ({:.4g}%)</td></tr>\n",
                   escape_text(pair_name(pair)), verdict_class(pair.verdict), verdict_span(pair.verdict), m.max_steps,
                   m.worst_x, m.worst_y, m.mean_steps, m.rmse_steps, escape_text(describe_psnr(m.psnr)),
                   m.failing_pixels, m.failing_fraction * 100.0);
  }
  out += "</table>\n";
  std::string figures;
  for (const CrossLaneResult& pair : scene.cross_lane)
    if (!pair.identical) figures += figure(pair_name(pair) + ": difference", pair.diff, "no difference image");
  if (!figures.empty()) out += "<div class=\"images\">\n" + figures + "</div>\n";
  out += "</section>\n";
}

// The image-diff viewer (viewer/viewer.js) with its data; without JavaScript, links to the
// images it would show.
void images_section(std::string& out, const SceneResult& scene, const ViewerPage& viewer) {
  auto to = std::back_inserter(out);
  out += "<section id=\"images\">\n<h2>Images</h2>\n<noscript><p>The image viewer needs JavaScript. The images: ";
  for (const LaneResult& lane : scene.lanes)
    for (const auto& [what, path] :
         {std::pair{"", &lane.image}, std::pair{" golden", &lane.golden}, std::pair{" heat map", &lane.diff}})
      if (!path->empty())
        fmt::format_to(to, "<a href=\"{}\">{}{}</a> ", escape_attribute(url_path(*path)), escape_text(lane.lane), what);
  out += "</p></noscript>\n<div id=\"xshade-viewer\"></div>\n";
  fmt::format_to(to, "<script id=\"xshade-viewer-data\" type=\"application/json\">{}</script>\n", viewer.data_json);
  for (const ViewerPage::PixelScript& pixels : viewer.pixels)
    fmt::format_to(to, "<script src=\"{}\"></script>\n", escape_attribute(url_path(pixel_script_path(pixels.image))));
  fmt::format_to(to, "<link rel=\"stylesheet\" href=\"{}\">\n<script src=\"{}\"></script>\n</section>\n",
                 kViewerStyleFile, kViewerScriptFile);
}

}  // namespace

std::vector<std::string> scene_page_names(const RunResults& results) {
  std::vector<std::string> names;
  std::set<std::string> taken = {"index"};  // compared in lower case
  for (const SceneResult& scene : results.scenes) {
    const std::string base = safe_name(scene.scene);
    std::string name = base;
    for (int suffix = 2; taken.count(lower(name)) != 0; ++suffix) name = fmt::format("{}-{}", base, suffix);
    taken.insert(lower(name));
    names.push_back(name + ".html");
  }
  return names;
}

std::string index_html(const RunResults& results) {
  const Verdict verdict = run_verdict(results);
  const std::vector<std::string> pages = scene_page_names(results);
  const std::vector<std::string> lanes = lane_columns(results);

  std::string out = page_start(fmt::format("xshade: {}", verdict_word(verdict)));
  auto to = std::back_inserter(out);
  fmt::format_to(to, "<header class=\"{}\">\n<h1>xshade run {}</h1>\n<dl class=\"facts\">\n", verdict_class(verdict),
                 badge(verdict));
  fmt::format_to(to, "<dt>started</dt><dd>{}</dd>\n", escape_text(results.started));
  fmt::format_to(to, "<dt>took</dt><dd>{}{}</dd>\n", escape_text(describe_duration(results.seconds)),
                 results.merged_from.empty() ? "" : " (the runs' times added)");
  fmt::format_to(to, "<dt>command</dt><dd><code>{}</code></dd>\n", escape_text(results.command));
  // A merged report's runs are listed, folded, below its results: a CTest run merges one per test.
  if (!results.merged_from.empty())
    fmt::format_to(to, "<dt>merged from</dt><dd>{} runs, <a href=\"#runs\">listed below the scenes</a></dd>\n",
                   results.merged_from.size());
  const auto merged_runs = [&] {
    if (results.merged_from.empty()) return;
    fmt::format_to(to, "<details id=\"runs\" class=\"runs\"><summary>The {} runs merged here</summary><ul>\n",
                   results.merged_from.size());
    for (const MergedRun& run : results.merged_from)
      fmt::format_to(to, "<li><span class=\"mono\">{}</span>: <code>{}</code>, {}, {}</li>\n", escape_text(run.folder),
                     escape_text(run.command), escape_text(run.started), escape_text(describe_duration(run.seconds)));
    out += "</ul></details>\n";
  };
  fmt::format_to(to, "<dt>scenes</dt><dd class=\"counts\">{}</dd>\n", counts_html(count_scenes(results)));
  fmt::format_to(
      to,
      "<dt>checks</dt><dd class=\"counts\">{} <span class=\"description\">(lanes and cross-lane pairs)</span></dd>\n",
      counts_html(count_checks(results)));
  out +=
      "</dl>\n<p class=\"description\">Machine-readable: <a href=\"junit.xml\">junit.xml</a>, "
      "<a href=\"results.json\">results.json</a></p>\n</header>\n";

  if (results.scenes.empty()) {
    out += "<p>No scene ran.</p>\n";
    merged_runs();
    return out + std::string(kPageEnd);
  }
  // The scenes that need a look first, the most urgent at the top; otherwise in run order.
  std::vector<size_t> order(results.scenes.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return urgency(results.scenes[a].verdict) > urgency(results.scenes[b].verdict);
  });
  const size_t columns = 3 + std::max<size_t>(lanes.size(), 1);

  // Filter by verdict: the buttons set the table's data-show, which the style sheet reads.
  const VerdictCounts counts = count_scenes(results);
  const size_t problems = counts.fail + counts.error + counts.crash;
  out += "<p class=\"filter\" role=\"toolbar\" aria-label=\"show scenes\">Show: ";
  const auto filter_button = [&](std::string_view show, std::string_view label, size_t count, bool always) {
    if (count == 0 && !always) return;
    fmt::format_to(to, "<button type=\"button\" data-show=\"{}\" aria-pressed=\"{}\">{} ({})</button> ", show,
                   show == "all" ? "true" : "false", label, count);
  };
  filter_button("all", "all", counts.total(), true);
  filter_button("problem", "did not pass", problems, true);
  filter_button("fail", "fail", counts.fail, false);
  filter_button("error", "error", counts.error, false);
  filter_button("crash", "crash", counts.crash, false);
  filter_button("pass", "pass", counts.pass, false);
  filter_button("skipped", "skipped", counts.skipped, false);
  out += "</p>\n";

  out += "<table class=\"index\" data-show=\"all\">\n<thead><tr><th>scene</th><th>verdict</th>";
  for (const std::string& lane : lanes) fmt::format_to(to, "<th>{}</th>", escape_text(lane));
  if (lanes.empty()) out += "<th>lanes</th>";
  out += "<th>cross-lane</th></tr></thead>\n<tbody>\n";
  bool in_problems = false, in_rest = false;
  for (const size_t i : order) {
    const bool problem = is_problem(results.scenes[i].verdict);
    if (problem && !in_problems) {
      const size_t count = static_cast<size_t>(std::count_if(
          results.scenes.begin(), results.scenes.end(), [](const SceneResult& s) { return is_problem(s.verdict); }));
      fmt::format_to(to, "<tr class=\"separator\"><td colspan=\"{}\">Did not pass ({})</td></tr>\n", columns, count);
      in_problems = true;
    }
    if (!problem && in_problems && !in_rest) {
      fmt::format_to(to, "<tr class=\"separator\"><td colspan=\"{}\">Passed or skipped</td></tr>\n", columns);
      in_rest = true;
    }
    index_row(out, results.scenes[i], pages[i], lanes);
  }
  out += "</tbody>\n</table>\n";
  merged_runs();
  out += R"js(<script>
// The verdict filter: one table attribute, read by the style sheet; the address keeps the choice.
(function () {
  const table = document.querySelector("table.index");
  const buttons = document.querySelectorAll(".filter button");
  function show(which) {
    if (![...buttons].some((b) => b.dataset.show === which)) which = "all";
    table.dataset.show = which;
    for (const b of buttons) b.setAttribute("aria-pressed", String(b.dataset.show === which));
    history.replaceState(null, "", which === "all" ? location.pathname : "#show=" + which);
  }
  for (const b of buttons) b.addEventListener("click", () => show(b.dataset.show));
  const asked = /^#show=(\w+)$/.exec(location.hash);
  if (asked) show(asked[1]);
})();
</script>
)js";
  return out + std::string(kPageEnd);
}

std::string_view viewer_script() { return kViewerScript; }
std::string_view viewer_style() { return kViewerStyle; }

std::string scene_html(const SceneResult& scene, const ViewerPage& viewer) {
  std::string out = page_start(fmt::format("{}: {}", scene.scene, verdict_word(scene.verdict)));
  auto to = std::back_inserter(out);
  fmt::format_to(to, "<nav><a href=\"index.html\">← all scenes</a></nav>\n<header class=\"{}\">\n<h1>{} {}</h1>\n",
                 verdict_class(scene.verdict), escape_text(scene.scene), badge(scene.verdict));
  if (!scene.description.empty()) fmt::format_to(to, "<p>{}</p>\n", escape_text(scene.description));
  out += "</header>\n";
  if (!scene.message.empty())
    fmt::format_to(to, "<section>\n<h2>The scene did not render</h2>\n<pre class=\"message\">{}</pre>\n</section>\n",
                   escape_text(scene.message));
  if (!scene.warnings.empty()) {
    out += "<section>\n<h2>Warnings</h2>\n<pre class=\"warnings\">";
    for (const std::string& warning : scene.warnings) out += escape_text(warning) + "\n";
    out += "</pre>\n</section>\n";
  }

  if (!scene.lanes.empty()) {
    out += "<section>\n<table>\n<tr><th>lane</th><th>verdict</th><th>first failure</th><th>time</th></tr>\n";
    for (const LaneResult& lane : scene.lanes)
      fmt::format_to(to,
                     "<tr><td><a href=\"#{}\">{}</a></td><td class=\"cell {}\">{}</td>"
                     "<td>{}</td><td class=\"num\">{:.3f} s</td></tr>\n",
                     lane_anchor(lane.lane), escape_text(lane.lane), verdict_class(lane.verdict),
                     verdict_span(lane.verdict), escape_text(first_line(first_failure(lane))), lane.seconds);
    out += "</table>\n</section>\n";
  }
  if (std::any_of(scene.lanes.begin(), scene.lanes.end(), [](const LaneResult& lane) { return !lane.image.empty(); }))
    images_section(out, scene, viewer);
  for (const LaneResult& lane : scene.lanes) lane_section(out, lane);
  if (!scene.lanes.empty() || !scene.cross_lane.empty()) cross_lane_section(out, scene);
  if (!scene.plan.empty())
    fmt::format_to(to, "<section>\n<h2>Plan</h2>\n<pre>{}</pre>\n</section>\n", escape_text(scene.plan));
  return out + std::string(kPageEnd);
}

}  // namespace xshade::harness
