#include "harness/gate/result_json.h"

#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include <nlohmann/json.hpp>

namespace xshade::harness {
namespace {

using nlohmann::json;

// nlohmann writes non-finite numbers as null anyway; saying so here keeps the rule visible.
json number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json pixel_json(const std::optional<std::pair<uint32_t, uint32_t>>& pixel) {
  if (!pixel) return nullptr;
  return {{"x", pixel->first}, {"y", pixel->second}};
}

json rgba_json(const std::array<float, 4>& value) {
  json channels = json::array();
  for (float channel : value) channels.push_back(number(channel));
  return channels;
}

json non_finite_json(const NonFiniteCount& count) {
  return {{"nan", count.nan},
          {"inf", count.inf},
          {"negative", count.negative},
          {"total", count.total()},
          {"first", pixel_json(count.first)}};
}

json driver_json(const DriverInfo& driver) {
  return {{"api", driver.api},
          {"renderer", driver.renderer},
          {"api_version", driver.api_version},
          {"driver_version", driver.driver_version},
          {"llvm_version", driver.llvm_version}};
}

json site_json(const glsl::TraceSite& site) {
  return {{"kind", glsl::trace_site_kind_name(site.kind)},
          {"file", site.file},
          {"line", site.line},
          {"column", site.column},
          {"source_line", site.source_line},
          {"function", site.function},
          {"what", site.what},
          {"description", glsl::describe_site(site)}};
}

json trace_json(const NonfiniteTraceResult& trace) {
  json passes = json::array();
  for (const PassOrigins& pass : trace.passes) {
    json origins = json::array();
    for (const NonfiniteOrigin& origin : pass.origins) {
      json calls = json::array();
      for (const glsl::TraceCall& call : origin.calls)
        calls.push_back({{"callee", call.callee},
                         {"caller", call.caller},
                         {"file", call.file},
                         {"line", call.line},
                         {"column", call.column},
                         {"source_line", call.source_line}});
      origins.push_back({{"program", origin.program},
                         {"site", site_json(origin.site)},
                         {"calls", std::move(calls)},
                         {"pixels", origin.pixels},
                         {"nan", origin.nan},
                         {"inf", origin.inf},
                         {"negative", origin.negative},
                         {"first", {{"x", origin.first_x}, {"y", origin.first_y}}}});
    }
    passes.push_back({{"pass", pass.pass},
                      {"output", pass.output},
                      {"origins", std::move(origins)},
                      {"unattributed_pixels", pass.unattributed_pixels},
                      {"recovered_pixels", pass.recovered_pixels},
                      {"map", pass.map}});
  }
  return {{"passes", std::move(passes)},
          {"traced_milliseconds", number(trace.traced_milliseconds)},
          {"plain_milliseconds", number(trace.plain_milliseconds)},
          {"identical", trace.identical},
          {"traced_image", trace.traced_image},
          {"note", trace.note}};
}

// Reads a document xshade wrote: a field that is not there or of another type is xshade's fault.
class Reader {
 public:
  template <class T>
  T get(const json& object, const char* key, T fallback = T()) {
    const auto found = object.find(key);
    if (found == object.end()) {
      note(key);
      return fallback;
    }
    if constexpr (std::is_same_v<T, bool>) {
      if (!found->is_boolean()) return note(key), fallback;
    } else if constexpr (std::is_floating_point_v<T>) {
      if (found->is_null()) return std::numeric_limits<T>::quiet_NaN();
      if (!found->is_number()) return note(key), fallback;
    } else if constexpr (std::is_integral_v<T>) {
      if (!found->is_number_integer()) return note(key), fallback;
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!found->is_string()) return note(key), fallback;
    }
    return found->get<T>();
  }
  const json& object(const json& parent, const char* key) {
    static const json empty = json::object();
    const auto found = parent.find(key);
    if (found == parent.end() || !found->is_object()) return note(key), empty;
    return *found;
  }
  const json& array(const json& parent, const char* key) {
    static const json empty = json::array();
    const auto found = parent.find(key);
    if (found == parent.end() || !found->is_array()) return note(key), empty;
    return *found;
  }
  std::optional<std::pair<uint32_t, uint32_t>> pixel(const json& parent, const char* key) {
    const auto found = parent.find(key);
    if (found == parent.end()) return note(key), std::nullopt;
    if (found->is_null()) return std::nullopt;
    return std::pair{get<uint32_t>(*found, "x"), get<uint32_t>(*found, "y")};
  }
  std::array<float, 4> rgba(const json& parent, const char* key) {
    std::array<float, 4> value{};
    const json& channels = array(parent, key);
    if (channels.size() != 4) return note(key), value;
    for (size_t c = 0; c < 4; ++c)
      value[c] = channels[c].is_number() ? channels[c].get<float>() : std::numeric_limits<float>::quiet_NaN();
    return value;
  }
  Verdict verdict(const json& parent, const char* key) {
    if (const std::optional<Verdict> verdict = verdict_from_name(get<std::string>(parent, key))) return *verdict;
    note(key);
    return Verdict::Crash;
  }
  ImageMetrics metrics(const json& object) {
    ImageMetrics metrics;
    const json& steps = this->object(object, "steps");
    metrics.max_steps = get<uint32_t>(steps, "worst");
    metrics.worst_x = get<uint32_t>(steps, "worst_x");
    metrics.worst_y = get<uint32_t>(steps, "worst_y");
    metrics.worst_test = rgba(steps, "worst_test");
    metrics.worst_reference = rgba(steps, "worst_reference");
    metrics.first_failing = pixel(steps, "first_failing");
    metrics.mean_steps = get<double>(steps, "mean");
    metrics.rmse_steps = get<double>(steps, "rmse");
    // The only PSNR JSON cannot hold is that of identical images.
    metrics.psnr = steps.contains("psnr") && steps["psnr"].is_null() ? std::numeric_limits<double>::infinity()
                                                                     : get<double>(steps, "psnr");
    metrics.failing_pixels = get<size_t>(steps, "failing_pixels");
    metrics.failing_fraction = get<double>(steps, "failing_fraction");
    const json& above_one = this->object(object, "above_one");
    metrics.hdr_values = get<size_t>(above_one, "values");
    metrics.float_failing_pixels = get<size_t>(above_one, "failing_pixels");
    metrics.float_max_relative = get<double>(above_one, "worst_relative");
    metrics.float_x = get<uint32_t>(above_one, "worst_x");
    metrics.float_y = get<uint32_t>(above_one, "worst_y");
    const json& linear = this->object(object, "linear");
    metrics.max_difference = get<double>(linear, "max_difference");
    metrics.max_x = get<uint32_t>(linear, "max_x");
    metrics.max_y = get<uint32_t>(linear, "max_y");
    metrics.mean = get<double>(linear, "mean");
    metrics.rmse = get<double>(linear, "rmse");
    // Only a scene that chose a metric has one (and results written before metrics have none).
    if (object.contains("metric") && !object["metric"].is_null()) {
      const json& metric = this->object(object, "metric");
      MetricFigures figures{
          get<std::string>(metric, "name"), get<double>(metric, "value"), get<double>(metric, "threshold"), {}};
      const json& named = this->object(metric, "figures");
      for (auto it = named.begin(); it != named.end(); ++it)
        figures.figures.emplace_back(it.key(), get<double>(named, it.key().c_str()));
      metrics.metric = std::move(figures);
    }
    return metrics;
  }

