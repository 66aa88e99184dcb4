// Renders a planned scene on one backend: the scene pass (every instance with its material),
// then each post effect's passes in order. The renderer supplies the uniforms a shader names
// (docs/shader_library.md lists them) and binds every texture by name.
#pragma once

#include <string>
#include <vector>

#include "harness/backend.h"
#include "harness/environment.h"
#include "harness/planner.h"
#include "harness/shader_cache.h"

namespace xshade::harness {

struct PassTiming {
  std::string pass;
  double milliseconds = 0.0;  // wall time of Backend::render, which runs the pass to completion
};

struct RenderedScene {
  FloatImage image;
  std::vector<PassTiming> timings;
};

// `variants` holds the compiled form of each of the plan's variants for this backend's lane.
Result<RenderedScene> render_scene(Backend& backend, const Scene& scene, const Plan& plan,
                                   const std::vector<CompiledVariant>& variants, const Environment& environment);

// The environment description of a scene's [environment] table.
EnvironmentDesc environment_desc(const EnvironmentSpec& spec);

}  // namespace xshade::harness
