// SHADERS.md section 5, case 12: the toon terms of include/toon.hlsl on their hard inputs,
// through the probe stability/probes/toon_terms.hlsl.
#include <fmt/core.h>

#include <cmath>

#include "stability/cases.h"
#include "stability/forms.h"
#include "stability/probe.h"

namespace xshade::stability {
namespace {

struct ToonInput {
  std::string label;
  float NoL, NoV, NoH;
  float smooth;  // the ramp's, specular's and rim's smoothing alike
  float shininess, gloss;
  float threshold = 0.5f;  // the ramp's and the rim's
  float atten = 1.0f;
};

struct ToonOutput {
  double ramp, specular, rim;
};

Result<std::vector<ToonOutput>> run_toon(const CaseContext& context, const std::vector<ToonInput>& inputs) {
  std::vector<glm::vec4> packed;
  for (const ToonInput& in : inputs) {
    packed.push_back({in.NoL, in.NoV, in.NoH, in.atten});
    packed.push_back({in.threshold, in.smooth, in.shininess, in.gloss});
  }
  std::vector<std::string> labels;
  for (const ToonInput& in : inputs) labels.push_back(in.label);
  auto image = run_probe(context, "toon_terms.hlsl", 2, packed, 1, labels);
  if (!image) return fail(image.error());
  std::vector<ToonOutput> outputs;
  for (uint32_t x = 0; x < image->width; ++x) {
    const glm::vec4 p = image->at(x, 0);
    outputs.push_back({p.x, p.y, p.z});
  }
  return outputs;
}

bool in_unit_range(double value) { return std::isfinite(value) && value >= 0.0 && value <= 1.0; }

Case toon_hard_inputs() {
  Case c;
  c.id = "toon_hard_inputs";
  c.title = "toon: smoothing 0 or -0.1, gloss 0, NoV = -0.2, NoL = -0.5: every term finite and in [0, 1]";
  c.section = "5.12";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    struct Dots {
      float NoL, NoV, NoH;
    };
    // SHADERS.md's inputs; then every term exactly on its edge (NoL = 0 puts the half-Lambert
    // ramp at its threshold 0.5; NoV = 0 with NoL = 0.5 puts the rim there) with NoH = 0 for
    // pow(0, 0).
    const std::vector<Dots> dots = {{-0.5f, -0.2f, -0.3f}, {0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 1.0f}};
    struct Knobs {
      float shininess, gloss;
    };
    const std::vector<Knobs> knobs = {{0.2f, 1.0f}, {0.0f, 0.0f}};
    std::vector<ToonInput> inputs;
    for (const Dots& d : dots)
      for (float smooth : {0.0f, -0.1f})
        for (const Knobs& k : knobs)
          inputs.push_back(
              {fmt::format("NoL = {}, NoV = {}, NoH = {}, smooth = {}, shininess = {}, gloss = {}", number(d.NoL),
                           number(d.NoV), number(d.NoH), number(smooth), number(k.shininess), number(k.gloss)),
               d.NoL, d.NoV, d.NoH, smooth, k.shininess, k.gloss});
    auto outputs = run_toon(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const ToonOutput& out = (*outputs)[i];
      for (auto [name, value] : {std::pair{"ramp", out.ramp}, {"specular", out.specular}, {"rim", out.rim}})
        measurements.push_back({inputs[i].label, name, value, "finite and in [0, 1]", in_unit_range(value)});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.seed)
      return {{},
              "Holds, against hazards 5-7: every seed term ends in smoothstep, and Mesa computes it as "
              "saturate((x - e0) / (e1 - e0)) with a saturate that turns NaN into 0. So pow(0, 0) and "
              "0/0 at a zero-width edge come out 0, and a rim factor of -0.6 or 1.2 is clamped. The "
              "hazards are undefined behaviour that these drivers happen to resolve to finite values; "
              "toon_hard_edge shows the seed's wrong steps."};
    return {};
  };
  return c;
}

Case toon_hard_edge() {
  Case c;
  c.id = "toon_hard_edge";
  c.title = "toon: smoothing 0 or -0.1 still gives a step: ramp 0 in shadow, 1 in light, 0.5 at the threshold";
  c.section = "5.12";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    // The half-Lambert ramp's argument is NoL * 0.5 + 0.5: NoL = 0 is its threshold 0.5.
    const std::vector<std::pair<float, double>> expected = {{-0.5f, 0.0}, {0.0f, 0.5}, {0.5f, 1.0}};
    std::vector<ToonInput> inputs;
    for (float smooth : {0.0f, -0.1f})
      for (const auto& [NoL, value] : expected)
        inputs.push_back(
            {fmt::format("NoL = {}, smooth = {}", number(NoL), number(smooth)), NoL, 0.5f, 0.5f, smooth, 0.2f, 1.0f});
    auto outputs = run_toon(context, inputs);
    if (!outputs) return fail(outputs.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < inputs.size(); ++i) {
      const double want = expected[i % expected.size()].second;
      // A step is exactly 0 and 1 away from its edge, and smoothstep's midpoint is exactly 0.5.
      // fp16 rounds each edge by up to 2.4e-4 (half an ulp near 0.5); across a band of 0.1 that
      // moves the midpoint's value by up to 1.5 x 2.4e-4 / 0.1 = 3.6e-3: hence 5e-3.
      const double value = (*outputs)[i].ramp;
      measurements.push_back({inputs[i].label, "ramp", value, fmt::format("= {} +- 5e-3", number(want)),
                              std::isfinite(value) && std::abs(value - want) <= 5e-3});
    }
    return measurements;
  };
  c.predict = [](const Form& form, Precision) -> Prediction {
    if (form.seed)
      return {{"NoL = 0, smooth = 0", "NoL = -0.5, smooth = -0.1", "NoL = 0.5, smooth = -0.1"},
              "hazard 5: smoothstep with edge0 >= edge1 is undefined in GLSL. Mesa computes "
              "saturate((x - e0) / (e1 - e0)): with smoothing 0 the threshold itself is 0/0, which the "
              "saturate turns into 0 (finite, but not the step's midpoint); with -0.1 the edges swap and "
              "the ramp comes out inverted, lit in shadow and dark in light. Every value stays finite and "
              "in [0, 1], so toon_hard_inputs cannot see this; here the seed breaks as predicted."};
    return {};
  };
  return c;
}

