#include "accuracy/measure.h"

#include <algorithm>
#include <chrono>

#include "harness/assets/environment.h"
#include "harness/image/image_compare.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"
#include "harness/scene/scene.h"

namespace xshade::accuracy {
namespace {

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

harness::Scene configured(const harness::Scene& base, const Configuration& configuration) {
  harness::Scene scene = base;
  if (configuration.material_keywords)
    for (harness::SceneObject& object : scene.objects) object.keywords = *configuration.material_keywords;
  for (harness::SceneObject& object : scene.objects)
    for (const auto& [name, value] : configuration.object_parameters)
      object.properties[name] = harness::PropertyValue::scalar(value);
  for (harness::PostEffect& effect : scene.post) {
    if (configuration.post_keywords) effect.keywords = *configuration.post_keywords;
    for (const auto& [name, value] : configuration.post_parameters)
      effect.parameters[name] = harness::PropertyValue::scalar(value);
  }
  for (harness::Light& light : scene.lights) {
    if (light.shadows == harness::Light::Shadows::None) continue;
    if (configuration.shadow_resolution) light.shadow_resolution = *configuration.shadow_resolution;
    if (configuration.soft_shadows)
      light.shadows = *configuration.soft_shadows ? harness::Light::Shadows::Soft : harness::Light::Shadows::Hard;
  }
  scene.width *= configuration.supersample;
  scene.height *= configuration.supersample;
  return scene;
}

// A configuration compiled and rendered once: its image, and what timing it again needs.
struct Prepared {
  harness::Scene scene;
  harness::Plan plan;
  std::vector<harness::CompiledVariant> variants;
  ConfigurationResult result;
  std::vector<double> times;
};

Result<Prepared> prepare(const Configuration& configuration, const harness::Scene& base, harness::Lane lane,
                         harness::Backend& backend, const harness::Environment& environment,
                         const MeasureOptions& options, harness::ProgramCache& programs) {
  Prepared prepared;
  prepared.scene = configured(base, configuration);
  std::vector<std::filesystem::path> folders = options.shader_folders;
  folders.push_back(options.shaders_dir);
  const harness::ShaderSearchPath shaders(folders);
  auto plan = harness::plan_scene(prepared.scene, shaders);
  if (!plan) return fail(plan.error());
  prepared.plan = std::move(*plan);

  // No cache: the compile time is what a cold build of this configuration costs.
  harness::VariantCompiler compiler(shaders, nullptr);
  const auto compile_start = std::chrono::steady_clock::now();
  auto variants = compiler.compile_plan(prepared.plan, lane, configuration.half_emulation);
  if (!variants) return fail(variants.error().kind, configuration.label + ": " + variants.error().to_string());
  prepared.variants = std::move(*variants);
  prepared.result.label = configuration.label;
  prepared.result.compile_ms = milliseconds_since(compile_start);

  auto rendered = harness::render_scene(backend, prepared.scene, prepared.plan, prepared.variants, environment,
                                        {.programs = &programs});
  if (!rendered) return fail(rendered.error().kind, configuration.label + ": " + rendered.error().to_string());
  prepared.result.image = configuration.supersample > 1 ? box_downsample(rendered->image, configuration.supersample)
                                                        : std::move(rendered->image);
  return prepared;
}

// One round of timing: a warm-up frame (resources are made again; programs come from the
// cache), then the timed frames.
Result<void> time_round(const Study& study, Prepared& prepared, harness::Backend& backend,
                        const harness::Environment& environment, const MeasureOptions& options,
                        harness::ProgramCache& programs) {
  auto rendered =
      harness::render_scene(backend, prepared.scene, prepared.plan, prepared.variants, environment,
                            {.frames = options.warmup_frames + options.frames_per_round, .programs = &programs});
  if (!rendered) return fail(rendered.error().kind, prepared.result.label + ": " + rendered.error().to_string());
  for (size_t frame = options.warmup_frames; frame < rendered->frame_timings.size(); ++frame)
    prepared.times.push_back(harness::milliseconds_of(rendered->frame_timings[frame], study.timed_passes));
  return {};
}

void judge(ConfigurationResult& result, const ConfigurationResult& reference,
           const harness::CompareSettings& settings) {
  const harness::Comparison comparison = harness::compare_images(result.image, reference.image, settings);
  result.error = comparison.metrics;
  result.failing_fraction = comparison.metrics.failing_fraction;
}

}  // namespace

Timing summarize(std::vector<double> samples) {
  Timing timing;
  timing.repetitions = samples.size();
  if (samples.empty()) return timing;
  std::sort(samples.begin(), samples.end());
  auto quantile = [&](double q) {
    const double position = q * double(samples.size() - 1);
    const auto below = size_t(position);
    const size_t above = std::min(below + 1, samples.size() - 1);
    return samples[below] + (position - double(below)) * (samples[above] - samples[below]);
  };
  timing.q1_ms = quantile(0.25);
  timing.median_ms = quantile(0.5);
  timing.q3_ms = quantile(0.75);
  return timing;
}

harness::FloatImage box_downsample(const harness::FloatImage& image, uint32_t k) {
  harness::FloatImage out(image.width / k, image.height / k);
  const float weight = 1.0f / float(k * k);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      glm::vec4 sum(0.0f);
      for (uint32_t j = 0; j < k; ++j)
        for (uint32_t i = 0; i < k; ++i) sum += image.at(x * k + i, y * k + j);
      out.set(x, y, sum * weight);
    }
  return out;
}

