#include "harness/report/results_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

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

// The per-pixel layer's domain (8-bit sRGB steps) for the summary, the float layer's for values
// above 1, and the linear differences of the floats as they are.
json metrics_json(const ImageMetrics& metrics) {
  json first_failing = nullptr;
  if (metrics.first_failing) first_failing = {{"x", metrics.first_failing->first}, {"y", metrics.first_failing->second}};
  return {{"steps", {{"worst", metrics.max_steps},
                     {"worst_x", metrics.worst_x},
                     {"worst_y", metrics.worst_y},
                     {"first_failing", first_failing},
                     {"mean", number(metrics.mean_steps)},
                     {"rmse", number(metrics.rmse_steps)},
                     {"psnr", number(metrics.psnr)},
                     {"failing_pixels", metrics.failing_pixels},
                     {"failing_fraction", number(metrics.failing_fraction)}}},
          {"above_one", {{"values", metrics.hdr_values},
                         {"failing_pixels", metrics.float_failing_pixels},
                         {"worst_relative", number(metrics.float_max_relative)},
                         {"worst_x", metrics.float_x},
                         {"worst_y", metrics.float_y}}},
          {"linear", {{"max_difference", number(metrics.max_difference)},
                      {"max_x", metrics.max_x},
                      {"max_y", metrics.max_y},
                      {"mean", number(metrics.mean)},
                      {"rmse", number(metrics.rmse)}}}};
}

json non_finite_json(const NonFiniteCount& count) {
  json first = nullptr;
  if (count.first) first = {{"x", count.first->first}, {"y", count.first->second}};
  return {{"nan", count.nan}, {"inf", count.inf}, {"negative", count.negative}, {"total", count.total()},
          {"first", first}};
}

json driver_json(const DriverInfo& driver) {
  return {{"api", driver.api},
          {"renderer", driver.renderer},
          {"api_version", driver.api_version},
          {"driver_version", driver.driver_version},
          {"llvm_version", driver.llvm_version}};
}

json lane_json(const LaneResult& lane) {
  json layers = json::array();
  for (const LayerResult& layer : lane.layers)
    layers.push_back({{"layer", layer.layer}, {"verdict", verdict_json(layer.verdict)}, {"detail", layer.detail}});
  json timings = json::array();
  for (const PassTime& time : lane.timings)
    timings.push_back({{"pass", time.pass}, {"milliseconds", number(time.milliseconds)}});
  return {{"lane", lane.lane},
          {"verdict", verdict_json(lane.verdict)},
          {"first_failure", first_failure(lane)},
          {"layers", std::move(layers)},
          {"against_golden", lane.against_golden ? metrics_json(*lane.against_golden) : json(nullptr)},
          {"non_finite", non_finite_json(lane.non_finite)},
          {"image", lane.image},
          {"image_exr", lane.image_exr},
          {"golden", lane.golden},
          {"diff", lane.diff},
          {"non_finite_mask", lane.non_finite_mask},
          {"timings", std::move(timings)},
          {"seconds", number(lane.seconds)},
          {"driver", driver_json(lane.driver)},
          {"message", lane.message}};
}

json pair_json(const CrossLaneResult& pair) {
  return {{"first_lane", pair.first_lane},
          {"second_lane", pair.second_lane},
          {"verdict", verdict_json(pair.verdict)},
          {"metrics", metrics_json(pair.metrics)},
          {"diff", pair.diff}};
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
          {"message", scene.message}};
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
                         {"verdict", verdict_json(verdict)},
                         {"exit_code", exit_code(verdict)},
                         {"scene_counts", counts_json(count_scenes(results))},
                         {"check_counts", counts_json(count_checks(results))},
                         {"scenes", std::move(scenes)}};
  return document.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace xshade::harness
