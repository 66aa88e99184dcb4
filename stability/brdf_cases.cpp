// SHADERS.md section 5, cases 1-8, 10 and 11: the Cook-Torrance terms of include/brdf.hlsl on
// their hard inputs, through the probe stability/probes/brdf_terms.hlsl.
#include <fmt/core.h>

#include <cmath>
#include <numbers>

#include "harness/image/image_compare.h"
#include "stability/cases.h"
#include "stability/forms.h"
#include "stability/probe.h"

namespace xshade::stability {
namespace {

constexpr double kPi = std::numbers::pi;
// The largest finite fp16 value.
constexpr double kHalfMax = 65504.0;

// One input of the probe: the vectors and the knobs the terms read.
struct BrdfInput {
  std::string label;
  glm::vec3 n{0.0f, 0.0f, 1.0f};
  glm::vec3 v{0.0f, 0.0f, 1.0f};
  glm::vec3 l{0.0f, 0.0f, 1.0f};
  float a = 0.5f;
  float r0 = 0.04f;
  float LoH = 1.0f;  // the argument of fresnel() in row 0
  float metallic = 0.0f;
};

// What the probe wrote for one input.
struct BrdfOutput {
  double D, V, F, specular;              // row 0
  double direct, specular_cos, diffuse;  // row 1
};

// A direction at `cosine` to n = +z in the xz plane, on the +x side (or -x with `mirrored`).
glm::vec3 at_cosine(double cosine, bool mirrored = false) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cosine * cosine));
  return glm::vec3(float(mirrored ? -s : s), 0.0f, float(cosine));
}

Result<std::vector<BrdfOutput>> run_brdf(const CaseContext& context, const std::vector<BrdfInput>& inputs) {
  std::vector<glm::vec4> packed;
  for (const BrdfInput& in : inputs) {
    packed.push_back(glm::vec4(in.n, in.a));
    packed.push_back(glm::vec4(in.v, in.r0));
    packed.push_back(glm::vec4(in.l, in.LoH));
    packed.push_back(glm::vec4(in.metallic, 0.0f, 0.0f, 0.0f));
  }
  std::vector<std::string> labels;
  for (const BrdfInput& in : inputs) labels.push_back(in.label);
  auto image = run_probe(context, "brdf_terms.hlsl", 4, packed, 2, labels);
  if (!image) return fail(image.error());
  std::vector<BrdfOutput> outputs;
  for (uint32_t x = 0; x < image->width; ++x) {
    const glm::vec4 r0 = image->at(x, 0), r1 = image->at(x, 1);
    outputs.push_back({r0.x, r0.y, r0.z, r0.w, r1.x, r1.y, r1.z});
  }
  return outputs;
}

bool finite(double value) { return std::isfinite(value); }

std::string alpha_label(float a) { return "a = " + number(a); }

// ---- 5.1 and 5.11: the GGX peak -------------------------------------------------------------

Case ggx_peak() {
  Case c;
  c.id = "ggx_peak";
  c.title = "n = v = l: D = 1/(pi a^2)";
  c.section = "5.1";
  c.forms = {kSeed, kGuardsSeedD, kGuarded};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    std::vector<BrdfInput> inputs;
    for (float a : {0.002f, 0.0079f, 0.05f, 1.0f}) inputs.push_back({.label = alpha_label(a), .a = a});
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const double D = (*outputs)[i].D;
      const double expected = 1.0 / (kPi * double(inputs[i].a) * double(inputs[i].a));
      if (context.precision == Precision::Float) {
        // SHADERS.md's bound: 1e-5 relative is 80 fp32 ulps, room for the rounding of a handful
        // of operations and of kPi, and far below anything an image could show.
        measurements.push_back({inputs[i].label, "D", D, fmt::format("= {} +- 1e-5 relative", number(expected)),
                                finite(D) && std::abs(D - expected) <= 1e-5 * expected});
      } else {
        measurements.push_back(
            {inputs[i].label, "D", D, "finite and <= 65504 (fp16's largest)", finite(D) && D <= kHalfMax});
      }
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (precision == Precision::Float && form.seed)
      return {{},
              "Holds, though strict IEEE fp32 would not: the seed's denominator NoH^2 (a^2 - 1) + 1 is "
              "a^2 computed as 1 - (1 - a^2), which in strict fp32 loses 0.3% of D at a = 0.002 and "
              "1.3e-4 at a = 0.0079 (checked with a C program). GLSL lets a driver reassociate "
              "arithmetic, and Mesa's compiler folds the cancellation away at NoH = 1: the lanes "
              "measure D to 1e-6. The Lagrange form has no cancellation to rely on."};
    if (precision == Precision::Float) return {};
    if (form.name == kSeed.name)
      return {{"a = 0.002", "a = 0.0079"},
              "hazard 8: in fp16 a^2 - 1 rounds to -1 below a ~ 0.0156, so the seed's denominator is 0 and D = +inf."};
    if (form.name == kGuardsSeedD.name)
      return {{"a = 0.002", "a = 0.0079"},
              "hazard 8: the guards raise a to 0.0079 in fp16, where the seed's a^2 - 1 still rounds to -1: "
              "D = +inf. SHADERS.md's fp16 guard is the Lagrange form, the 'guarded' row."};
    return {};
  };
  return c;
}

