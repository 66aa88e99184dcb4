#include "harness/gate/scene_check.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "base/file_io.h"
#include "harness/assets/environment.h"
#include "harness/image/image_compare.h"
#include "harness/image/image_io.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// Whose fault a failed render is: a scene's or a shader's mistake is the user's (exit 2), a
// driver's or xshade's is a crash (exit 3).
Verdict verdict_of(const Error& error) { return error.kind == ErrorKind::UserInput ? Verdict::Error : Verdict::Crash; }

// Records a layer; a deciding one sets the lane's verdict (the first failing one its message).
// A comparison layer that does not decide is shown but judges nothing: a per-pixel failure that
// the position layer forgives leaves the lane passing.
void add_layer(LaneResult& lane, LayerResult layer, bool decides = true) {
  if (decides && layer.verdict != Verdict::Pass && layer.verdict != Verdict::Skipped) {
    lane.verdict = worst(lane.verdict, layer.verdict);
    if (lane.message.empty()) lane.message = layer.layer + ": " + layer.detail;
  }
  lane.layers.push_back(std::move(layer));
}

// "finite": the image has no NaN, Inf or negative value.
LayerResult finite_layer(const NonFiniteCount& bad) {
  return {"finite", bad.total() ? Verdict::Fail : Verdict::Pass,
          bad.total() ? std::to_string(bad.nan) + " NaN, " + std::to_string(bad.inf) + " Inf, " +
                            std::to_string(bad.negative) + " negative values, first at (" +
                            std::to_string(bad.first->first) + ", " + std::to_string(bad.first->second) + ")"
                      : "no NaN, Inf or negative values"};
}

}  // namespace

SceneChecker::SceneChecker(VariantCompiler& compiler, SceneCheckOptions options, Progress progress)
    : compiler_(compiler), options_(std::move(options)), progress_(std::move(progress)) {}

std::string SceneChecker::copy_file(const fs::path& from, const std::string& scene, const std::string& file) {
  const std::string relative = scene + "/" + file;
  const fs::path path = options_.report_dir / relative;
  std::error_code ignored;
  fs::create_directories(path.parent_path(), ignored);
  // Whole or not at all: the workers of a scene's lanes copy its common golden at once.
  if (auto written = copy_file_whole(from, path); !written) {
    progress_("  cannot copy " + from.string() + ": " + written.error().message);
    return {};
  }
  return relative;
}

std::string SceneChecker::write_image(const FloatImage& image, const std::string& scene, const std::string& file,
                                      bool exr) {
  const std::string relative = scene + "/" + file;
  const fs::path path = options_.report_dir / relative;
  std::error_code ignored;
  fs::create_directories(path.parent_path(), ignored);
  auto written = exr ? write_exr(image, path) : write_png(image, path, PngCompression::Fast);
  if (!written) {
    progress_("  " + written.error().message);
    return {};
  }
  return relative;
}

std::string lane_progress_line(const std::string& scene, const LaneResult& lane) {
  std::string line = scene + " on " + lane.lane + ": " + std::string(verdict_name(lane.verdict)) +
                     (lane.message.empty() ? "" : " - " + first_line(lane.message));
  // The output's sites, most pixels first, so that a failing gate says where to look.
  if (lane.trace && !lane.trace->passes.empty() && lane.trace->passes.front().output) {
    const PassOrigins& pass = lane.trace->passes.front();
    for (size_t i = 0; i < pass.origins.size() && i < 3; ++i) {
      const NonfiniteOrigin& origin = pass.origins[i];
      line += fmt::format("\n    {} pixels non-finite from {}:{}:{}: {} in {}", origin.pixels, origin.site.file,
                          origin.site.line, origin.site.column, glsl::describe_site(origin.site), origin.site.function);
    }
    if (pass.origins.size() > 3)
      line += fmt::format("\n    ... and {} more sites (the report lists them)", pass.origins.size() - 3);
  }
  return line;
}

