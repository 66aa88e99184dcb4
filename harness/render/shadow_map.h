// The main light's shadow map as Unity's built-in renderer makes a directional light's, without
// cascades: an orthographic view along the light fitted to everything the scene draws, the
// ShadowCaster passes drawn into its depth with Unity's biases, and what the receiving passes read
// of it (unity_WorldToShadow[0], _LightShadowData; docs/unity.md, "Shadows").
#pragma once

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "harness/render/renderer_inputs.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

struct ShadowView {
  glm::mat4 view{1.0f};        // world to the light's view space (looking down -z along the light)
  glm::mat4 projection{1.0f};  // orthographic, depth 0 to 1 over the fitted boxes
  float texel = 0.0f;          // the world size of one shadow-map texel (a spot's: half way along its range)
  float depth_range = 0.0f;    // the world distance depth 0 to 1 spans
  bool perspective = false;    // a spot light's
};

// An object-space box (low, high corners) under `model`, as a world-space box around its corners.
std::pair<glm::vec3, glm::vec3> world_box(const std::pair<glm::vec3, glm::vec3>& box, const glm::mat4& model);

// The view of a directional `light` that holds every box, its resolution the light's.
ShadowView directional_shadow_view(const Light& light, const std::vector<std::pair<glm::vec3, glm::vec3>>& boxes);

// The view of a spot `light`: a perspective from its position along its beam, the cone's angle
// square, from a near plane of 0.2 (Unity's default Shadow Near Plane, at most a tenth of the
// range) to the range.
ShadowView spot_shadow_view(const Light& light);

// What a ShadowCaster pass reads when drawn into the map: the light's view as the camera
// (unity_MatrixV, glstate_matrix_projection, unity_MatrixVP) and unity_LightShadowBias, Unity's
// depth bias (x, added to clip z over w), pancaking (y = 1 for a directional light, 0 for a spot)
// and normal offset (z, in world units), from the light's biases in texels.
void add_shadow_caster_inputs(const Light& light, const ShadowView& view, UniformValueMap& values);

// What a receiving pass reads: unity_WorldToShadow[0], world to the map's (u, v, depth);
// _LightShadowData.x = 1 - strength; _ShadowMapTexture_TexelSize.
void add_shadow_receiver_inputs(const Light& light, const ShadowView& view, UniformValueMap& values);

}  // namespace xshade::harness
