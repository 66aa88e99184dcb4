// What `xshade accuracy` measures: for each knob of SHADERS.md section 6, a scene rendered in
// several configurations and in a reference configuration, each configuration's error against
// the reference and its time.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace xshade::accuracy {

// One way of rendering a study's scene.
struct Configuration {
  std::string label = {};  // "16 samples", "fp16 emulation", "seed D, G, F"
  // Replace the keywords of every object's material, or of every post effect, when set.
  std::optional<std::vector<std::string>> material_keywords = std::nullopt;
  std::optional<std::vector<std::string>> post_keywords = std::nullopt;
  std::map<std::string, float> post_parameters = {};    // set on every post effect
  std::map<std::string, float> object_parameters = {};  // set on every object
  bool half_emulation = false;                          // gl and vk only
  uint32_t supersample = 1;                             // rendered at k times the size, then averaged over k x k pixels
  std::optional<uint32_t> shadow_resolution = std::nullopt;  // every shadow map's size
  // Every shadow-casting light's filter when set: soft (the 2x2 comparisons filtered) or hard
  // (one comparison). Soft is not run on vk-hlsl (harness::Light::Shadows).
  std::optional<bool> soft_shadows = std::nullopt;
};

struct Study {
  std::string id;             // "dof_kernel": names files and table rows
  std::string knob;           // "depth-of-field kernel"
  std::string scene;          // a scene of scenes
  std::string why_reference;  // what makes the reference the most accurate configuration
  Configuration reference;
  // The reference with its own accuracy doubled (twice the samples): it must differ from the
  // reference by less than the smallest error the reference judges.
  std::optional<Configuration> reference_check;
  std::vector<Configuration> configurations;
  // The passes whose time is the configuration's cost: those whose name starts with this
  // ("scene", or "depth_of_field." for the effect's passes).
  std::string timed_passes;
  bool quick = true;  // part of `xshade accuracy --quick`
  // Its scene draws Unity .shader files: run only when named, with the folders that hold them and
  // Unity's include files (xshade ships none).
  bool unity = false;
  // What the measurements showed when this study was written, and why: shown under its table.
  std::string findings = {};
};

std::vector<Study> all_studies();

}  // namespace xshade::accuracy