CheckedScene SceneChecker::prepare(const fs::path& scene_file, const std::vector<Lane>& lanes) {
  CheckedScene checked;
  SceneResult& result = checked.result;
  result.scene = scene_file.stem().string();
  auto scene = load_scene(scene_file);
  if (!scene) {
    result.verdict = Verdict::Error;
    result.message = scene.error().to_string();
    return checked;
  }
  checked.scene = *scene;
  result.description = scene->description;
  result.compare = scene->compare;
  auto plan = plan_scene(*scene, compiler_.shaders(), &checked.files_read);
  if (!plan) {
    result.verdict = Verdict::Error;
    result.message = plan.error().to_string();
    return checked;
  }
  std::vector<Lane> scene_lanes;
  for (Lane lane : lanes)
    if (std::find(scene->lanes.begin(), scene->lanes.end(), lane_name(lane)) != scene->lanes.end())
      scene_lanes.push_back(lane);
  std::vector<bool> cached;
  for (const VariantRequest& variant : plan->variants)
    cached.push_back(!scene_lanes.empty() && std::all_of(scene_lanes.begin(), scene_lanes.end(),
                                                         [&](Lane lane) { return compiler_.in_cache(variant, lane); }));
  result.plan = describe_plan(*scene, *plan, cached);
  result.warnings = plan->warnings;
  if (options_.plan_only) return checked;
  if (scene_lanes.empty()) {
    // Not a pass: nothing was checked. A CI job that asks for a lane the scene does not list
    // sees the scene skipped, and why.
    std::string listed;
    for (const std::string& lane : scene->lanes) listed += (listed.empty() ? "" : ", ") + lane;
    result.verdict = Verdict::Skipped;
    result.message = "skipped: the scene runs on " + listed + ", none of the lanes asked for";
    return checked;
  }
  checked.plan = std::make_shared<const Plan>(std::move(*plan));
  checked.lanes = std::move(scene_lanes);
  return checked;
}

void SceneChecker::conclude(CheckedScene& checked) {
  SceneResult& result = checked.result;
  for (const std::string& warning : result.warnings) progress_(result.scene + ": " + warning);
  for (const LaneResult& lane : result.lanes) progress_(lane_progress_line(result.scene, lane));
  if (checked.scene) compare_lanes(*checked.scene, checked);
  for (const LaneResult& lane : result.lanes) result.verdict = worst(result.verdict, lane.verdict);
  for (const CrossLaneResult& pair : result.cross_lane) result.verdict = worst(result.verdict, pair.verdict);
}

