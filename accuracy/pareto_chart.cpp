#include "accuracy/pareto_chart.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <string_view>

#include "base/markup.h"

namespace xshade::accuracy {
namespace {

// Okabe and Ito's palette: told apart with any form of colour blindness; the marker shapes tell
// series apart in grey too.
constexpr std::array<std::string_view, 7> kColours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000"};
enum class Shape { Circle, Square, Triangle, Diamond, TriangleDown, Star };
constexpr std::array<Shape, 6> kShapes = {Shape::Circle,  Shape::Square,       Shape::Triangle,
                                          Shape::Diamond, Shape::TriangleDown, Shape::Star};

constexpr double kLabelFont = 11;
constexpr double kTickFont = 11;
constexpr double kMarkerRadius = 4.5;
constexpr size_t kMaxNotes = 12;

// ---- text ----

// Labels come from configuration names and may hold anything: escape_text makes them
// well-formed XML; a chart label is one line, so line breaks and tabs become spaces.
std::string escape_xml(std::string_view text) {
  std::string out = escape_text(text);
  std::replace_if(
      out.begin(), out.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; }, ' ');
  return out;
}

// A rough width for layout: sans-serif glyphs average a little over half the font size.
double text_width(std::string_view text, double font_size) {
  size_t code_points = 0;
  for (const char c : text)
    if ((static_cast<uint8_t>(c) & 0xC0) != 0x80) ++code_points;
  return static_cast<double>(code_points) * font_size * 0.58;
}

// Five significant digits at most, in the shortest form a person reads: 0.5, 2, 10, 1500, 0.001,
// 1e-4, 2.5e6.
std::string format_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (value == 0) return "0";
  const std::string scientific = fmt::format("{:.4e}", value);  // -d.dddde±XX
  const size_t e = scientific.find('e');
  std::string mantissa = scientific.substr(0, e);
  const int exponent = std::stoi(scientific.substr(e + 1));
  while (mantissa.back() == '0') mantissa.pop_back();
  if (mantissa.back() == '.') mantissa.pop_back();
  if (exponent < -3 || exponent > 5) return fmt::format("{}e{}", mantissa, exponent);
  const size_t point = mantissa.find('.');
  const int decimals = point == std::string::npos ? 0 : static_cast<int>(mantissa.size() - point - 1);
  return fmt::format("{:.{}f}", value, std::max(0, decimals - exponent));
}

// Pixel coordinates: two decimals are finer than any display and keep the output byte-stable.
std::string px(double value) { return fmt::format("{:.2f}", value); }

// ---- axes ----

struct Axis {
  bool log = true;
  double lo = 0, hi = 1;        // the range in axis space (log10 of the value on a log axis)
  double px_lo = 0, px_hi = 1;  // the pixels of lo and hi (px_hi < px_lo on the y axis)
  double space(double value) const { return log ? std::log10(value) : value; }
  double pixel(double value) const { return px_lo + (space(value) - lo) / (hi - lo) * (px_hi - px_lo); }
  double clamp_pixel(double pixel_value) const {
    return std::clamp(pixel_value, std::min(px_lo, px_hi), std::max(px_lo, px_hi));
  }
};

// The data's range in axis space, padded by 6% on each side so that no point sits on the frame;
// a single value gets half a decade (log) or 10% (linear) on either side.
void fit_range(Axis& axis, const std::vector<double>& values, double fallback_lo, double fallback_hi) {
  if (values.empty()) {
    axis.lo = axis.space(fallback_lo);
    axis.hi = axis.space(fallback_hi);
    return;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double v : values) {
    lo = std::min(lo, axis.space(v));
    hi = std::max(hi, axis.space(v));
  }
  if (hi - lo <= 0) {
    const double half = axis.log ? 0.5 : (lo == 0 ? 1.0 : std::abs(lo) * 0.1);
    lo -= half;
    hi += half;
  }
  const double pad = (hi - lo) * 0.06;
  axis.lo = lo - pad;
  axis.hi = hi + pad;
}

double nice_step(double rough) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(rough)));
  const double f = rough / magnitude;
  return (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * magnitude;
}

