#include "harness/report/results_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "harness/gate/result_json.h"
#include "harness/report/report_text.h"

namespace xshade::harness {
namespace {

using nlohmann::json;

// nlohmann writes non-finite numbers as null anyway; saying so here keeps the rule visible.
json number(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json verdict_json(Verdict verdict) { return std::string(verdict_name(verdict)); }

json counts_json(const VerdictCounts& counts) {
  return {{"total", counts.total()}, {"pass", counts.pass},   {"fail", counts.fail},
          {"error", counts.error},   {"crash", counts.crash}, {"skipped", counts.skipped}};
}

// The lane's own fields (harness/gate/result_json.h), with the failure a reviewer reads first.
json lane_json(const LaneResult& lane) {
  json object = lane_to_json(lane);
  object["first_failure"] = first_failure(lane);
  return object;
}

json pair_json(const CrossLaneResult& pair) {
  return {{"first_lane", pair.first_lane},         {"second_lane", pair.second_lane},
          {"verdict", verdict_json(pair.verdict)}, {"metrics", metrics_to_json(pair.metrics)},
          {"identical", pair.identical},           {"diff", pair.diff}};
}

json compare_metric_json(const MetricSettings& metric) {
  return {{"name", std::string(metric_name(metric.metric))},
          {"threshold", metric.threshold},
          {"pixel_threshold", metric.pixel_threshold},
          {"incorrect_fraction", metric.incorrect_fraction},
          {"pixels_per_degree", metric.pixels_per_degree}};
}

json scene_json(const SceneResult& scene) {
  json lanes = json::array();
  for (const LaneResult& lane : scene.lanes) lanes.push_back(lane_json(lane));
  json pairs = json::array();
  for (const CrossLaneResult& pair : scene.cross_lane) pairs.push_back(pair_json(pair));
  return {{"scene", scene.scene},
          {"description", scene.description},
          {"verdict", verdict_json(scene.verdict)},
          {"lanes", std::move(lanes)},
          {"cross_lane", std::move(pairs)},
          {"plan", scene.plan},
          {"warnings", scene.warnings},
          {"message", scene.message},
          {"compare",
           {{"channel_tolerance", scene.compare.channel_tolerance},
            {"max_failing_fraction", scene.compare.max_failing_fraction},
            {"position_radius", scene.compare.position_radius},
            {"float_tolerance", scene.compare.float_tolerance},
            {"metric", scene.compare.metric ? compare_metric_json(*scene.compare.metric) : json(nullptr)},
            {"reason", scene.compare.reason}}}};
}

json merged_json(const std::vector<MergedRun>& runs) {
  json array = json::array();
  for (const MergedRun& run : runs)
    array.push_back(
        {{"folder", run.folder}, {"started", run.started}, {"seconds", number(run.seconds)}, {"command", run.command}});
  return array;
}

}  // namespace

std::string results_json(const RunResults& results) {
  json scenes = json::array();
  for (const SceneResult& scene : results.scenes) scenes.push_back(scene_json(scene));
  const Verdict verdict = run_verdict(results);
  const json document = {{"format", "xshade-results-1"},
                         {"started", results.started},
                         {"seconds", number(results.seconds)},
                         {"command", results.command},
                         {"merged_from", merged_json(results.merged_from)},
                         {"verdict", verdict_json(verdict)},
                         {"exit_code", exit_code(verdict)},
                         {"scene_counts", counts_json(count_scenes(results))},
                         {"check_counts", counts_json(count_checks(results))},
                         {"scenes", std::move(scenes)}};
  return document.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

namespace {

// Reads what scene_json wrote. Fields are looked up with at(), whose exception names the key.
Result<SceneResult> scene_from_json(const json& object) {
  SceneResult scene;
  scene.scene = object.at("scene").get<std::string>();
  scene.description = object.at("description").get<std::string>();
  scene.plan = object.at("plan").get<std::string>();
  // Results written before warnings were kept have none.
  if (object.contains("warnings")) scene.warnings = object.at("warnings").get<std::vector<std::string>>();
  scene.message = object.at("message").get<std::string>();
  const json& compare = object.at("compare");
  scene.compare.channel_tolerance = compare.at("channel_tolerance").get<uint32_t>();
  scene.compare.max_failing_fraction = compare.at("max_failing_fraction").get<double>();
  scene.compare.position_radius = compare.at("position_radius").get<uint32_t>();
  scene.compare.float_tolerance = compare.at("float_tolerance").get<double>();
  scene.compare.reason = compare.at("reason").get<std::string>();
  // Results written before metrics, and scenes that chose none, have no metric.
  if (compare.contains("metric") && !compare.at("metric").is_null()) {
    const json& metric = compare.at("metric");
    const std::optional<Metric> named = metric_named(metric.at("name").get<std::string>());
    if (!named)
      return fail(ErrorKind::UserInput, "scene " + scene.scene + " is compared by the metric '" +
                                            metric.at("name").get<std::string>() + "', which xshade does not have");
    scene.compare.metric =
        MetricSettings{*named, metric.at("threshold").get<double>(), metric.at("pixel_threshold").get<double>(),
                       metric.at("incorrect_fraction").get<double>(), metric.at("pixels_per_degree").get<double>()};
  }
  const std::string verdict = object.at("verdict").get<std::string>();
  if (!verdict_from_name(verdict))
    return fail(ErrorKind::UserInput,
                "scene " + scene.scene + " has the verdict '" + verdict + "', which xshade does not give");
  scene.verdict = *verdict_from_name(verdict);
  for (const json& lane : object.at("lanes")) {
    auto read = lane_from_json(lane);
    if (!read) return fail(ErrorKind::UserInput, "scene " + scene.scene + ": " + read.error().message);
    scene.lanes.push_back(std::move(*read));
  }
  for (const json& pair : object.at("cross_lane")) {
    CrossLaneResult cross;
    cross.first_lane = pair.at("first_lane").get<std::string>();
    cross.second_lane = pair.at("second_lane").get<std::string>();
    cross.diff = pair.at("diff").get<std::string>();
    cross.identical = pair.at("identical").get<bool>();
    const std::string pair_verdict = pair.at("verdict").get<std::string>();
    if (!verdict_from_name(pair_verdict))
      return fail(ErrorKind::UserInput, "scene " + scene.scene + " has a pair with the verdict '" + pair_verdict + "'");
    cross.verdict = *verdict_from_name(pair_verdict);
    auto metrics = metrics_from_json(pair.at("metrics"));
    if (!metrics) return fail(ErrorKind::UserInput, "scene " + scene.scene + ": " + metrics.error().message);
    cross.metrics = *metrics;
    scene.cross_lane.push_back(std::move(cross));
  }
  return scene;
}

}  // namespace

Result<RunResults> results_from_json(std::string_view text, const std::string& file) {
  const auto refuse = [&](const std::string& why) {
    return fail(ErrorKind::UserInput, file + ": not a results.json xshade wrote (" + why + ")");
  };
  const json document = json::parse(text, nullptr, false);
  if (document.is_discarded()) return refuse("it is not JSON");
  if (!document.is_object() || document.value("format", "") != "xshade-results-1")
    return refuse("its \"format\" is not \"xshade-results-1\"");
  RunResults results;
  try {
    results.started = document.at("started").get<std::string>();
    results.seconds = document.at("seconds").is_null() ? 0.0 : document.at("seconds").get<double>();
    results.command = document.at("command").get<std::string>();
    for (const json& run : document.at("merged_from"))
      results.merged_from.push_back({run.at("folder").get<std::string>(), run.at("started").get<std::string>(),
                                     run.at("seconds").is_null() ? 0.0 : run.at("seconds").get<double>(),
                                     run.at("command").get<std::string>()});
    for (const json& scene : document.at("scenes")) {
      auto read = scene_from_json(scene);
      if (!read) return refuse(read.error().message);
      results.scenes.push_back(std::move(*read));
    }
  } catch (const json::exception& error) {
    return refuse(error.what());
  }
  return results;
}

}  // namespace xshade::harness
