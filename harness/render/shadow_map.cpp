#include "harness/render/shadow_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace xshade::harness {

std::pair<glm::vec3, glm::vec3> world_box(const std::pair<glm::vec3, glm::vec3>& box, const glm::mat4& model) {
  glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 local((corner & 1) ? box.second.x : box.first.x, (corner & 2) ? box.second.y : box.first.y,
                          (corner & 4) ? box.second.z : box.first.z);
    const glm::vec3 world = glm::vec3(model * glm::vec4(local, 1.0f));
    low = glm::min(low, world);
    high = glm::max(high, world);
  }
  return {low, high};
}

ShadowView directional_shadow_view(const Light& light, const std::vector<std::pair<glm::vec3, glm::vec3>>& boxes) {
  ShadowView out;
  // Looking along the light's travel (-direction), from the origin: only the orientation matters
  // to an orthographic view, whose box is fitted below.
  const glm::vec3 forward = -light.direction;
  const glm::vec3 up = std::abs(forward.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  out.view = glm::lookAtRH(glm::vec3(0.0f), forward, up);
  glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
  for (const auto& box : boxes) {
    const auto [view_low, view_high] = world_box(box, out.view);
    low = glm::min(low, view_low);
    high = glm::max(high, view_high);
  }
  if (boxes.empty()) low = high = glm::vec3(0.0f);
  // Square texels: the larger side on both axes, and a margin of a texel's fraction so that the
  // outermost caster's edge is inside.
  const glm::vec2 centre = (glm::vec2(low) + glm::vec2(high)) * 0.5f;
  const float half = std::max(std::max(high.x - low.x, high.y - low.y) * 0.5f * 1.02f, 1e-3f);
  // View space looks down -z: the nearest point has the largest z.
  const float near_plane = -high.z - 0.01f * (high.z - low.z + 1.0f),
              far_plane = -low.z + 0.01f * (high.z - low.z + 1.0f);
  out.projection =
      glm::orthoRH_ZO(centre.x - half, centre.x + half, centre.y - half, centre.y + half, near_plane, far_plane);
  out.texel = 2.0f * half / float(light.shadow_resolution);
  out.depth_range = far_plane - near_plane;
  return out;
}

ShadowView spot_shadow_view(const Light& light) {
  ShadowView out;
  const glm::vec3 beam = -light.direction;
  const glm::vec3 up = std::abs(beam.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  out.view = glm::lookAtRH(light.position, light.position + beam, up);
  const float near_plane = std::min(0.2f, 0.1f * light.range);
  out.projection = glm::perspectiveRH_ZO(glm::radians(light.spot_angle), 1.0f, near_plane, light.range);
  out.texel =
      2.0f * 0.5f * light.range * std::tan(glm::radians(light.spot_angle) * 0.5f) / float(light.shadow_resolution);
  out.depth_range = light.range - near_plane;
  out.perspective = true;
  return out;
}

void add_shadow_caster_inputs(const Light& light, const ShadowView& view, UniformValueMap& values) {
  values["unity_MatrixV"] = hlsl_components(view.view);
  values["unity_MatrixInvV"] = hlsl_components(glm::inverse(view.view));
  values["glstate_matrix_projection"] = hlsl_components(view.projection);
  values["unity_MatrixVP"] = hlsl_components(view.projection * view.view);
  // UnityApplyLinearShadowBias adds x / w to the clip depth (pushing casters away from the light);
  // UnityClipSpaceShadowCasterPos moves each vertex z world units against its normal, scaled by
  // the sine of the light's angle to it. Both from the light's biases in texels, as Unity scales
  // its Bias and Normal Bias by the texel's world size.
  // A perspective's depth d = f (z - n) / ((f - n) z) moves by f n dz / ((f - n) z^2) for dz world
  // units at distance z, and adding x / w (w = z) to clip z moves it by x / z^2: x = f n dz / (f - n)
  // is the same world offset at every distance.
  float depth_bias = light.shadow_bias * view.texel / view.depth_range;
  if (view.perspective) {
    const float far_plane = light.range, near_plane = light.range - view.depth_range;
    depth_bias = far_plane * near_plane / (far_plane - near_plane) * light.shadow_bias * view.texel;
  }
  values["unity_LightShadowBias"] = {depth_bias, view.perspective ? 0.0f : 1.0f, light.shadow_normal_bias * view.texel,
                                     0.0f};
}

void add_shadow_receiver_inputs(const Light& light, const ShadowView& view, UniformValueMap& values) {
  // Clip x, y in [-1, 1] to the map's u, v in [0, 1] (its row 0 the bottom, as every target of a
  // Unity scene keeps it), depth as it is (0 to 1).
  glm::mat4 to_texture = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, 0.0f)) *
                         glm::scale(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, 1.0f));
  std::vector<float> world_to_shadow = hlsl_components(to_texture * view.projection * view.view);
  // Cascades 1 to 3 are unused (no cascades): the same matrix, as Unity fills unused ones.
  std::vector<float>& all = values["unity_WorldToShadow"];
  all.clear();
  for (int cascade = 0; cascade < 4; ++cascade) all.insert(all.end(), world_to_shadow.begin(), world_to_shadow.end());
  values["_LightShadowData"] = {1.0f - light.shadow_strength, 0.0f, 0.0f, 0.0f};
  values["_ShadowMapTexture_TexelSize"] = texel_size({light.shadow_resolution, light.shadow_resolution});
}

}  // namespace xshade::harness