Case ggx_peak_fp16() {
  Case c;
  c.id = "ggx_peak_fp16";
  c.title = "fp16 emulation of D at n = h: seed +inf for a <= 0.0156 and -15% at a = 0.03; guarded within 1%";
  c.section = "5.11";
  c.forms = {kSeed, kGuardsSeedD, kGuarded};
  c.precisions = {Precision::Half};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    std::vector<BrdfInput> inputs;
    for (float a : {0.0079f, 0.0156f, 0.02f, 0.03f, 0.05f, 0.1f, 0.25f, 1.0f})
      inputs.push_back({.label = alpha_label(a), .a = a});
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const double D = (*outputs)[i].D;
      const double expected = 1.0 / (kPi * double(inputs[i].a) * double(inputs[i].a));
      // SHADERS.md's bound for the guarded form in fp16: 1%, about 20 fp16 ulps.
      measurements.push_back({inputs[i].label, "D / (1/(pi a^2))", D / expected, "within 1% of 1",
                              finite(D) && std::abs(D / expected - 1.0) <= 0.01});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.name == kGuarded.name) return {};
    return {{"a = 0.0079", "a = 0.0156", "a = 0.02", "a = 0.03", "a = 0.05", "a = 0.1"},
            "hazard 8 as predicted: +inf at a <= 0.0156 (a^2 - 1 rounds to -1) and 15% low at a = 0.03 "
            "(a^2 - 1 rounds to -0.99902 instead of -0.9991). SHADERS.md stops at 0.03; the same "
            "rounding of a^2 - 1 to fp16's 11 bits puts a = 0.02 33% low and a = 0.05 and 0.1 5% high. "
            "At a = 0.25, 1 - a^2 = 0.9375 is an fp16 number and D is exact."};
  };
  return c;
}

// ---- 5.2: perfect smoothness ----------------------------------------------------------------

Case zero_alpha() {
  Case c;
  c.id = "zero_alpha";
  c.title = "a = 0 at NoH = 1 and 0.999: no NaN, every term >= 0";
  c.section = "5.2";
  c.forms = {kSeed, kGuardsSeedD, kGuarded};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    // v = l = h, so NoV = NoL = NoH.
    std::vector<BrdfInput> inputs;
    for (double NoH : {1.0, 0.999}) {
      const glm::vec3 h = at_cosine(NoH);
      inputs.push_back({.label = "a = 0, NoH = " + number(NoH), .v = h, .l = h, .a = 0.0f});
    }
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const BrdfOutput& out = (*outputs)[i];
      for (auto [name, value] : {std::pair{"D", out.D}, {"V", out.V}, {"D F V pi", out.specular}})
        measurements.push_back({inputs[i].label, name, value, "finite and >= 0", finite(value) && value >= 0.0});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (form.name == kSeed.name)
      return {{"a = 0, NoH = 1"}, "hazard 2: D = 0 / 0 at a = 0 and NoH = 1. At NoH = 0.999 it is 0 / 0.002 = 0."};
    if (form.name == kGuardsSeedD.name && precision == Precision::Half)
      return {{"a = 0, NoH = 1"}, "hazard 8: a is raised to 0.0079, but the seed's D still overflows fp16 there."};
    return {};
  };
  return c;
}