void SceneChecker::check_lane(Lane lane, CheckedScene& checked, const Status& status) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = *checked.scene;
  const Plan& plan = *checked.plan;
  auto at = [&](const std::string& where) {
    if (status) status(where);
  };
  LaneResult result;
  result.lane = std::string(lane_name(lane));
  auto finish = [&](Verdict verdict, std::string message) {
    result.verdict = verdict == Verdict::Skipped ? verdict : worst(result.verdict, verdict);
    if (!message.empty()) result.message = std::move(message);
    result.seconds = seconds_since(start);
    checked.result.lanes.push_back(std::move(result));
  };

  if (options_.half_emulation && lane == Lane::VkHlsl)
    return finish(Verdict::Skipped,
                  "half emulation rewrites the GLSL xshade emits; this lane compiles the source with glslang");
  if (!checked.environment) {
    at("while building the environment");
    if (Result<void> built = build_scene_environment(checked); !built)
      return finish(Verdict::Error, built.error().to_string());
  }
  at("while compiling");
  auto compiled = compiler_.compile_plan(plan, lane, options_.half_emulation);
  if (!compiled) return finish(Verdict::Error, compiled.error().to_string());
  const std::vector<CompiledVariant>& variants = *compiled;
  at("while creating the " + result.lane + " backend");
  auto backend = create_backend(lane, options_.backend);
  if (!backend) return finish(Verdict::Crash, backend.error().to_string());
  result.driver = (*backend)->driver_info();

  auto in_pass = [&](int render) {
    return [&at, render](std::string_view pass) {
      at("in pass " + std::string(pass) + " (render " + std::to_string(render) + " of 2)");
    };
  };
  auto rendered = render_scene(**backend, scene, plan, variants, *checked.environment,
                               {.keep_pass_images = options_.pass_images, .on_pass = in_pass(1)});
  if (!rendered) return finish(verdict_of(rendered.error()), rendered.error().to_string());
  for (const PassTiming& timing : rendered->timings) result.timings.push_back({timing.pass, timing.milliseconds});
  for (const auto& [pass, image] : rendered->pass_images)
    write_image(image, scene.name, "passes/" + pass + "." + result.lane + ".exr", true);

  // The same scene again on the same driver must give the same bits.
  auto again = render_scene(**backend, scene, plan, variants, *checked.environment, {.on_pass = in_pass(2)});
  if (!again) return finish(verdict_of(again.error()), again.error().to_string());
  at("while comparing");
  for (const std::string& message : (*backend)->take_driver_messages())
    add_layer(result, {"driver", Verdict::Fail, message});

  const FloatImage& image = rendered->image;
  write_lane_images(scene, image, result);
  if (options_.trace_nonfinite || result.non_finite.total()) {
    at("while tracing non-finite values");
    trace_lane(lane, scene, plan, *checked.environment, **backend, image, result);
  }

  add_layer(result, determinism_layer(rendered->image, again->image));
  add_reference_layers(scene, image, result);
  checked.images.emplace(lane, image);
  finish(Verdict::Pass, {});
}

// The layers that hold a lane's image to what it should be: its golden (the common one or the
// lane's own), or, with no golden to hold it to (none kept, or half emulation, which goldens are not
// renders of), that it is finite.
void SceneChecker::add_reference_layers(const Scene& scene, const FloatImage& image, LaneResult& result) {
  if (!options_.goldens || options_.half_emulation) {
    if (options_.half_emulation)
      add_layer(result,
                {"golden", Verdict::Skipped, "goldens are fp32 renders; half emulation is not compared with them"});
    add_layer(result, finite_layer(result.non_finite));
    return;
  }
  auto golden = options_.goldens->find(scene.name, result.lane);
  if (!golden) {
    add_layer(result, {"golden", Verdict::Error, golden.error().to_string()});
  } else if (!*golden) {
    add_layer(result, {"golden", Verdict::Fail, options_.goldens->missing_message(scene.name, result.lane)});
  } else if ((*golden)->image.width != image.width || (*golden)->image.height != image.height) {
    // The scene's size changed since the golden was blessed: nothing to compare pixel by pixel.
    const FloatImage& old = (*golden)->image;
    add_layer(result,
              {"golden", Verdict::Error,
               fmt::format("{} is {}x{} and the scene renders {}x{}: its size changed since it was blessed; "
                           "review the new image and bless it with {}",
                           (*golden)->path.string(), old.width, old.height, image.width, image.height,
                           GoldenStore::bless_command(
                               scene.name, (*golden)->lane_specific ? std::optional(result.lane) : std::nullopt))});
  } else {
    const GoldenImage& reference = **golden;
    // The golden's own files, as bless wrote them: its PNG, and its float image where it has one;
    // the common golden once for the scene, a lane's own golden as that lane's.
    const bool has_float = reference.path.extension() == ".exr";
    const std::string name = reference.lane_specific ? result.lane + ".golden" : std::string("golden");
    result.golden = copy_file(fs::path(reference.path).replace_extension(".png"), scene.name, name + ".png");
    if (has_float) result.golden_exr = copy_file(reference.path, scene.name, name + ".exr");
    Comparison comparison = compare_images(image, reference.image, scene.compare);
    for (LayerResult& layer : comparison.layers) {
      const bool decides = layer.layer == comparison.decided_by;
      add_layer(result, std::move(layer), decides);
    }
    // A failed comparison says how to accept the new image, as a missing golden does (not an
    // image with NaN, Inf or negative values, which bless refuses).
    if (comparison.verdict == Verdict::Fail && comparison.decided_by != "finite")
      result.message +=
          "\nif the new image is what the change means, accept it with " +
          GoldenStore::bless_command(scene.name, reference.lane_specific ? std::optional(result.lane) : std::nullopt);
    result.against_golden = comparison.metrics;
    result.diff = write_image(comparison.heat_map, scene.name, result.lane + ".diff.png");
    if (comparison.metrics.metric && comparison.metric_heat_map.width > 0)
      result.metric_map = write_image(comparison.metric_heat_map, scene.name,
                                      result.lane + "." + comparison.metrics.metric->name + ".png");
  }
}

