#include "stability/probe.h"

#include <fmt/core.h>

#include <cstring>

#include "harness/assets/environment.h"
#include "harness/render/evaluate.h"
#include "harness/render/planner.h"
#include "harness/scene/scene.h"
#include "harness/render/scene_renderer.h"

namespace xshade::stability {

Result<const harness::FullscreenProgram*> ProbePrograms::get(const CaseContext& context, const std::string& file) {
  std::string key = file + (context.precision == Precision::Half ? " half" : "");
  for (const std::string& keyword : context.form.keywords) key += " " + keyword;
  if (auto known = programs_.find(key); known != programs_.end()) return &known->second;

  hlsl::CompileOptions options;
  options.include_dirs = {context.shaders_dir};
  options.keywords = context.form.keywords;
  if (context.precision == Precision::Half) options.defines.push_back({harness::kHalfEmulationMacro, "1"});
  const auto path = context.probes_dir / file;
  auto module = hlsl::compile_file(path, options);
  if (!module->ok()) return fail(path.string() + " does not compile:\n" + module->diagnostics.render_all());
  auto program = harness::FullscreenProgram::create(*module, context.lane, context.backend,
                                                    {.half_emulation = context.precision == Precision::Half});
  if (!program) return fail(program.error());
  return &programs_.emplace(key, std::move(*program)).first->second;
}

Result<harness::FloatImage> run_probe(const CaseContext& context, const std::string& file, uint32_t vectors_per_input,
                                      const std::vector<glm::vec4>& inputs, uint32_t rows) {
  auto program = context.probes.get(context, file);
  if (!program) return fail(program.error());
  const std::optional<uint32_t> size = (*program)->constant_buffer_size("ProbeInputs");
  if (!size) return fail(file + " has no constant buffer ProbeInputs");
  std::vector<std::byte> bytes(*size);
  if (inputs.size() * sizeof(glm::vec4) > bytes.size())
    return fail(fmt::format("{} inputs do not fit {}'s ProbeInputs", inputs.size() / vectors_per_input, file));
  std::memcpy(bytes.data(), inputs.data(), inputs.size() * sizeof(glm::vec4));
  const auto columns = uint32_t(inputs.size() / vectors_per_input);
  return (*program)->run(context.backend, columns, rows, {{"ProbeInputs", std::move(bytes)}});
}

Result<harness::FloatImage> render_scene_with_form(const CaseContext& context, const std::string& scene_name) {
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
  return std::move(rendered->image);
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
