// What accuracy costs, as one picture: a Pareto chart of error against GPU time as an SVG image.
// One point per configuration of a shader knob (a kernel size, fp32 or fp16, the seed's terms or
// exact ones), one series (colour and marker) per backend lane, each series' Pareto front as a
// step line. `xshade accuracy` measures; this only draws.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace xshade::accuracy {

struct ChartPoint {
  std::string label;        // the configuration, e.g. "43 samples"
  double milliseconds = 0;  // median time
  double spread_ms = 0;     // half-width of the bar drawn through the marker: milliseconds ± spread_ms
                            // (e.g. (max - min) / 2 of the repetitions); 0 draws no bar
  double error = 0;         // e.g. RMSE against the reference; 0 is the reference itself
};

struct ChartSeries {
  std::string name;  // the lane, e.g. "vk-hlsl"
  std::vector<ChartPoint> points;
};

struct ChartOptions {
  std::string title;
  std::string x_label = "GPU time (ms)";
  std::string y_label = "error";
  bool log_x = true;
  bool log_y = true;
  int width = 720;  // the chart's size in pixels; notes about points not drawn add lines below it
  int height = 480;
};

// The indices of the points that no other point dominates, in order of time (then error, then
// index). A point dominates another when it is no slower and no less accurate, and strictly better
// in one of the two; so two points with equal time and error are both kept. Points whose time or
// error is not finite are never on the front and dominate nothing.
std::vector<size_t> pareto_front(const std::vector<ChartPoint>& points);

// The chart as a self-contained SVG 1.1 document; the same input gives the same bytes.
//
// On a log error axis, a point with error exactly 0 is drawn on its own row below the log scale,
// at its true time, with the row's tick labelled "0 (reference)". A point that cannot be placed
// (a time or error that is NaN or infinite, a time <= 0 on a log time axis, an error < 0 on a log
// error axis) is left out and named in a note below the chart, with the value that kept it out; a
// point whose spread is not finite or negative is drawn without its bar, and noted too.
std::string pareto_chart_svg(const std::vector<ChartSeries>& series, const ChartOptions& options);

}  // namespace xshade::accuracy