// ---- 5.3: grazing view -----------------------------------------------------------------------

Case grazing_view() {
  Case c;
  c.id = "grazing_view";
  c.title = "NoV in {0, 1e-6, 1e-4}, NoL = 0.5: finite, >= 0, f NoL bounded as NoV -> 0";
  c.section = "5.3";
  c.forms = {kSeed, kGuardsSeedD, kGuarded, kGuardedSmith, kGuardedSmithFast};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    const std::vector<double> cosines = {0.0, 1e-6, 1e-4};
    const std::vector<float> alphas = {0.05f, 0.5f, 1.0f};
    std::vector<BrdfInput> inputs;
    for (float a : alphas)
      for (double NoV : cosines)
        inputs.push_back({.label = fmt::format("NoV = {}, NoL = 0.5, a = {}", number(NoV), number(a)),
                          .v = at_cosine(NoV),
                          .l = at_cosine(0.5, true),
                          .a = a});
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t g = 0; g < alphas.size(); ++g) {
      // The value at the largest NoV of the group (1e-4) is what the smaller ones are held to.
      const double reference = (*outputs)[g * cosines.size() + cosines.size() - 1].specular_cos;
      for (size_t k = 0; k < cosines.size(); ++k) {
        const size_t i = g * cosines.size() + k;
        const double value = (*outputs)[i].specular_cos;
        // Bounded: as NoV falls from 1e-4 to 0 the lobe may not grow by more than 2x (a true
        // limit is finite; a term that diverges like 1/NoV grows 100x per decade).
        const bool ok = finite(value) && value >= 0.0 && finite(reference) && value <= 2.0 * reference + 1e-6;
        measurements.push_back({inputs[i].label, "f NoL (specular)", value,
                                fmt::format("finite, >= 0 and <= 2x its value at NoV = 1e-4 ({})", number(reference)),
                                ok});
      }
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.name == kSeed.name)
      return {{"NoV = 0, NoL = 0.5, a = 0.05", "NoV = 0, NoL = 0.5, a = 0.5", "NoV = 0, NoL = 0.5, a = 1"},
              "hazard 1: the Cook-Torrance G is 0 at NoV = 0 and the seed divides it by 4 NoL NoV = 0: 0/0 = NaN."};
    return {};
  };
  return c;
}

// ---- 5.4 and 5.5: light below the horizon, light and view on opposite horizons ---------------

Case light_below_horizon() {
  Case c;
  c.id = "light_below_horizon";
  c.title = "NoL in {0, -1e-3}: the direct term is exactly 0";
  c.section = "5.4";
  c.forms = {kSeed, kGuardsSeedD, kGuarded, kGuardedSmith, kGuardedSmithFast};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    std::vector<BrdfInput> inputs;
    for (float a : {0.05f, 0.5f})
      for (double NoL : {0.0, -1e-3})
        inputs.push_back({.label = fmt::format("NoL = {}, NoV = 0.7, a = {}", number(NoL), number(a)),
                          .v = at_cosine(0.7),
                          .l = at_cosine(NoL, true),
                          .a = a});
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const double value = (*outputs)[i].direct;
      measurements.push_back({inputs[i].label, "direct light", value, "exactly 0", value == 0.0});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.name == kSeed.name)
      return {{"NoL = 0, NoV = 0.7, a = 0.05", "NoL = 0, NoV = 0.7, a = 0.5"},
              "hazard 1 at the terminator: G = 0 divided by 4 NoL NoV = 0 is NaN, and NaN times "
              "saturate(NoL) = 0 stays NaN. Below the horizon (NoL = -1e-3) G and NoL are both "
              "negative, the quotient is finite, and saturate(NoL) = 0 makes the term 0."};
    return {};
  };
  return c;
}

