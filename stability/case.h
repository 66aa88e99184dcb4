// The stability suite's vocabulary: a case of SHADERS.md section 5, the forms of the library it
// runs (keyword sets), what it measured, and what SHADERS.md predicts for the seed's forms.
//
// A case runs the library's own shader code on a lane (a probe shader that calls the library's
// functions, or the library's post effect itself) and checks each input's results against a
// bound that C++ computes. Nothing here re-implements a formula of the library.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/render/lanes.h"
#include "harness/render/scene_renderer.h"
#include "harness/render/variant_compiler.h"

namespace xshade::stability {

enum class Precision {
  Float,  // fp32: half is float, as on a desktop GPU
  Half,   // half emulation: every half-typed result rounded to fp16 (GLSL lanes only)
};
std::string_view precision_name(Precision precision);

// One form of the library a case runs: the keywords its shader is compiled with.
struct Form {
  std::string name;                   // "seed", "guarded", "guarded+smith", ...
  std::vector<std::string> keywords;  // as a material or effect would be compiled with
  bool seed = false;                  // the seed's own form: allowed to fail where predicted
};

// What one input of a case gave, and whether it kept the case's bound.
struct Measurement {
  std::string input;     // "a = 0.002, NoH = 1": enough to reproduce it
  std::string quantity;  // "D", "E(v)", "output energy"
  double value = 0.0;    // what the shader computed (NaN and infinities as they came)
  std::string bound;     // "= 79577.5 +- 1e-5 relative", "finite and in [0, 1]"
  bool ok = true;
  // Where a NaN or infinity in the value was born (the tracing variant, gl and vk): "brdf.hlsl:19:
  // the value D_GGX_seed returns"; empty for a finite value or where nothing traced it.
  std::string born_at = {};
};

class ProbePrograms;

// Where the shader code for a case comes from and runs.
struct CaseContext {
  harness::Backend& backend;
  harness::Lane lane;
  Precision precision;
  const Form& form;
  const std::filesystem::path& shaders_dir;  // the shader library (shaders)
  const std::filesystem::path& probes_dir;   // the suite's probe shaders (stability/probes)
  const std::filesystem::path& scenes_dir;   // the project's scenes (scenes)
  harness::VariantCompiler& compiler;        // for cases that run the library's post effects
  ProbePrograms& probes;                     // the probes compiled so far on this backend
  harness::ProgramCache& programs;           // the effects' programs made so far on this backend
  // Where the non-finite values of a probe's inputs were born, by input label (run_probe with
  // labels fills it), or under "*" for a whole image's (the depth of field's); the suite copies
  // it into the non-finite measurements of those inputs, or of the run.
  std::map<std::string, std::string>& born_at;
};

// What SHADERS.md says a form does on a case at a precision: the inputs (Measurement::input)
// at which it breaks, and why. An empty set: it must keep the bound at every input.
struct Prediction {
  std::set<std::string> failing_inputs;
  std::string note;
};

struct Case {
  std::string id;       // "ggx_peak": names the CTest test and the row of docs/stability.md
  std::string title;    // "n = v = l: D = 1/(pi a^2)"
  std::string section;  // "5.1": where SHADERS.md states it
  std::vector<Form> forms;
  std::vector<Precision> precisions = {Precision::Float, Precision::Half};
  // Runs the form on the context's lane; fails when the shader does not compile or run.
  std::function<Result<std::vector<Measurement>>(const CaseContext&)> run;
  // Defaults to "passes everywhere".
  std::function<Prediction(const Form&, Precision)> predict;
};

}  // namespace xshade::stability