// Values (not axis space) at multiples of a 1, 2 or 5 x 10^k step.
std::vector<double> linear_ticks(double lo, double hi, size_t target) {
  std::vector<double> ticks;
  if (!(hi > lo)) return ticks;
  const double step = nice_step((hi - lo) / static_cast<double>(std::max<size_t>(target, 1)));
  for (double i = std::ceil(lo / step - 1e-9); i * step <= hi + step * 1e-9; ++i) {
    const double v = i * step;
    ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  }
  return ticks;
}

// At 1, 2, 5 x 10^k when that is few enough, else at decades (every n-th when even those are too
// many); in a range narrower than that, at 1..9 x 10^k, and in the narrowest at linear steps.
std::vector<double> log_ticks(double lo, double hi, size_t max_ticks) {
  const auto at = [&](std::initializer_list<double> mantissas, int every) {
    std::vector<double> ticks;
    for (int k = static_cast<int>(std::floor(lo)) - 1; k <= static_cast<int>(std::ceil(hi)) + 1; ++k) {
      if (k % every != 0) continue;
      for (const double m : mantissas) {
        const double v = m * std::pow(10.0, k);
        const double s = std::log10(v);
        if (s >= lo - 1e-9 && s <= hi + 1e-9) ticks.push_back(v);
      }
    }
    return ticks;
  };
  std::vector<double> ticks = at({1, 2, 5}, 1);
  if (ticks.size() > max_ticks) {
    ticks = at({1}, 1);
    if (ticks.size() > max_ticks) {
      const int every = static_cast<int>((ticks.size() + max_ticks - 1) / std::max<size_t>(max_ticks, 1));
      ticks = at({1}, std::max(every, 1));
    }
  } else if (ticks.size() < 2) {
    ticks = at({1, 2, 3, 4, 5, 6, 7, 8, 9}, 1);
    if (ticks.size() < 2) ticks = linear_ticks(std::pow(10.0, lo), std::pow(10.0, hi), std::min<size_t>(max_ticks, 6));
  }
  return ticks;
}

std::vector<double> ticks_of(const Axis& axis, size_t max_ticks) {
  max_ticks = std::max<size_t>(max_ticks, 2);
  return axis.log ? log_ticks(axis.lo, axis.hi, max_ticks)
                  : linear_ticks(axis.lo, axis.hi, std::min<size_t>(max_ticks, 6));
}

// ---- marks ----