Case toon_continuity() {
  Case c;
  c.id = "toon_continuity";
  c.title = "toon: the ramp and the rim are continuous in NoL when smoothing > 0";
  c.section = "5.12";
  c.forms = {kSeed, kGuardedOnly};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    constexpr int kSteps = 256;
    const double step = 2.0 / kSteps;
    std::vector<Measurement> measurements;
    for (float smooth : {0.1f, 0.02f}) {
      std::vector<ToonInput> inputs;
      for (int k = 0; k <= kSteps; ++k) {
        const float NoL = float(-1.0 + step * k);
        inputs.push_back(
            {fmt::format("NoL = {}, smooth = {}", number(NoL), number(smooth)), NoL, 0.3f, 0.5f, smooth, 0.2f, 1.0f});
      }
      auto outputs = run_toon(context, inputs);
      if (!outputs) return fail(outputs.error());
      // smoothstep's steepest slope is 1.5 / width. The ramp reads NoL * 0.5 + 0.5, the rim
      // (1 - NoV) NoL = 0.7 NoL here, so one step of NoL moves them at most by slope x step.
      // In fp16 each neighbour's argument may also be off by half an ulp below 1 (2.4e-4), which
      // the slope magnifies, and each result by half an ulp: that is the allowance on top.
      const double input_rounding = context.precision == Precision::Half ? 2 * 2.4e-4 : 0.0;
      const double output_rounding = context.precision == Precision::Half ? 2 * 2.4e-4 : 1e-6;
      const double ramp_bound = 1.5 / smooth * (0.5 * step + input_rounding) + output_rounding;
      const double rim_bound = 1.5 / smooth * (0.7 * step + input_rounding) + output_rounding;
      double ramp_jump = 0.0, rim_jump = 0.0;
      size_t ramp_at = 0, rim_at = 0;
      for (int k = 0; k < kSteps; ++k) {
        const double dr = std::abs((*outputs)[k + 1].ramp - (*outputs)[k].ramp);
        const double di = std::abs((*outputs)[k + 1].rim - (*outputs)[k].rim);
        if (!(dr <= ramp_jump)) ramp_jump = dr, ramp_at = k + 1;
        if (!(di <= rim_jump)) rim_jump = di, rim_at = k + 1;
      }
      const std::string sweep =
          fmt::format("NoL from -1 to 1 in {} steps, NoV = 0.3, smooth = {}", kSteps, number(smooth));
      measurements.push_back({sweep + " (worst at " + inputs[ramp_at].label + ")", "largest step of the ramp",
                              ramp_jump, fmt::format("<= {} (steepest smoothstep slope x step)", number(ramp_bound)),
                              std::isfinite(ramp_jump) && ramp_jump <= ramp_bound});
      measurements.push_back({sweep + " (worst at " + inputs[rim_at].label + ")", "largest step of the rim", rim_jump,
                              fmt::format("<= {} (steepest smoothstep slope x step)", number(rim_bound)),
                              std::isfinite(rim_jump) && rim_jump <= rim_bound});
    }
    return measurements;
  };
  return c;
}

}  // namespace

std::vector<Case> toon_cases() { return {toon_hard_inputs(), toon_hard_edge(), toon_continuity()}; }

}  // namespace xshade::stability