  NonfiniteTraceResult trace(const json& object) {
    NonfiniteTraceResult trace;
    for (const json& pass_object : array(object, "passes")) {
      PassOrigins pass;
      pass.pass = get<std::string>(pass_object, "pass");
      pass.output = get<bool>(pass_object, "output");
      for (const json& origin_object : array(pass_object, "origins")) {
        NonfiniteOrigin origin;
        origin.pass = pass.pass;
        origin.program = get<std::string>(origin_object, "program");
        const json& site = this->object(origin_object, "site");
        origin.site.kind = site_kind(get<std::string>(site, "kind"));
        origin.site.file = get<std::string>(site, "file");
        origin.site.line = get<uint32_t>(site, "line");
        origin.site.column = get<uint32_t>(site, "column");
        origin.site.source_line = get<std::string>(site, "source_line");
        origin.site.function = get<std::string>(site, "function");
        origin.site.what = get<std::string>(site, "what");
        for (const json& call : array(origin_object, "calls"))
          origin.calls.push_back({get<std::string>(call, "callee"), get<std::string>(call, "caller"),
                                  get<std::string>(call, "file"), get<uint32_t>(call, "line"),
                                  get<uint32_t>(call, "column"), get<std::string>(call, "source_line")});
        origin.pixels = get<size_t>(origin_object, "pixels");
        origin.nan = get<size_t>(origin_object, "nan");
        origin.inf = get<size_t>(origin_object, "inf");
        origin.negative = get<size_t>(origin_object, "negative");
        const auto first = pixel(origin_object, "first");
        if (first) std::tie(origin.first_x, origin.first_y) = *first;
        pass.origins.push_back(std::move(origin));
      }
      pass.unattributed_pixels = get<size_t>(pass_object, "unattributed_pixels");
      pass.recovered_pixels = get<size_t>(pass_object, "recovered_pixels");
      pass.map = get<std::string>(pass_object, "map");
      trace.passes.push_back(std::move(pass));
    }
    trace.traced_milliseconds = get<double>(object, "traced_milliseconds");
    trace.plain_milliseconds = get<double>(object, "plain_milliseconds");
    trace.identical = get<bool>(object, "identical");
    trace.traced_image = get<std::string>(object, "traced_image");
    trace.note = get<std::string>(object, "note");
    return trace;
  }