Case opposite_horizon() {
  Case c;
  c.id = "opposite_horizon";
  c.title = "l = -v on the horizon: finite, and the direct term 0";
  c.section = "5.5";
  c.forms = {kSeed, kGuardsSeedD, kGuarded, kGuardedSmith, kGuardedSmithFast};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    std::vector<BrdfInput> inputs;
    for (float a : {0.05f, 0.5f})
      inputs.push_back(
          {.label = "l = -v = (1, 0, 0), a = " + number(a), .v = at_cosine(0.0, true), .l = at_cosine(0.0), .a = a});
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const BrdfOutput& out = (*outputs)[i];
      measurements.push_back({inputs[i].label, "D F V pi", out.specular, "finite", finite(out.specular)});
      measurements.push_back({inputs[i].label, "direct light", out.direct, "exactly 0", out.direct == 0.0});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.name == kSeed.name)
      return {{"l = -v = (1, 0, 0), a = 0.05", "l = -v = (1, 0, 0), a = 0.5"},
              "hazard 3: h = normalize(l + v) = normalize(0) = NaN, and every term after it."};
    return {};
  };
  return c;
}

// ---- 5.6 and 5.7: Fresnel -------------------------------------------------------------------

const std::vector<Form> kFresnelForms = {kSeed, kGuarded, kGuardedSG, kGuardedExactF};

Case loh_above_one() {
  Case c;
  c.id = "loh_above_one";
  c.title = "LoH = 1 + 1e-7: F within [R0, 1], no NaN";
  c.section = "5.6";
  c.forms = kFresnelForms;
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    // 1 + 1e-7 is not an fp32 number; the next fp32 number above 1 (1 + 2^-23) is what a
    // rounded dot product gives.
    const float above_one = std::nextafter(1.0f, 2.0f);
    std::vector<BrdfInput> inputs;
    for (float r0 : {0.04f, 0.56f}) {
      BrdfInput in{"LoH = 1 + 2^-23, R0 = " + number(r0)};
      in.r0 = r0;
      in.LoH = above_one;
      inputs.push_back(in);
    }
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const double F = (*outputs)[i].F;
      const double r0 = inputs[i].r0;
      // R0 as the probe's precision stores it: fp16 rounds 0.04 to 0.039978.
      const double floor = r0 - (context.precision == Precision::Half ? 5e-4 : 1e-7);
      measurements.push_back({inputs[i].label, "F", F, fmt::format("in [R0, 1] = [{}, 1]", number(r0)),
                              finite(F) && F >= floor && F <= 1.0});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (form.name == kSeed.name && precision == Precision::Float)
      return {{"LoH = 1 + 2^-23, R0 = 0.04", "LoH = 1 + 2^-23, R0 = 0.56"},
              "hazard 4: pow(1 - LoH, 5) of a negative base is undefined in GLSL; llvmpipe computes pow "
              "as exp2(5 log2(x)), and log2 of a negative number is NaN."};
    if (form.name == kSeed.name)
      return {{},
              "hazard 4 does not show in fp16: the seed's F takes half parameters, and 1 + 2^-23 rounds to "
              "exactly 1 in fp16, so the base is 0 and F = R0."};
    return {};
  };
  return c;
}

