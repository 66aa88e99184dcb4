// Running the library's shader code for a case: a probe shader over a row of inputs, or a scene
// file of the project with the case's form.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/render/evaluate.h"
#include "harness/image/image.h"
#include "stability/case.h"

namespace xshade::stability {

// The probe programs made so far on one backend, by file, keywords and precision: the driver
// compiles each once, however many cases run it.
class ProbePrograms {
 public:
  Result<const harness::FullscreenProgram*> get(const CaseContext& context, const std::string& file);

 private:
  std::map<std::string, harness::FullscreenProgram> programs_;
};

// Renders the probe `file` (in the context's probes folder, compiled with the form's keywords)
// as a full-screen pass of inputs.size() / vectors_per_input columns and `rows` rows; its
// constant buffer ProbeInputs holds `inputs`, zero-padded to the probe's size.
Result<harness::FloatImage> run_probe(const CaseContext& context, const std::string& file, uint32_t vectors_per_input,
                                      const std::vector<glm::vec4>& inputs, uint32_t rows);

// Renders a scene of the project (scenes/NAME.toml) with every object's keywords
// replaced by the form's.
Result<harness::FloatImage> render_scene_with_form(const CaseContext& context, const std::string& scene_name);

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
