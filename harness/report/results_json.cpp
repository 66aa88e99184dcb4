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
  return {{"first_lane", pair.first_lane},
          {"second_lane", pair.second_lane},
          {"verdict", verdict_json(pair.verdict)},
          {"metrics", metrics_to_json(pair.metrics)},
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
