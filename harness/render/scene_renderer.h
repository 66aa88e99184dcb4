// Renders a planned scene on one backend: the scene pass (every instance with its material),
// then each post effect's passes in order. The renderer supplies the uniforms a shader names
// (docs/shader_library.md lists them) and binds every texture by name. The post effects can also
// run alone, on a colour and depth image given by the caller (the stability suite's inputs).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "harness/assets/environment.h"
#include "harness/backend/backend.h"
#include "harness/render/planner.h"
#include "harness/render/shader_cache.h"

namespace xshade::harness {

struct PassTiming {
  std::string pass;
  double milliseconds = 0.0;  // wall time of Backend::render, which runs the pass to completion
};

// What a traced pass recorded (glsl::NonfiniteTrace says how it reads), by the pass's name.
struct PassTrace {
  std::string pass;
  FloatImage record;
};

struct RenderedScene {
  FloatImage image;
  std::vector<PassTiming> timings;  // of the last frame
  // With RenderOptions::keep_pass_images: each pass's own output, in order (name, image), to
  // find the pass where lanes part.
  std::vector<std::pair<std::string, FloatImage>> pass_images;
  // The pass times of each frame, in order. The first frame also creates the programs, meshes,
  // textures and targets (and drivers compile their pipelines then).
  std::vector<std::vector<PassTiming>> frame_timings;
  // With RenderOptions::trace_nonfinite: each pass's record, in order, of the last frame.
  std::vector<PassTrace> traces = {};
};

// The time of the passes of one frame whose name starts with `prefix` ("" for all of them).
double milliseconds_of(const std::vector<PassTiming>& frame, std::string_view prefix = {});

// Programs kept across renders on one backend, by their code: a later render of the same code (on
// other images, at another size, with other parameters, or from another keyword set that compiles
// to the same pass) reuses the program instead of creating it again, which llvmpipe's OpenGL
// compiles anew every time. The backend owns the programs: a cache serves one backend only and
// must not outlive it.
class ProgramCache {
 public:
  Result<ProgramHandle> program(Backend& backend, const ProgramDesc& desc);

 private:
  Backend* backend_ = nullptr;
  std::map<std::string, ProgramHandle> programs_;  // by the stages' code
};

struct RenderOptions {
  bool keep_pass_images = false;
  uint32_t frames = 1;               // rendered one after another with the same resources; the last one is returned
  ProgramCache* programs = nullptr;  // when given, programs come from it (and go into it)
  // Told each pass's name before it is drawn: where a render that hangs or crashes was.
  std::function<void(std::string_view pass)> on_pass = {};
  // The variants are tracing variants (VariantCompiler::compile_plan): every target gets the
  // second colour attachment they record into, and each pass's record is read back.
  bool trace_nonfinite = false;
};

// `variants` holds the compiled form of each of the plan's variants for this backend's lane.
Result<RenderedScene> render_scene(Backend& backend, const Scene& scene, const Plan& plan,
                                   const std::vector<CompiledVariant>& variants, const Environment& environment,
                                   const RenderOptions& options = {});

// Runs the plan's post passes (and no scene pass) on `color` and `depth` instead of the scene
// pass's target: every pass input that names scene.color reads `color` (RGBA32F), every one that
// names scene.depth reads the red channel of `depth` (the depth-buffer value, 0 at the near plane
// and 1 at the far plane). Both must be scene.width x scene.height; the uniforms are those of
// render_scene (_CameraNearFar from scene.camera, X_TexelSize of each input). Fails when the
// plan has no post pass.
Result<RenderedScene> render_post_effects(Backend& backend, const Scene& scene, const Plan& plan,
                                          const std::vector<CompiledVariant>& variants, const FloatImage& color,
                                          const FloatImage& depth, const RenderOptions& options = {});

}  // namespace xshade::harness
