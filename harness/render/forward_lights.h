// The lights of a scene as Unity's built-in forward renderer divides them: the main light (the
// brightest directional one) lights every object's ForwardBase pass; each further light, up to the
// scene's pixel light count and brightest first, draws the objects again in their ForwardAdd pass;
// point lights beyond that light ForwardBase per vertex (unity_4Light*, four at most). What each
// light gives the passes it lights, and the textures Unity's attenuation reads, are written here
// with where each formula comes from (docs/unity.md, "Lights").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/render/renderer_inputs.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

struct ForwardLights {
  std::optional<size_t> main;         // index into Scene::lights
  std::vector<size_t> pixel;          // ForwardAdd's, in the order they are drawn
  std::vector<size_t> vertex;         // ForwardBase's per-vertex point lights
  std::vector<std::string> left_out;  // lights that light nothing, and why
};

ForwardLights forward_lights(const Scene& scene);

// The texture a pass that receives the main light's shadow samples, with a comparison sampler.
inline constexpr const char* kShadowMapTexture = "_ShadowMapTexture";

// The main light; where the scene has no directional light, one of no colour pointing up, which
// lights nothing.
Light main_light(const Scene& scene);

// The keyword of Unity's multi_compile_fwdadd that a pass lit by `light` is compiled with.
const char* additive_keyword(LightType type);

// What an additive pass lit by `light` reads of it, added to (or replaced in) `values`:
// _WorldSpaceLightPos0 (a direction with w = 0, or a position with w = 1), _LightColor0 and
// unity_WorldToLight, the light's space in which Unity's attenuation and cookie are looked up.
void add_light_inputs(const Light& light, UniformValueMap& values);

// ForwardBase's per-vertex lights (unity_4LightPos*, unity_4LightAtten0, unity_LightColor[0..3]).
void add_vertex_light_inputs(const Scene& scene, const std::vector<size_t>& vertex, UniformValueMap& values);

// Unity's attenuation of a point or spot light over (distance / range)^2, as the texture
// _LightTexture0 (a point light's) or _LightTextureB0 (a spot's) holds it.
float light_falloff(float distance_squared_over_range_squared);
// The textures a light's additive pass reads: the falloff (256 texels along u, sampled at
// (t, t)) and the spot's default cookie (its alpha a soft disc filling the cone).
TextureData light_falloff_texture();
TextureData spot_cookie_texture();

}  // namespace xshade::harness
