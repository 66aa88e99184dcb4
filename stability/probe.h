// Running the library's shader code for a case: a probe shader over a row of inputs, or a scene
// file of the project with the case's form.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/image/image.h"
#include "harness/render/evaluate.h"
#include "stability/case.h"

namespace xshade::stability {

// The probe programs made so far on one backend, by file, keywords and precision: the driver
// compiles each once, however many cases run it.
class ProbePrograms {
 public:
  // With `traced`, the probe's tracing variant (glsl::EmitOptions::trace_nonfinite).
  Result<const harness::FullscreenProgram*> get(const CaseContext& context, const std::string& file,
                                                bool traced = false);

 private:
  std::map<std::string, harness::FullscreenProgram> programs_;
};

// Renders the probe `file` (in the context's probes folder, compiled with the form's keywords)
// as a full-screen pass of inputs.size() / vectors_per_input columns and `rows` rows; its
// constant buffer ProbeInputs holds `inputs`, zero-padded to the probe's size.
// With `labels` (one per column), where a column's first NaN or infinity was born goes into
// context.born_at under its label: the probe runs again traced when the image has any (gl and vk).
Result<harness::FloatImage> run_probe(const CaseContext& context, const std::string& file, uint32_t vectors_per_input,
                                      const std::vector<glm::vec4>& inputs, uint32_t rows,
                                      const std::vector<std::string>& labels = {});

// Renders a scene of the project (scenes/NAME.toml) with every object's keywords
// replaced by the form's.
// With `born_at`, where most of its NaN and infinities were born, when it has any: the scene
// renders again traced (gl and vk).
Result<harness::FloatImage> render_scene_with_form(const CaseContext& context, const std::string& scene_name,
                                                   std::string* born_at = nullptr);

// "brdf.hlsl:19: the value D_GGX_seed returns": a traced site as the case notes name it.
std::string site_text(const glsl::TraceSite& site);

// Where most of a traced render's NaN and infinities were born: the leading site of the first
// pass whose image has any (the render kept its pass images), with its pass and pixels; empty
// when no pass has any.
Result<std::string> first_born_at(const harness::RenderedScene& traced,
                                  const std::vector<harness::CompiledVariant>& variants);

// The largest rise from one value to the next, and the index of the later value; NaN if a
// difference is NaN.
struct Rise {
  double value = -INFINITY;
  size_t at = 0;
};
Rise largest_rise(const std::vector<double>& values);

// "0.002", "1e-07", "-inf": a number as the case tables show it.
std::string number(double value);

}  // namespace xshade::stability