Case fresnel_endpoints() {
  Case c;
  c.id = "fresnel_endpoints";
  c.title = "F(LoH = 1) = R0, F(LoH = 0) = 1, monotone in between";
  c.section = "5.7";
  c.forms = kFresnelForms;
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    constexpr int kSteps = 32;
    std::vector<BrdfInput> inputs;
    const std::vector<float> r0s = {0.04f, 0.56f};
    for (float r0 : r0s)
      for (int k = 0; k <= kSteps; ++k) {
        BrdfInput in{fmt::format("LoH = {}, R0 = {}", number(double(k) / kSteps), number(r0))};
        in.r0 = r0;
        in.LoH = float(k) / float(kSteps);
        inputs.push_back(in);
      }
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    // 1e-3: a quarter of an 8-bit step. The spherical-Gaussian fit leaves 1.6e-4 (1 - R0) at
    // LoH = 1, fp16 rounds F by up to 4.9e-4 near 1; both are within it, a wrong endpoint is not.
    constexpr double kTolerance = 1e-3;
    std::vector<Measurement> measurements;
    for (size_t g = 0; g < r0s.size(); ++g) {
      const size_t first = g * (kSteps + 1);
      const double r0 = r0s[g];
      const double at_one = (*outputs)[first + kSteps].F, at_zero = (*outputs)[first].F;
      measurements.push_back({inputs[first + kSteps].label, "F", at_one, fmt::format("= R0 = {} +- 1e-3", number(r0)),
                              finite(at_one) && std::abs(at_one - r0) <= kTolerance});
      measurements.push_back(
          {inputs[first].label, "F", at_zero, "= 1 +- 1e-3", finite(at_zero) && std::abs(at_zero - 1.0) <= kTolerance});
      // Monotone: the largest rise from one step to the next, which must not exceed rounding.
      std::vector<double> sweep;
      for (int k = 0; k <= kSteps; ++k) sweep.push_back((*outputs)[first + k].F);
      const Rise rise = largest_rise(sweep);
      measurements.push_back({fmt::format("LoH from 0 to 1 in {} steps, R0 = {}", kSteps, number(r0)),
                              fmt::format("largest rise of F (at LoH = {})", number(inputs[first + rise.at].LoH)),
                              rise.value, "<= 1e-3 (non-increasing up to rounding)",
                              finite(rise.value) && rise.value <= kTolerance});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.name == kGuardedExactF.name)
      return {{"LoH from 0 to 1 in 32 steps, R0 = 0.56"},
              "Physics, not a hazard: the exact Fresnel of a dielectric whose R0 is 0.56 (index 6.9) dips "
              "near Brewster's angle, by 0.0085 at LoH = 0.31. The monotone shape SHADERS.md states is "
              "Schlick's; R0 = 0.56 is a metal's value, for which brdf.hlsl calls this form a reference of "
              "the shape only. At R0 = 0.04 it is monotone."};
    return {};
  };
  return c;
}

// ---- 5.10: the material grid ----------------------------------------------------------------

Case material_grid() {
  Case c;
  c.id = "material_grid";
  c.title = "material grid: no NaN/inf in any cell; diffuse non-increasing in metallic";
  c.section = "5.10";
  c.forms = {kSeed, kGuardsSeedD, kGuarded};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    std::vector<Measurement> measurements;
    std::string born_at;
    auto image = render_scene_with_form(context, "material_grid", &born_at);
    if (!image) return fail(image.error());
    const harness::NonFiniteCount bad = harness::count_non_finite(*image);
    measurements.push_back({"scene material_grid (5 x 5 cells, metallic x smoothness)", "NaN and inf channel values",
                            double(bad.nan + bad.inf), "0", bad.nan + bad.inf == 0, born_at});

    constexpr int kSteps = 16;
    std::vector<BrdfInput> inputs;
    for (int k = 0; k <= kSteps; ++k) {
      BrdfInput in{fmt::format("metallic = {}", number(double(k) / kSteps))};
      in.metallic = float(k) / float(kSteps);
      inputs.push_back(in);
    }
    auto outputs = run_brdf(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<double> diffuse;
    for (const BrdfOutput& out : *outputs) diffuse.push_back(out.diffuse);
    const double rise = largest_rise(diffuse).value;
    measurements.push_back({fmt::format("white albedo, metallic from 0 to 1 in {} steps", kSteps),
                            "largest rise of the diffuse colour", rise, "<= 0", rise <= 0.0});
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (form.seed && precision == Precision::Half)
      return {{"scene material_grid (5 x 5 cells, metallic x smoothness)"},
              "hazard 8: the seed's D overflows fp16 on the smoothest row (a = 0, or 0.0079 with the guards) and "
              "the infinity meets a zero: inf x 0 = NaN."};
    return {};
  };
  return c;
}

}  // namespace

std::vector<Case> brdf_cases() {
  return {ggx_peak(),      zero_alpha(),        grazing_view(),  light_below_horizon(), opposite_horizon(),
          loh_above_one(), fresnel_endpoints(), material_grid(), ggx_peak_fp16()};
}

}  // namespace xshade::stability