  const std::string& missing() const { return missing_; }

 private:
  void note(const char* key) {
    if (missing_.empty()) missing_ = key;
  }
  glsl::TraceSite::Kind site_kind(const std::string& name) {
    using Kind = glsl::TraceSite::Kind;
    for (Kind kind : {Kind::Initialization, Kind::Assignment, Kind::CompoundAssignment, Kind::Return, Kind::Call,
                      Kind::Input, Kind::Output, Kind::NegativeOutput})
      if (name == glsl::trace_site_kind_name(kind)) return kind;
    note("kind");
    return Kind::Assignment;
  }
  std::string missing_;
};

}  // namespace

json metric_to_json(const MetricFigures& metric) {
  json figures = json::object();
  for (const auto& [name, value] : metric.figures) figures[name] = number(value);
  return {{"name", metric.name},
          {"value", number(metric.value)},
          {"threshold", number(metric.threshold)},
          {"figures", std::move(figures)}};
}

json metrics_to_json(const ImageMetrics& metrics) {
  return {{"steps",
           {{"worst", metrics.max_steps},
            {"worst_x", metrics.worst_x},
            {"worst_y", metrics.worst_y},
            {"worst_test", rgba_json(metrics.worst_test)},
            {"worst_reference", rgba_json(metrics.worst_reference)},
            {"first_failing", pixel_json(metrics.first_failing)},
            {"mean", number(metrics.mean_steps)},
            {"rmse", number(metrics.rmse_steps)},
            {"psnr", number(metrics.psnr)},
            {"failing_pixels", metrics.failing_pixels},
            {"failing_fraction", number(metrics.failing_fraction)}}},
          {"above_one",
           {{"values", metrics.hdr_values},
            {"failing_pixels", metrics.float_failing_pixels},
            {"worst_relative", number(metrics.float_max_relative)},
            {"worst_x", metrics.float_x},
            {"worst_y", metrics.float_y}}},
          {"linear",
           {{"max_difference", number(metrics.max_difference)},
            {"max_x", metrics.max_x},
            {"max_y", metrics.max_y},
            {"mean", number(metrics.mean)},
            {"rmse", number(metrics.rmse)}}},
          {"metric", metrics.metric ? metric_to_json(*metrics.metric) : json(nullptr)}};
}

