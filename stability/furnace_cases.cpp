// SHADERS.md section 5, cases 8 and 9: integrals of the library's BRDF terms over the
// hemisphere (stability/probes/furnace.hlsl), against the reference values of section 4, and the
// white-furnace scene.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "stability/cases.h"
#include "stability/forms.h"
#include "stability/probe.h"

namespace xshade::stability {
namespace {

struct Integral {
  float NoV = 1.0f;
  float a = 0.5f;
  int points = 64;  // per dimension: 64 x 64 for E(v), 64 steps for the normalisation
  bool normalisation = false;
};

Result<std::vector<double>> integrate(const CaseContext& context, const std::vector<Integral>& integrals) {
  std::vector<glm::vec4> packed;
  for (const Integral& i : integrals) packed.push_back({i.NoV, i.a, float(i.points), i.normalisation ? 1.0f : 0.0f});
  auto image = run_probe(context, "furnace.hlsl", 1, packed, 1);
  if (!image) return fail(image.error());
  std::vector<double> values;
  for (uint32_t x = 0; x < image->width; ++x) values.push_back(image->at(x, 0).x);
  return values;
}

Case ggx_normalisation() {
  Case c;
  c.id = "ggx_normalisation";
  c.title = "GGX normalisation: integral of D (n.m) over the hemisphere = 1 within 1e-3, a in [0.05, 1]";
  c.section = "5.8";
  c.forms = {kSeed, kGuarded};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    const std::vector<float> alphas = {0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
    std::vector<Integral> integrals;
    for (float a : alphas) integrals.push_back({1.0f, a, 2048, true});
    auto values = integrate(context, integrals);
    if (!values) return fail(values.error());
    std::vector<Measurement> measurements;
    for (size_t i = 0; i < alphas.size(); ++i)
      // SHADERS.md's bound. The 2048-point rule itself is exact to ~1e-6 here (the substitution
      // makes the integrand smooth), so the bound judges D, not the quadrature.
      measurements.push_back({"a = " + number(alphas[i]) + " (2048-point rule)", "integral of D (n.m)", (*values)[i],
                              "= 1 +- 1e-3", std::isfinite((*values)[i]) && std::abs((*values)[i] - 1.0) <= 1e-3});
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (form.name == kSeed.name && precision == Precision::Half)
      return {{"a = 0.05 (2048-point rule)", "a = 0.1 (2048-point rule)"},
              "hazard 8: in fp16 the seed's D is 5% high around its peak at a = 0.05 and 0.1 (a^2 - 1 rounded "
              "to 11 bits), and its integral follows: 1.046 and 1.019."};
    return {};
  };
  return c;
}

// SHADERS.md section 4: E(v) at NoV = 1 with F = 1, for a = 0.05, 0.25, 0.5, 0.75, 1.
const std::vector<float> kReferenceAlphas = {0.05f, 0.25f, 0.5f, 0.75f, 1.0f};
const std::map<std::string, std::vector<double>> kReferenceAlbedo = {
    {kSeed.name, {0.996, 0.901, 0.699, 0.513, 0.375}},  // Cook-Torrance G (3/8 exactly at a = 1)
    {kGuarded.name, {0.996, 0.901, 0.699, 0.513, 0.375}},
    {kGuardedSmith.name, {0.997, 0.916, 0.688, 0.464, 0.307}},  // height-correlated Smith (1 - ln 2 at a = 1)
};

Case directional_albedo() {
  Case c;
  c.id = "directional_albedo";
  c.title = "white furnace: E(v) <= 1, the reference values at NoV = 1, and E(1) falling as a rises";
  c.section = "5.9";
  c.forms = {kSeed, kGuarded, kGuardedSmith, kGuardedSmithFast};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    const std::vector<float> cosines = {1.0f, 0.5f, 0.1f};
    std::vector<Integral> integrals;
    for (float NoV : cosines)
      for (float a : kReferenceAlphas) integrals.push_back({NoV, a, 64});
    // The rule's own error: the NoV = 1 row again with twice the points per dimension.
    for (float a : kReferenceAlphas) integrals.push_back({1.0f, a, 128});
    auto values = integrate(context, integrals);
    if (!values) return fail(values.error());
    const size_t n = kReferenceAlphas.size();
    auto reference = kReferenceAlbedo.find(context.form.name);

    std::vector<Measurement> measurements;
    for (size_t i = 0; i < cosines.size() * n; ++i) {
      const Integral& in = integrals[i];
      const double E = (*values)[i];
      const std::string label = fmt::format("NoV = {}, a = {} (64 x 64 points)", number(in.NoV), number(in.a));
      if (in.NoV == 1.0f && reference != kReferenceAlbedo.end()) {
        const double expected = reference->second[i];
        // The references have three decimals (+-5e-4); the 64 x 64 rule moves E by less than
        // 5e-4 when the points are doubled (the rows below): 2e-3 holds both with room.
        measurements.push_back({label, "E(v)", E, fmt::format("= {} +- 2e-3 (SHADERS.md section 4)", number(expected)),
                                std::isfinite(E) && std::abs(E - expected) <= 2e-3});
      } else {
        // <= 1, plus the rule's error (see the doubled rows).
        measurements.push_back({label, "E(v)", E, "<= 1 + 1e-3", std::isfinite(E) && E <= 1.0 + 1e-3});
      }
    }
    // The rule is judged in fp32; in fp16 the terms' own rounding is noise the rule cannot remove.
    for (size_t k = 0; k < n && context.precision == Precision::Float; ++k) {
      const double coarse = (*values)[k], fine = (*values)[cosines.size() * n + k];
      measurements.push_back(
          {fmt::format("NoV = 1, a = {}: 128 x 128 points against 64 x 64", number(kReferenceAlphas[k])),
           "change of E(v)", fine - coarse, "within +-5e-4 (the rule has converged)",
           std::isfinite(fine) && std::abs(fine - coarse) <= 5e-4});
    }
    const double rise = largest_rise({values->begin(), values->begin() + long(n)}).value;
    measurements.push_back({"NoV = 1, a = 0.05 .. 1", "largest rise of E(v) from one a to the next", rise,
                            "< 0 (E falls as a rises)", std::isfinite(rise) && rise < 0.0});
    return measurements;
  };
  c.predict = [](const Form& form, Precision precision) -> Prediction {
    if (form.name == kSeed.name && precision == Precision::Half)
      return {{"NoV = 1, a = 0.05 (64 x 64 points)", "NoV = 0.5, a = 0.05 (64 x 64 points)"},
              "hazard 8: the seed's D, 5% high near its peak in fp16 at a = 0.05, makes energy: E = 1.026."};
    return {};
  };
  return c;
}

Case white_furnace_scene() {
  Case c;
  c.id = "white_furnace_scene";
  c.title = "white furnace scene: no pixel brighter than the white environment";
  c.section = "5.9";
  c.forms = {kSeed, kGuardsSeedD, kGuarded};
  c.run = [](const CaseContext& context) -> Result<std::vector<Measurement>> {
    auto image = render_scene_with_form(context, "white_furnace");
    if (!image) return fail(image.error());
    double brightest = -INFINITY;
    uint32_t at_x = 0, at_y = 0;
    for (uint32_t y = 0; y < image->height; ++y)
      for (uint32_t x = 0; x < image->width; ++x) {
        const glm::vec4 p = image->at(x, y);
        const double value = std::max({double(p.r), double(p.g), double(p.b)});
        if (!(value <= brightest)) brightest = value, at_x = x, at_y = y;
      }
    // The constant environment's prefiltered mips are 1 up to the rounding of their weighted
    // sums (a few fp32 ulps); 1e-4 is far above that and far below one 8-bit step.
    return std::vector<Measurement>{{fmt::format("scene white_furnace (brightest at ({}, {}))", at_x, at_y),
                                     "largest channel", brightest, "<= 1 + 1e-4 (the environment's radiance)",
                                     std::isfinite(brightest) && brightest <= 1.0 + 1e-4}};
  };
  return c;
}

}  // namespace

std::vector<Case> furnace_cases() { return {ggx_normalisation(), directional_albedo(), white_furnace_scene()}; }

}  // namespace xshade::stability