std::string marker_svg(Shape shape, double x, double y, std::string_view colour) {
  const double r = kMarkerRadius;
  const std::string style = fmt::format(R"(fill="{}" stroke="#ffffff" stroke-width="1")", colour);
  const auto polygon = [&](std::initializer_list<std::pair<double, double>> corners) {
    std::string points;
    for (const auto& [dx, dy] : corners) {
      if (!points.empty()) points += ' ';
      points += px(x + dx) + ',' + px(y + dy);
    }
    return fmt::format(R"(<polygon class="marker" points="{}" {}/>)", points, style);
  };
  switch (shape) {
    case Shape::Circle:
      return fmt::format(R"(<circle class="marker" cx="{}" cy="{}" r="{}" {}/>)", px(x), px(y), px(r), style);
    case Shape::Square: {
      const double s = r * 0.9;
      return fmt::format(R"(<rect class="marker" x="{}" y="{}" width="{}" height="{}" {}/>)", px(x - s), px(y - s),
                         px(2 * s), px(2 * s), style);
    }
    case Shape::Triangle: return polygon({{0, -r * 1.2}, {r * 1.1, r * 0.8}, {-r * 1.1, r * 0.8}});
    case Shape::TriangleDown: return polygon({{0, r * 1.2}, {r * 1.1, -r * 0.8}, {-r * 1.1, -r * 0.8}});
    case Shape::Diamond: return polygon({{0, -r * 1.25}, {r * 1.1, 0}, {0, r * 1.25}, {-r * 1.1, 0}});
    case Shape::Star: {
      std::string points;
      for (int i = 0; i < 10; ++i) {
        const double angle = -std::numbers::pi / 2 + i * std::numbers::pi / 5;
        const double radius = i % 2 == 0 ? r * 1.3 : r * 0.55;
        if (!points.empty()) points += ' ';
        points += px(x + radius * std::cos(angle)) + ',' + px(y + radius * std::sin(angle));
      }
      return fmt::format(R"(<polygon class="marker" points="{}" {}/>)", points, style);
    }
  }
  return {};
}

struct Box {
  double left, top, right, bottom;
};

double overlap(const Box& a, const Box& b) {
  const double w = std::min(a.right, b.right) - std::max(a.left, b.left);
  const double h = std::min(a.bottom, b.bottom) - std::max(a.top, b.top);
  return w > 0 && h > 0 ? w * h : 0;
}

double area(const Box& b) { return (b.right - b.left) * (b.bottom - b.top); }

// Where a point's label may go, in order of preference: beside the marker above or below its bar,
// then centred above or below, then on the bar, then a line further out.
struct LabelSpot {
  double dx, dy;  // from the marker to the text's anchor and baseline
  std::string_view anchor;
};
constexpr std::array<LabelSpot, 14> kLabelSpots = {{
    {6, -6, "start"},
    {6, 15, "start"},
    {-6, -6, "end"},
    {-6, 15, "end"},
    {0, -10, "middle"},
    {0, 19, "middle"},
    {9, 4, "start"},
    {-9, 4, "end"},
    {6, -19, "start"},
    {6, 28, "start"},
    {-6, -19, "end"},
    {-6, 28, "end"},
    {0, -23, "middle"},
    {0, 32, "middle"},
}};

Box label_box(double x, double y, const LabelSpot& spot, double width) {
  const double ax = x + spot.dx, baseline = y + spot.dy;
  const double left = spot.anchor == "start" ? ax : spot.anchor == "end" ? ax - width : ax - width / 2;
  return {left - 3, baseline - kLabelFont * 0.8, left + width + 3,
          baseline + kLabelFont * 0.25};  // a gap between words
}

// ---- the chart's points ----

struct Placed {
  size_t series = 0, index = 0;
  double x = 0, y = 0;
  bool zero_row = false;
  bool bar = false;
  double bar_left = 0, bar_right = 0;
  bool open_left = false, open_right = false;  // the bar runs past the frame
};

std::string point_name(const ChartSeries& series, const ChartPoint& point) {
  return point.label.empty() ? series.name : fmt::format("{}, {}", series.name, point.label);
}

}  // namespace

std::vector<size_t> pareto_front(const std::vector<ChartPoint>& points) {
  const auto finite = [](const ChartPoint& p) { return std::isfinite(p.milliseconds) && std::isfinite(p.error); };
  const auto dominates = [](const ChartPoint& a, const ChartPoint& b) {
    return a.milliseconds <= b.milliseconds && a.error <= b.error &&
           (a.milliseconds < b.milliseconds || a.error < b.error);
  };
  std::vector<size_t> front;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) continue;
    bool dominated = false;
    for (size_t j = 0; j < points.size() && !dominated; ++j)
      dominated = j != i && finite(points[j]) && dominates(points[j], points[i]);
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) {
    const ChartPoint &pa = points[a], &pb = points[b];
    if (pa.milliseconds != pb.milliseconds) return pa.milliseconds < pb.milliseconds;
    if (pa.error != pb.error) return pa.error < pb.error;
    return a < b;
  });
  return front;
}

