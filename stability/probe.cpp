#include "stability/probe.h"

#include <fmt/core.h>

#include <cstring>

#include "harness/assets/environment.h"
#include "harness/image/image_compare.h"
#include "harness/render/evaluate.h"
#include "harness/render/nonfinite_origins.h"
#include "harness/render/planner.h"
#include "harness/render/scene_renderer.h"
#include "harness/scene/scene.h"

namespace xshade::stability {

Result<const harness::FullscreenProgram*> ProbePrograms::get(const CaseContext& context, const std::string& file,
                                                             bool traced) {
  std::string key = file + (context.precision == Precision::Half ? " half" : "") + (traced ? " traced" : "");
  for (const std::string& keyword : context.form.keywords) key += " " + keyword;
  if (auto known = programs_.find(key); known != programs_.end()) return &known->second;

  hlsl::CompileOptions options;
  options.include_dirs = {context.shaders_dir};
  options.keywords = context.form.keywords;
  if (context.precision == Precision::Half) options.defines.push_back({harness::kHalfEmulationMacro, "1"});
  const auto path = context.probes_dir / file;
  auto module = hlsl::compile_file(path, options);
  if (!module->ok())
    return fail(ErrorKind::UserInput, path.string() + " does not compile:\n" + module->diagnostics.render_all());
  auto program = harness::FullscreenProgram::create(
      *module, context.lane, context.backend,
      {.half_emulation = context.precision == Precision::Half, .trace_nonfinite = traced});
  if (!program) return fail(program.error());
  return &programs_.emplace(key, std::move(*program)).first->second;
}

Result<harness::FloatImage> run_probe(const CaseContext& context, const std::string& file, uint32_t vectors_per_input,
                                      const std::vector<glm::vec4>& inputs, uint32_t rows,
                                      const std::vector<std::string>& labels) {
  auto program = context.probes.get(context, file);
  if (!program) return fail(program.error());
  const std::optional<uint32_t> size = (*program)->constant_buffer_size("ProbeInputs");
  if (!size) return fail(ErrorKind::UserInput, file + " has no constant buffer ProbeInputs");
  std::vector<std::byte> bytes(*size);
  if (inputs.size() * sizeof(glm::vec4) > bytes.size())
    return fail(ErrorKind::UserInput,
                fmt::format("{} inputs do not fit {}'s ProbeInputs", inputs.size() / vectors_per_input, file));
  std::memcpy(bytes.data(), inputs.data(), inputs.size() * sizeof(glm::vec4));
  const auto columns = uint32_t(inputs.size() / vectors_per_input);
  auto image = (*program)->run(context.backend, columns, rows, {.constant_buffers = {{"ProbeInputs", bytes}}});
  if (!image || labels.empty() || context.lane == harness::Lane::VkHlsl) return image;
  const harness::NonFiniteCount bad = harness::count_non_finite(*image);
  if (bad.nan + bad.inf == 0) return image;
  // Again, traced: which line of the library made each column's first NaN or infinity.
  auto traced = context.probes.get(context, file, /*traced=*/true);
  if (!traced) return fail(traced.error());
  harness::FloatImage record;
  auto again = (*traced)->run(context.backend, columns, rows, {.constant_buffers = {{"ProbeInputs", std::move(bytes)}}},
                              &record);
  if (!again) return fail(again.error());
  const glsl::NonfiniteTrace& table = (*traced)->trace();
  for (uint32_t x = 0; x < columns && x < labels.size(); ++x)
    for (uint32_t y = 0; y < rows; ++y) {
      const glsl::TraceSite* site = table.site_in(uint32_t(record.at(x, y).r));
      if (!site) continue;
      context.born_at[labels[x]] = site_text(*site);
      break;
    }
  return image;
}

Result<harness::FloatImage> render_scene_with_form(const CaseContext& context, const std::string& scene_name,
                                                   std::string* born_at) {
  auto scene = harness::load_scene(context.scenes_dir / (scene_name + ".toml"));
  if (!scene) return fail(scene.error());
  for (harness::SceneObject& object : scene->objects) object.keywords = context.form.keywords;
  auto plan = harness::plan_scene(*scene, context.shaders_dir);
  if (!plan) return fail(plan.error());
  auto variants = context.compiler.compile_plan(*plan, context.lane, context.precision == Precision::Half);
  if (!variants) return fail(variants.error());
  auto environment = harness::build_environment(scene->environment);
  if (!environment) return fail(environment.error());
  auto rendered = harness::render_scene(context.backend, *scene, *plan, *variants, *environment);
  if (!rendered) return fail(rendered.error());
  const harness::NonFiniteCount bad = harness::count_non_finite(rendered->image);
  if (!born_at || bad.nan + bad.inf == 0 || context.lane == harness::Lane::VkHlsl) return std::move(rendered->image);
  auto traced_variants = context.compiler.compile_plan(*plan, context.lane, context.precision == Precision::Half,
                                                       /*trace_nonfinite=*/true);
  if (!traced_variants) return fail(traced_variants.error());
  auto traced = harness::render_scene(context.backend, *scene, *plan, *traced_variants, *environment,
                                      {.keep_pass_images = true, .trace_nonfinite = true});
  if (!traced) return fail(traced.error());
  auto born = first_born_at(*traced, *traced_variants);
  if (!born) return fail(born.error());
  *born_at = std::move(*born);
  return std::move(rendered->image);
}

std::string site_text(const glsl::TraceSite& site) {
  return fmt::format("{}:{}: {}", std::filesystem::path(site.file).filename().string(), site.line,
                     glsl::describe_site(site));
}

Result<std::string> first_born_at(const harness::RenderedScene& traced,
                                  const std::vector<harness::CompiledVariant>& variants) {
  for (size_t i = 0; i < traced.traces.size() && i < traced.pass_images.size(); ++i) {
    const harness::FloatImage& image = traced.pass_images[i].second;
    const harness::NonFiniteCount bad = harness::count_non_finite(image);
    if (bad.nan + bad.inf == 0) continue;
    auto origins = harness::find_nonfinite_origins(image, traced.traces[i], variants, /*count_negative=*/false);
    if (!origins) return fail(origins.error());
    if (origins->origins.empty()) continue;
    size_t pixels = 0;
    for (const harness::NonfiniteOrigin& origin : origins->origins) pixels += origin.pixels;
    const harness::NonfiniteOrigin& most = origins->origins.front();
    return fmt::format("{} (pass {}, {} of {} pixels)", site_text(most.site), traced.traces[i].pass, most.pixels,
                       pixels);
  }
  return std::string();
}

Rise largest_rise(const std::vector<double>& values) {
  Rise rise;
  for (size_t k = 1; k < values.size(); ++k) {
    const double step = values[k] - values[k - 1];
    if (!(step <= rise.value)) rise = {step, k};
  }
  return rise;
}

std::string number(double value) { return fmt::format("{:.6g}", value); }

}  // namespace xshade::stability
