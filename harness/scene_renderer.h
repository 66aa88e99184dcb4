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
  // With RenderOptions::keep_pass_images: each pass's own output, in order (name, image), to
  // find the pass where lanes part.
  std::vector<std::pair<std::string, FloatImage>> pass_images;
  // The sum of the pass times of each frame, in order. The first frame also creates the
  // programs, meshes, textures and targets (and drivers compile their pipelines then).
  std::vector<double> frame_milliseconds;
};

struct RenderOptions {
  bool keep_pass_images = false;
  uint32_t frames = 1;  // rendered one after another with the same resources; the last one is returned
};

// `variants` holds the compiled form of each of the plan's variants for this backend's lane.
Result<RenderedScene> render_scene(Backend& backend, const Scene& scene, const Plan& plan,
                                   const std::vector<CompiledVariant>& variants, const Environment& environment,
                                   const RenderOptions& options = {});

}  // namespace xshade::harness
