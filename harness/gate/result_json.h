// A lane's result as JSON and back: the lane objects of results.json, and what a worker process
// hands the run that supervises it. Reading what was written gives the same result, except that
// a number JSON cannot hold (an infinite PSNR, a NaN) comes back as infinity for the PSNR and as
// NaN for the others.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "base/result.h"
#include "harness/gate/run_results.h"

namespace xshade::harness {

nlohmann::json metrics_to_json(const ImageMetrics& metrics);
// A perceptual metric's name, value, threshold and figures (results.json's "metric").
nlohmann::json metric_to_json(const MetricFigures& metric);
// Metrics written by metrics_to_json; a missing or mistyped field is an Internal error naming it.
Result<ImageMetrics> metrics_from_json(const nlohmann::json& json);
nlohmann::json lane_to_json(const LaneResult& lane);
// A lane object written by lane_to_json; a missing or mistyped field is an Internal error
// naming it (only xshade writes these).
Result<LaneResult> lane_from_json(const nlohmann::json& json);

}  // namespace xshade::harness