// The lane's image as PNG and EXR, and a mask of its non-finite pixels when it has any.
void SceneChecker::write_lane_images(const Scene& scene, const FloatImage& image, LaneResult& result) {
  result.image = write_image(image, scene.name, result.lane + ".png");
  result.image_exr = write_image(image, scene.name, result.lane + ".exr", true);
  result.non_finite = count_non_finite(image);
  if (result.non_finite.total())
    result.non_finite_mask = write_image(non_finite_mask(image), scene.name, result.lane + ".nonfinite.png");
}

// The scene's environment, from the shared cache of them when the checker has one.
Result<void> SceneChecker::build_scene_environment(CheckedScene& checked) {
  const EnvironmentSpec& wanted = checked.scene->environment;
  if (options_.environments) {
    auto environment = options_.environments->get(wanted);
    if (!environment) return fail(environment.error());
    checked.environment = *environment;
    return {};
  }
  auto environment = build_environment(wanted);
  if (!environment) return fail(environment.error());
  checked.environment = std::make_shared<const Environment>(std::move(*environment));
  return {};
}

void SceneChecker::trace_lane(Lane lane, const Scene& scene, const Plan& plan, const Environment& environment,
                              Backend& backend, const FloatImage& plain, LaneResult& result) {
  NonfiniteTraceResult& trace = result.trace.emplace();
  for (const PassTime& time : result.timings) trace.plain_milliseconds += time.milliseconds;
  if (lane == Lane::VkHlsl) {
    trace.note =
        "vk-hlsl compiles the source with glslang's HLSL front end, which xshade cannot instrument: the gl and "
        "vk lanes say where the values were born";
    return;
  }
  auto variants = compiler_.compile_plan(plan, lane, options_.half_emulation, /*trace_nonfinite=*/true);
  if (!variants) {
    trace.note = "the tracing variant did not compile: " + variants.error().to_string();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  auto traced =
      render_scene(backend, scene, plan, *variants, environment, {.keep_pass_images = true, .trace_nonfinite = true});
  trace.traced_milliseconds = seconds_since(start) * 1000.0;
  if (!traced) {
    trace.note = "the traced render failed: " + traced.error().to_string();
    return;
  }
  trace.identical = bitwise_equal(traced->image, plain);
  // A traced image that is not the plain one's is a fault of the tracing variant: kept for a look.
  if (!trace.identical) trace.traced_image = write_image(traced->image, scene.name, result.lane + ".traced.exr", true);
  // Each pass that made non-finite values of its own (which a later pass read back through a
  // texture), and the output's pass whatever it holds; the output's goes first below.
  for (size_t i = 0; i < traced->traces.size(); ++i) {
    const PassTrace& record = traced->traces[i];
    const FloatImage& image = traced->pass_images[i].second;
    const bool output = i + 1 == traced->traces.size();
    const NonFiniteCount bad = count_non_finite(image);
    if (!output && bad.nan + bad.inf == 0) continue;
    auto origins = find_nonfinite_origins(image, record, *variants, /*count_negative=*/output);
    if (!origins) {
      trace.note = origins.error().to_string();
      return;
    }
    PassOrigins pass{
        record.pass, output, std::move(origins->origins), origins->unattributed_pixels, origins->recovered_pixels, {}};
    if (!pass.origins.empty())
      pass.map = write_image(origins->map, scene.name, result.lane + "." + record.pass + ".origins.png");
    trace.passes.push_back(std::move(pass));
  }
  // The output's pass first: its counts are the lane's; the earlier ones in the order they ran.
  if (!trace.passes.empty()) std::rotate(trace.passes.begin(), trace.passes.end() - 1, trace.passes.end());
}

LayerResult determinism_layer(const FloatImage& first, const FloatImage& second) {
  if (bitwise_equal(first, second)) return {"determinism", Verdict::Pass, "two renders are bit-identical"};
  const ImageDifference drift = max_difference(first, second);
  return {"determinism", Verdict::Fail,
          fmt::format("two renders differ: max {:g} at ({}, {})", drift.max, drift.x, drift.y)};
}

std::vector<LanePairComparison> compare_lane_images(const std::map<Lane, FloatImage>& images,
                                                    const CompareSettings& settings) {
  std::vector<LanePairComparison> pairs;
  if (images.size() < 2) return pairs;
  const auto& [first_lane, first] = *images.begin();
  for (const auto& [lane, image] : images)
    if (lane != first_lane) pairs.push_back({first_lane, lane, compare_images(image, first, settings)});
  return pairs;
}

std::optional<BlessRefusal> bless_refusal(const SceneResult& result) {
  for (const LaneResult& lane : result.lanes)
    if (lane.verdict != Verdict::Pass)
      return BlessRefusal{lane.verdict, fmt::format("{} on {}: {}", result.scene, lane.lane, lane.message)};
  for (const CrossLaneResult& pair : result.cross_lane)
    if (pair.verdict != Verdict::Pass)
      return BlessRefusal{Verdict::Fail,
                          fmt::format("{} and {} disagree ({}); a common golden is blessed only from lanes that agree. "
                                      "Find the lane that is wrong, or bless one lane with --lane and its reason.",
                                      pair.first_lane, pair.second_lane, describe_metrics(pair.metrics))};
  return std::nullopt;
}

std::vector<CrossLaneResult> cross_lane_results(
    const std::map<Lane, FloatImage>& images, const CompareSettings& settings, const HeatMapWriter& write,
    const std::function<void(const CrossLaneResult&, const std::string&)>& said) {
  std::vector<CrossLaneResult> pairs;
  for (LanePairComparison& compared : compare_lane_images(images, settings)) {
    Comparison& comparison = compared.comparison;
    CrossLaneResult pair;
    pair.first_lane = std::string(lane_name(compared.first));
    pair.second_lane = std::string(lane_name(compared.second));
    pair.verdict = comparison.verdict;
    pair.metrics = comparison.metrics;
    // A heat map of bit-identical images is black: the report says "identical" instead.
    pair.identical = comparison.decided_by == "exact";
    if (!pair.identical)
      pair.diff = write(comparison.heat_map, pair.first_lane + "_vs_" + pair.second_lane + ".diff.png");
    std::string detail;
    for (const LayerResult& layer : comparison.layers)
      if (layer.layer == comparison.decided_by) detail = layer.detail;
    if (said) said(pair, detail);
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

void SceneChecker::compare_lanes(const Scene& scene, CheckedScene& checked) {
  checked.result.cross_lane = cross_lane_results(
      checked.images, scene.compare,
      [&](const FloatImage& heat_map, const std::string& file) { return write_image(heat_map, scene.name, file); },
      [&](const CrossLaneResult& pair, const std::string& detail) {
        progress_(scene.name + ": " + pair.first_lane + " vs " + pair.second_lane + ": " +
                  std::string(verdict_name(pair.verdict)) + " - " + detail);
      });
}

}  // namespace xshade::harness