std::string pareto_chart_svg(const std::vector<ChartSeries>& series, const ChartOptions& options) {
  const double width = std::max(options.width, 320);
  const double height = std::max(options.height, 240);

  // Which points can be drawn, and notes on those that cannot.
  std::vector<std::string> notes;
  std::vector<Placed> placed;
  std::vector<double> x_values, y_values;
  for (size_t s = 0; s < series.size(); ++s) {
    for (size_t i = 0; i < series[s].points.size(); ++i) {
      const ChartPoint& point = series[s].points[i];
      std::vector<std::string> reasons;
      if (!std::isfinite(point.milliseconds))
        reasons.push_back(fmt::format("time {} ms", format_number(point.milliseconds)));
      else if (options.log_x && point.milliseconds <= 0)
        reasons.push_back(fmt::format("time {} ms, not on a log axis", format_number(point.milliseconds)));
      if (!std::isfinite(point.error))
        reasons.push_back(fmt::format("error {}", format_number(point.error)));
      else if (options.log_y && point.error < 0)
        reasons.push_back(fmt::format("error {}, not on a log axis", format_number(point.error)));
      if (!reasons.empty()) {
        std::string joined;
        for (const std::string& reason : reasons) joined += (joined.empty() ? "" : "; ") + reason;
        notes.push_back(fmt::format("Not drawn: {}: {}", point_name(series[s], point), joined));
        continue;
      }
      Placed p;
      p.series = s;
      p.index = i;
      p.zero_row = options.log_y && point.error == 0;
      x_values.push_back(point.milliseconds);
      if (!p.zero_row) y_values.push_back(point.error);
      if (!std::isfinite(point.spread_ms) || point.spread_ms < 0) {
        notes.push_back(fmt::format("No spread bar: {}: spread {} ms", point_name(series[s], point),
                                    format_number(point.spread_ms)));
      } else if (point.spread_ms > 0) {
        p.bar = true;
        // The bar's ends widen the time axis, except that on a log axis an end far below the
        // point (or below 0) would squash everything else: that end runs off the frame instead.
        const double right = point.milliseconds + point.spread_ms;
        const double left = point.milliseconds - point.spread_ms;
        if (std::isfinite(right)) x_values.push_back(right);
        if (std::isfinite(left) && (!options.log_x || left >= point.milliseconds / 10)) x_values.push_back(left);
      }
      placed.push_back(p);
    }
  }
  const bool zero_row = std::any_of(placed.begin(), placed.end(), [](const Placed& p) { return p.zero_row; });

  // Header: the title, then the legend in centred rows.
  enum class Key { Series, Front, Spread };
  struct LegendEntry {
    std::string text;
    Key key;
    size_t series;  // for Key::Series
    double width;
  };
  std::vector<LegendEntry> legend;
  for (size_t s = 0; s < series.size(); ++s) {
    std::string name = series[s].name.empty() ? fmt::format("series {}", s + 1) : series[s].name;
    const double w = 20 + text_width(name, kLabelFont);
    legend.push_back({std::move(name), Key::Series, s, w});
  }
  legend.push_back({"Pareto front", Key::Front, 0, 30 + text_width("Pareto front", kLabelFont)});
  legend.push_back({"time spread", Key::Spread, 0, 30 + text_width("time spread", kLabelFont)});
  std::vector<std::vector<size_t>> legend_rows(1);
  {
    double row_width = 0;
    for (size_t e = 0; e < legend.size(); ++e) {
      const double w = legend[e].width + 18;
      if (row_width > 0 && row_width + w > width - 32) {
        legend_rows.emplace_back();
        row_width = 0;
      }
      legend_rows.back().push_back(e);
      row_width += w;
    }
  }
  const double legend_top = options.title.empty() ? 12 : 36;
  const double plot_top = legend_top + 20 * static_cast<double>(legend_rows.size()) + 14;
  const double plot_bottom = height - (options.x_label.empty() ? 30 : 50);
  const double row_height = 36, row_gap = 8;  // tall enough for a label above and one below
  const double log_bottom = zero_row ? plot_bottom - row_height - row_gap : plot_bottom;
  const double zero_y = plot_bottom - row_height / 2;

  Axis y_axis{options.log_y};
  fit_range(y_axis, y_values, options.log_y ? 0.1 : 0, 1);
  y_axis.px_lo = log_bottom;
  y_axis.px_hi = plot_top;
  const std::vector<double> y_ticks = ticks_of(y_axis, static_cast<size_t>((log_bottom - plot_top) / 26));
  double y_label_width = zero_row ? text_width("0 (reference)", kTickFont) : 0;
  for (const double t : y_ticks) y_label_width = std::max(y_label_width, text_width(format_number(t), kTickFont));
  const double plot_left = 8 + (options.y_label.empty() ? 0 : 22) + y_label_width + 8;
  const double plot_right = width - 20;

  Axis x_axis{options.log_x};
  fit_range(x_axis, x_values, options.log_x ? 1 : 0, 10);
  x_axis.px_lo = plot_left;
  x_axis.px_hi = plot_right;
  const std::vector<double> x_ticks = ticks_of(x_axis, static_cast<size_t>((plot_right - plot_left) / 56));

  for (Placed& p : placed) {
    const ChartPoint& point = series[p.series].points[p.index];
    p.x = x_axis.pixel(point.milliseconds);
    p.y = p.zero_row ? zero_y : y_axis.pixel(point.error);
    if (p.bar) {
      const double left = point.milliseconds - point.spread_ms;
      const double right = point.milliseconds + point.spread_ms;
      const double left_px = options.log_x && left <= 0 ? -std::numeric_limits<double>::infinity() : x_axis.pixel(left);
      const double right_px = std::isfinite(right) ? x_axis.pixel(right) : std::numeric_limits<double>::infinity();
      p.bar_left = x_axis.clamp_pixel(left_px);
      p.bar_right = x_axis.clamp_pixel(right_px);
      p.open_left = left_px < plot_left;
      p.open_right = right_px > plot_right;
    }
  }

  const double notes_height = notes.empty() ? 0 : 10 + 16 * static_cast<double>(std::min(notes.size(), kMaxNotes + 1));
  const double total_height = height + notes_height;

  std::string svg;
  auto out = std::back_inserter(svg);
  fmt::format_to(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
  fmt::format_to(out,
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0}\" height=\"{1}\" "
                 "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\">\n",
                 px(width), px(total_height));
  fmt::format_to(out, "<rect x=\"0\" y=\"0\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n", px(width),
                 px(total_height));
  if (!options.title.empty())
    fmt::format_to(out,
                   "<text class=\"title\" x=\"{}\" y=\"22\" text-anchor=\"middle\" font-size=\"15\" "
                   "font-weight=\"bold\" fill=\"#222222\">{}</text>\n",
                   px(width / 2), escape_xml(options.title));

  // Legend.
  fmt::format_to(out, "<g class=\"legend\" font-size=\"{}\" fill=\"#222222\">\n", kLabelFont);
  for (size_t r = 0; r < legend_rows.size(); ++r) {
    double row_width = -18;
    for (const size_t e : legend_rows[r]) row_width += legend[e].width + 18;
    double x = (width - row_width) / 2;
    const double y = legend_top + 20 * static_cast<double>(r) + 10;
    for (const size_t e : legend_rows[r]) {
      const LegendEntry& entry = legend[e];
      double text_x = x + 20;
      if (entry.key == Key::Series) {
        const size_t s = entry.series;
        fmt::format_to(out, "{}\n", marker_svg(kShapes[s % kShapes.size()], x + 6, y, kColours[s % kColours.size()]));
      } else if (entry.key == Key::Front) {
        fmt::format_to(out,
                       "<polyline points=\"{},{} {},{} {},{}\" fill=\"none\" stroke=\"#555555\" "
                       "stroke-width=\"1.2\"/>\n",
                       px(x), px(y - 5), px(x + 12), px(y - 5), px(x + 12), px(y + 5));
        fmt::format_to(out,
                       "<line x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\" stroke=\"#555555\" stroke-width=\"1.2\"/>\n",
                       px(x + 12), px(x + 22), px(y + 5));
        text_x = x + 30;
      } else {
        fmt::format_to(out,
                       "<path d=\"M{0},{2} H{1} M{0},{3} V{4} M{1},{3} V{4}\" stroke=\"#555555\" "
                       "stroke-width=\"1.5\" fill=\"none\"/>\n",
                       px(x), px(x + 22), px(y), px(y - 3.5), px(y + 3.5));
        text_x = x + 30;
      }
      fmt::format_to(out, "<text x=\"{}\" y=\"{}\">{}</text>\n", px(text_x), px(y + 4), escape_xml(entry.text));
      x += entry.width + 18;
    }
  }
  fmt::format_to(out, "</g>\n");

  // Frames, grid and ticks.
  const std::string_view grid = "#e4e4e4", frame = "#666666";
  fmt::format_to(out, "<g class=\"axes\" font-size=\"{}\" fill=\"#333333\">\n", kTickFont);
  const auto frame_rect = [&](double top, double bottom) {
    fmt::format_to(out, "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"{}\"/>\n",
                   px(plot_left), px(top), px(plot_right - plot_left), px(bottom - top), frame);
  };
  for (const double t : y_ticks) {
    const double y = y_axis.pixel(t);
    fmt::format_to(out, "<line x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(plot_left),
                   px(plot_right), px(y), grid);
    fmt::format_to(out, "<line x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(plot_left - 5),
                   px(plot_left), px(y), frame);
    fmt::format_to(out, "<text class=\"y-tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", px(plot_left - 8),
                   px(y + 4), format_number(t));
  }
  for (const double t : x_ticks) {
    const double x = x_axis.pixel(t);
    fmt::format_to(out, "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(x), px(plot_top),
                   px(log_bottom), grid);
    if (zero_row)
      fmt::format_to(out, "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(x),
                     px(log_bottom + row_gap), px(plot_bottom), grid);
    fmt::format_to(out, "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(x), px(plot_bottom),
                   px(plot_bottom + 5), frame);
    fmt::format_to(out, "<text class=\"x-tick\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n", px(x),
                   px(plot_bottom + 18), format_number(t));
  }
  frame_rect(plot_top, log_bottom);
  if (zero_row) {
    // Its own frame, apart from the log scale, because 0 has no place on it.
    frame_rect(log_bottom + row_gap, plot_bottom);
    fmt::format_to(out, "<line x1=\"{0}\" y1=\"{2}\" x2=\"{1}\" y2=\"{2}\" stroke=\"{3}\"/>\n", px(plot_left - 5),
                   px(plot_left), px(zero_y), frame);
    fmt::format_to(out, "<text class=\"y-tick\" x=\"{}\" y=\"{}\" text-anchor=\"end\">0 (reference)</text>\n",
                   px(plot_left - 8), px(zero_y + 4));
  }
  if (!options.x_label.empty())
    fmt::format_to(out, "<text class=\"x-label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"12\">{}</text>\n",
                   px((plot_left + plot_right) / 2), px(plot_bottom + 38), escape_xml(options.x_label));
  if (!options.y_label.empty()) {
    const double cy = (plot_top + log_bottom) / 2;
    fmt::format_to(out,
                   "<text class=\"y-label\" x=\"16\" y=\"{0}\" text-anchor=\"middle\" font-size=\"12\" "
                   "transform=\"rotate(-90 16 {0})\">{1}</text>\n",
                   px(cy), escape_xml(options.y_label));
  }
  fmt::format_to(out, "</g>\n");

  // Each series' Pareto front, as the staircase of the best error reachable within a time.
  for (size_t s = 0; s < series.size(); ++s) {
    std::vector<ChartPoint> drawn;
    std::vector<const Placed*> drawn_placed;
    for (const Placed& p : placed)
      if (p.series == s) {
        drawn.push_back(series[s].points[p.index]);
        drawn_placed.push_back(&p);
      }
    const std::vector<size_t> front = pareto_front(drawn);
    if (front.size() < 2) continue;
    std::string points;
    for (size_t k = 0; k < front.size(); ++k) {
      const Placed& p = *drawn_placed[front[k]];
      if (k > 0) points += fmt::format(" {},{}", px(p.x), px(drawn_placed[front[k - 1]]->y));
      points += fmt::format("{}{},{}", k > 0 ? " " : "", px(p.x), px(p.y));
    }
    fmt::format_to(out,
                   "<polyline class=\"front\" points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.2\" "
                   "stroke-opacity=\"0.7\"/>\n",
                   points, kColours[s % kColours.size()]);
  }

  // Points: the spread bar, then the marker, with the values as a tooltip.
  for (const Placed& p : placed) {
    const ChartPoint& point = series[p.series].points[p.index];
    const std::string_view colour = kColours[p.series % kColours.size()];
    const std::string spread = p.bar ? fmt::format(" ± {}", format_number(point.spread_ms)) : std::string();
    fmt::format_to(out, "<g class=\"point\"><title>{}: {} ms{}, error {}</title>",
                   escape_xml(point_name(series[p.series], point)), format_number(point.milliseconds),
                   escape_xml(spread), format_number(point.error));
    if (p.bar) {
      fmt::format_to(out, "<path d=\"M{},{} H{}", px(p.bar_left), px(p.y), px(p.bar_right));
      if (!p.open_left) fmt::format_to(out, " M{0},{1} V{2}", px(p.bar_left), px(p.y - 3.5), px(p.y + 3.5));
      if (!p.open_right) fmt::format_to(out, " M{0},{1} V{2}", px(p.bar_right), px(p.y - 3.5), px(p.y + 3.5));
      fmt::format_to(out, "\" stroke=\"{}\" stroke-width=\"1.5\" fill=\"none\"/>", colour);
    }
    fmt::format_to(out, "{}</g>\n", marker_svg(kShapes[p.series % kShapes.size()], p.x, p.y, colour));
  }

  // Labels: each at the first of its spots that overlaps least with markers, bars and the labels
  // already placed, and stays inside the frame.
  std::vector<std::pair<Box, double>> obstacles;  // and the weight of overlapping each
  for (const Placed& p : placed) {
    obstacles.push_back(
        {{p.x - kMarkerRadius - 1, p.y - kMarkerRadius - 1, p.x + kMarkerRadius + 1, p.y + kMarkerRadius + 1}, 3.0});
    if (p.bar) obstacles.push_back({{p.bar_left, p.y - 3.5, p.bar_right, p.y + 3.5}, 0.5});
  }
  // A label stays in its point's own frame: the log scale's, or the row of zeros.
  const Box inside_log{plot_left + 2, plot_top + 2, plot_right - 2, log_bottom - 2};
  const Box inside_row{plot_left + 2, log_bottom + row_gap + 1, plot_right - 2, plot_bottom - 1};
  fmt::format_to(out, "<g class=\"labels\" font-size=\"{}\">\n", kLabelFont);
  for (const Placed& p : placed) {
    const ChartPoint& point = series[p.series].points[p.index];
    if (point.label.empty()) continue;
    const double w = text_width(point.label, kLabelFont);
    size_t best = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < kLabelSpots.size(); ++k) {
      const Box box = label_box(p.x, p.y, kLabelSpots[k], w);
      const Box& inside = p.zero_row ? inside_row : inside_log;
      double cost = 8 * (area(box) - overlap(box, inside)) + static_cast<double>(k) * 0.5;
      for (const auto& [obstacle, weight] : obstacles) cost += weight * overlap(box, obstacle);
      if (cost < best_cost) {
        best_cost = cost;
        best = k;
      }
    }
    const LabelSpot& spot = kLabelSpots[best];
    obstacles.push_back({label_box(p.x, p.y, spot, w), 6.0});
    const std::string text = escape_xml(point.label);
    const std::string at =
        fmt::format("x=\"{}\" y=\"{}\" text-anchor=\"{}\"", px(p.x + spot.dx), px(p.y + spot.dy), spot.anchor);
    // A white halo under the text keeps it legible where it crosses a line.
    fmt::format_to(out,
                   "<text {0} fill=\"none\" stroke=\"#ffffff\" stroke-width=\"3\" stroke-linejoin=\"round\" "
                   "stroke-opacity=\"0.85\">{1}</text>\n<text class=\"label\" {0} fill=\"{2}\">{1}</text>\n",
                   at, text, kColours[p.series % kColours.size()]);
  }
  fmt::format_to(out, "</g>\n");

  if (!notes.empty()) {
    fmt::format_to(out, "<g class=\"notes\" font-size=\"11\" fill=\"#444444\">\n");
    for (size_t n = 0; n < std::min(notes.size(), kMaxNotes); ++n)
      fmt::format_to(out, "<text class=\"note\" x=\"12\" y=\"{}\">{}</text>\n",
                     px(height + 14 + 16 * static_cast<double>(n)), escape_xml(notes[n]));
    if (notes.size() > kMaxNotes)
      fmt::format_to(out, "<text class=\"note\" x=\"12\" y=\"{}\">… and {} more</text>\n",
                     px(height + 14 + 16 * static_cast<double>(kMaxNotes)), notes.size() - kMaxNotes);
    fmt::format_to(out, "</g>\n");
  }
  fmt::format_to(out, "</svg>\n");
  return svg;
}

}  // namespace xshade::accuracy