Result<StudyResult> measure_study(const Study& study, harness::Lane lane, harness::Backend& backend,
                                  const MeasureOptions& options) {
  auto scene = harness::load_scene(options.scenes_dir / (study.scene + ".toml"));
  if (!scene) return fail(scene.error());
  auto environment = harness::build_environment(scene->environment);
  if (!environment) return fail(environment.error());
  harness::ProgramCache programs;

  StudyResult result{study.id, lane, {}, std::nullopt, {}, {}};
  auto reference = prepare(study.reference, *scene, lane, backend, *environment, options, programs);
  if (!reference) return fail(reference.error());
  result.reference = std::move(reference->result);
  if (study.reference_check && options.reference_check) {
    auto check = prepare(*study.reference_check, *scene, lane, backend, *environment, options, programs);
    if (!check) return fail(check.error());
    judge(check->result, result.reference, scene->compare);
    result.reference_check = std::move(check->result);
  }
  std::vector<Prepared> measured;
  for (const Configuration& configuration : study.configurations) {
    if (configuration.half_emulation && lane == harness::Lane::VkHlsl) {
      result.skipped.push_back(configuration.label +
                               ": vk-hlsl compiles the source with glslang, which cannot emulate fp16");
      continue;
    }
    if (configuration.soft_shadows.value_or(false) && lane == harness::Lane::VkHlsl) {
      result.skipped.push_back(configuration.label +
                               ": lavapipe cannot filter a depth texture, and glslang's HLSL output "
                               "leaves the filtering to it");
      continue;
    }
    auto prepared = prepare(configuration, *scene, lane, backend, *environment, options, programs);
    if (!prepared) return fail(prepared.error());
    judge(prepared->result, result.reference, scene->compare);
    measured.push_back(std::move(*prepared));
  }
  // The configurations take turns, round after round, so that a slow spell of a shared machine
  // falls on all of them rather than on whichever was being timed.
  for (uint32_t round = 0; round < options.rounds; ++round)
    for (Prepared& prepared : measured)
      if (auto timed = time_round(study, prepared, backend, *environment, options, programs); !timed)
        return fail(timed.error());
  for (Prepared& prepared : measured) {
    prepared.result.time = summarize(std::move(prepared.times));
    result.configurations.push_back(std::move(prepared.result));
  }
  return result;
}

}  // namespace xshade::accuracy