json lane_to_json(const LaneResult& lane) {
  json layers = json::array();
  for (const LayerResult& layer : lane.layers)
    layers.push_back(
        {{"layer", layer.layer}, {"verdict", std::string(verdict_name(layer.verdict))}, {"detail", layer.detail}});
  json timings = json::array();
  for (const PassTime& time : lane.timings)
    timings.push_back({{"pass", time.pass}, {"milliseconds", number(time.milliseconds)}});
  return {{"lane", lane.lane},
          {"verdict", std::string(verdict_name(lane.verdict))},
          {"layers", std::move(layers)},
          {"against_golden", lane.against_golden ? metrics_to_json(*lane.against_golden) : json(nullptr)},
          {"non_finite", non_finite_json(lane.non_finite)},
          {"image", lane.image},
          {"image_exr", lane.image_exr},
          {"golden", lane.golden},
          {"golden_exr", lane.golden_exr},
          {"diff", lane.diff},
          {"metric_map", lane.metric_map},
          {"non_finite_mask", lane.non_finite_mask},
          {"timings", std::move(timings)},
          {"seconds", number(lane.seconds)},
          {"driver", driver_json(lane.driver)},
          {"message", lane.message},
          {"nonfinite_trace", lane.trace ? trace_json(*lane.trace) : json(nullptr)}};
}

Result<ImageMetrics> metrics_from_json(const json& object) {
  if (!object.is_object()) return fail(ErrorKind::Internal, "metrics are not a JSON object");
  Reader read;
  ImageMetrics metrics = read.metrics(object);
  if (!read.missing().empty()) return fail(ErrorKind::Internal, "metrics have no valid '" + read.missing() + "'");
  return metrics;
}

Result<LaneResult> lane_from_json(const json& object) {
  if (!object.is_object()) return fail(ErrorKind::Internal, "a lane's result is not a JSON object");
  Reader read;
  LaneResult lane;
  lane.lane = read.get<std::string>(object, "lane");
  lane.verdict = read.verdict(object, "verdict");
  for (const json& layer : read.array(object, "layers"))
    lane.layers.push_back({read.get<std::string>(layer, "layer"), read.verdict(layer, "verdict"),
                           read.get<std::string>(layer, "detail")});
  if (const auto golden = object.find("against_golden"); golden != object.end() && golden->is_object())
    lane.against_golden = read.metrics(*golden);
  const json& non_finite = read.object(object, "non_finite");
  lane.non_finite.nan = read.get<size_t>(non_finite, "nan");
  lane.non_finite.inf = read.get<size_t>(non_finite, "inf");
  lane.non_finite.negative = read.get<size_t>(non_finite, "negative");
  lane.non_finite.first = read.pixel(non_finite, "first");
  lane.image = read.get<std::string>(object, "image");
  lane.image_exr = read.get<std::string>(object, "image_exr");
  lane.golden = read.get<std::string>(object, "golden");
  lane.golden_exr = read.get<std::string>(object, "golden_exr");
  lane.diff = read.get<std::string>(object, "diff");
  // Results written before metrics have none.
  if (object.contains("metric_map")) lane.metric_map = read.get<std::string>(object, "metric_map");
  lane.non_finite_mask = read.get<std::string>(object, "non_finite_mask");
  for (const json& time : read.array(object, "timings"))
    lane.timings.push_back({read.get<std::string>(time, "pass"), read.get<double>(time, "milliseconds")});
  lane.seconds = read.get<double>(object, "seconds");
  const json& driver = read.object(object, "driver");
  lane.driver = {read.get<std::string>(driver, "api"), read.get<std::string>(driver, "renderer"),
                 read.get<std::string>(driver, "api_version"), read.get<std::string>(driver, "driver_version"),
                 read.get<std::string>(driver, "llvm_version")};
  lane.message = read.get<std::string>(object, "message");
  if (const auto trace = object.find("nonfinite_trace"); trace != object.end() && trace->is_object())
    lane.trace = read.trace(*trace);
  if (!read.missing().empty())
    return fail(ErrorKind::Internal, "a lane's result has no valid '" + read.missing() + "'");
  // A lane xshade does not have would be left out of every check between lanes without a word.
  if (!parse_lane(lane.lane))
    return fail(ErrorKind::UserInput, "a lane's result names the lane '" + lane.lane + "', which xshade does not have");
  return lane;
}

}  // namespace xshade::harness
