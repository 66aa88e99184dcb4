// The knobs of SHADERS.md section 6 as studies: which scene each renders, in which
// configurations, against which reference.
#include "accuracy/study.h"

namespace xshade::accuracy {
namespace {

Study dof_kernel() {
  Study s;
  s.id = "dof_kernel";
  s.knob = "depth-of-field kernel";
  s.scene = "dof_on_16";
  s.why_reference =
      "_KERNEL_DENSE gathers every half-resolution texel within the bokeh radius: the exact disk the ring "
      "kernels sample. Its check gathers at half-texel spacing (_DenseStep = 0.5: four times the samples, "
      "between the texels).";
  s.reference = {.label = "dense gather", .post_keywords = std::vector<std::string>{"_KERNEL_DENSE"}};
  s.reference_check = Configuration{.label = "dense gather, half-texel spacing",
                                    .post_keywords = std::vector<std::string>{"_KERNEL_DENSE"},
                                    .post_parameters = {{"_DenseStep", 0.5f}}};
  for (auto [label, keyword] : {std::pair{"16 samples", "_KERNEL_SMALL"},
                                {"22 samples", "_KERNEL_MEDIUM"},
                                {"43 samples", "_KERNEL_LARGE"},
                                {"71 samples", "_KERNEL_VERY_LARGE"}})
    s.configurations.push_back({.label = label, .post_keywords = std::vector<std::string>{keyword}});
  s.timed_passes = "depth_of_field.";
  return s;
}

// The most accurate forms of the lobe: the cancellation-free D, the masking-shadowing that GGX
// actually implies (height-correlated Smith) and Fresnel's own equations, with the guards.
const std::vector<std::string> kExactForms = {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED", "_F_EXACT"};

Study brdf_forms() {
  Study s;
  s.id = "brdf_forms";
  s.knob = "D, G and F forms";
  s.scene = "material_grid";
  s.why_reference = "Lagrange D, height-correlated Smith G and exact Fresnel, guarded, in fp32.";
  s.reference = {.label = "exact forms", .material_keywords = kExactForms};
  using Keywords = std::vector<std::string>;
  for (auto& [label, keywords] : std::vector<std::pair<std::string, Keywords>>{
           {"seed D, G, F", {}},
           {"seed, guarded", {"_GUARDED"}},
           {"Lagrange D", {"_GUARDED", "_D_GGX_LAGRANGE"}},
           {"Smith G", {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED"}},
           {"fast Smith G", {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_FAST"}},
           {"Smith G, SG Fresnel", {"_GUARDED", "_D_GGX_LAGRANGE", "_G_SMITH_CORRELATED", "_F_SPHERICAL_GAUSSIAN"}},
           {"exact forms", kExactForms}})
    s.configurations.push_back({.label = label, .material_keywords = keywords});
  s.timed_passes = "scene";
  return s;
}

Study precision() {
  Study s;
  s.id = "precision";
  s.knob = "precision";
  s.scene = "material_grid";
  s.why_reference = "The same exact forms in fp32.";
  s.reference = {.label = "fp32", .material_keywords = kExactForms};
  s.configurations = {{.label = "fp32", .material_keywords = kExactForms},
                      {.label = "fp16 emulation", .material_keywords = kExactForms, .half_emulation = true}};
  s.timed_passes = "scene";
  return s;
}

Study supersampling() {
  Study s;
  s.id = "supersampling";
  s.knob = "resolution and supersampling";
  s.scene = "material_grid";
  s.why_reference = "4 x 4 samples per pixel (box filter); its check, 8 x 8 (a 2560 x 2560 render).";
  s.reference = {.label = "4x4 supersampled", .supersample = 4};
  s.reference_check = Configuration{.label = "8x8 supersampled", .supersample = 8};
  for (uint32_t k : {1u, 2u, 3u})
    s.configurations.push_back(
        {.label = k == 1 ? std::string("1 sample") : std::to_string(k) + "x" + std::to_string(k) + " supersampled",
         .supersample = k});
  s.timed_passes = "scene";
  s.quick = false;
  return s;
}

}  // namespace

std::vector<Study> all_studies() { return {dof_kernel(), brdf_forms(), precision(), supersampling()}; }

}  // namespace xshade::accuracy
