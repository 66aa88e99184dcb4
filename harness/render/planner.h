// The planner: from a scene, exactly the shader variants and passes it needs, and what it leaves
// out and why. Nothing is compiled or run that the plan does not list.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/render/shader_search_path.h"
#include "harness/scene/scene.h"
#include "hlsl_like/pass_declarations.h"

namespace xshade::harness {

// One compile of one source: a keyword set, and for a post pass the fragment entry it runs.
struct VariantRequest {
  std::filesystem::path source;                      // absolute
  std::string library_path;                          // as the scene names it, e.g. "materials/toon.hlsl"
  std::vector<std::string> keywords;                 // sorted, no repeats
  std::string fragment_entry;                        // a post pass's entry; empty for a material
  std::optional<size_t> shader_pass = std::nullopt;  // a .shader's pass, by its index in the drawn SubShader
  // The Unity platform a .shader compiles for (the scene's); GLCore for an .hlsl file.
  shaderlab::UnityPlatform unity_platform = shaderlab::UnityPlatform::GLCore;
  bool half_emulation = false;  // every half result rounded to fp16 (GLSL lanes only)
  // Drawn where its comparison samplers filter linearly (a soft shadow's map):
  // ProgramOptions::filter_comparisons.
  bool filtered_comparison = false;
  // The tracing variant (gl and vk lanes), numbered trace_program (render/shader_program.h).
  bool trace_nonfinite = false;
  uint32_t trace_program = 0;
  // The values the object gives the shader's specialization constants, by constant_id
  // (ProgramOptions::specialization).
  std::map<uint32_t, double> specialization = {};

  // "materials/toon.hlsl [_GUARDED]", "post/depth_of_field.hlsl:frag_coc [_KERNEL_SMALL]",
  // "Unlit/Outline.shader pass 1 []", "Unlit/Outline.shader pass 1 for d3d11 []" or
  // "Standard.shader pass 1 [SHADOWS_SCREEN] filtered comparison", "vk.hlsl [] specialized {0=2}".
  std::string label() const;
  friend bool operator==(const VariantRequest&, const VariantRequest&) = default;
};

struct PlannedPass {
  enum class Kind { Scene, Post };
  Kind kind = Kind::Scene;
  std::string name;                   // "scene", or "depth_of_field.coc"
  size_t effect = 0;                  // Post: index into Scene::post
  hlsl::PassDeclaration declaration;  // Post
  size_t variant = 0;                 // Post: index into Plan::variants
  // Post: textures the pass samples that nothing gives, from the shader's declared defaults.
  std::map<std::string, TextureRef> default_textures;
  // Post: a .shader's pass, drawn as Unity's Graphics.Blit draws it (identity view and projection,
  // so that UnityObjectToClipPos puts the full-screen triangle where it is).
  bool blit = false;
};

struct Plan {
  std::vector<VariantRequest> variants;
  // What the front end warned of in the scene's sources ("file:line:col: warning: ...", an
  // unknown pragma, ...), each once: run prints them and the report shows them.
  std::vector<std::string> warnings;
  std::vector<ObjectInstance> instances;
  // Per instance, its draws in order: a variant (index into variants) and how it is drawn (a
  // .shader's pass's render state; an .hlsl material's is DrawState's default). An .hlsl material
  // draws once, a .shader once for each pass the forward renderer draws and each ForwardAdd pass
  // once more for each pixel light besides the main one.
  struct InstanceDraw {
    size_t variant = 0;
    DrawState state;
    // A ForwardAdd pass's light (index into Scene::lights), whose values replace the main
    // light's for this draw (forward_lights.h); a caster's, the light whose map it is drawn into.
    std::optional<size_t> light;
    // A ShadowCaster pass, drawn into the shadow map of `light` (one of Plan::shadow_lights), not
    // the scene.
    bool caster = false;
  };
  std::vector<std::vector<InstanceDraw>> instance_draws;
  // The lights whose shadow maps the scene pass draws first: the main light and each spot pixel
  // light that casts shadows where something casts and a pass drawn for it receives them.
  std::vector<size_t> shadow_lights;
  // Per instance: its render queue (a .shader's SubShader Queue; Geometry otherwise).
  std::vector<int> instance_queue;
  // The instances in the order the scene pass draws them, as Unity's forward renderer orders
  // them: by queue; within an opaque queue in the scene's order, within a transparent one (above
  // AlphaTest) from the farthest to the nearest, by the distance from the camera to the object's
  // origin.
  std::vector<size_t> draw_order;
  std::vector<PlannedPass> passes;    // in the order they run: the scene, then each effect's
  std::vector<std::string> left_out;  // what the shader folders have that this scene does not run, and why
  // Per variant, what it should know before it runs: each vertex input its shader reads that the
  // meshes do not supply (anything but POSITION, NORMAL, TANGENT, TEXCOORD0), which reads zeros.
  std::vector<std::vector<std::string>> variant_notes;
};

// Plans `scene` against the shader folders. Reads each source the scene names (the front end
// only: keyword sets, pass declarations and the names each variant has); fails with the front
// end's diagnostics when one does not compile, or when a source is in none of the folders, and
// with every breach of the scene-shader contract (scene_contract.h) at its scene line. An
// instance's textures include those its material samples from their declared defaults.
// `files_read`, when given, gets every source and include read, whether it compiled or not, and
// where each source was looked for before the folder that has it (or in every folder, when none
// has it).
Result<Plan> plan_scene(const Scene& scene, const ShaderSearchPath& shaders,
                        std::set<std::filesystem::path>* files_read = nullptr);

// The plan as `xshade run --plan` prints it; `cached` says per variant whether its compiled form
// is already in the cache (empty: unknown).
std::string describe_plan(const Scene& scene, const Plan& plan, const std::vector<bool>& cached = {});

}  // namespace xshade::harness
