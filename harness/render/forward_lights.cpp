#include "harness/render/forward_lights.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

namespace xshade::harness {
namespace {

// The per-vertex lights Shade4PointLights adds (UnityCG.cginc): four.
constexpr size_t kVertexLights = 4;

std::vector<float> vec4_components(const glm::vec4& v) { return {v.x, v.y, v.z, v.w}; }

// A texture of `width` x `height` float texels from `texel(u, v)` (each in [0, 1] at texel
// centres), RGBA all equal.
template <class Texel>
TextureData float_texture(uint32_t width, uint32_t height, const Texel& texel) {
  TextureData data;
  data.format = TextureFormat::Rgba32Float;
  data.width = width;
  data.height = height;
  std::vector<float> texels;
  texels.reserve(size_t(width) * height * 4);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const float value = texel((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
      texels.insert(texels.end(), {value, value, value, value});
    }
  std::vector<std::byte> bytes(texels.size() * sizeof(float));
  std::memcpy(bytes.data(), texels.data(), bytes.size());
  data.levels.push_back(std::move(bytes));
  return data;
}

}  // namespace

Light main_light(const Scene& scene) {
  const ForwardLights lights = forward_lights(scene);
  if (lights.main) return scene.lights[*lights.main];
  Light none;
  none.color = glm::vec3(0.0f);
  none.intensity = 0.0f;
  return none;
}

ForwardLights forward_lights(const Scene& scene) {
  ForwardLights out;
  // Unity's main light is the brightest directional light; ties go to the one written first.
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].type == LightType::Directional &&
        (!out.main || scene.lights[i].brightness() > scene.lights[*out.main].brightness()))
      out.main = i;
  std::vector<size_t> rest;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (i != out.main) rest.push_back(i);
  // Unity ranks the others by how much they light (an object's nearest first among equals);
  // brightness, then the order written, ranks them here for the whole scene.
  std::stable_sort(rest.begin(), rest.end(),
                   [&](size_t a, size_t b) { return scene.lights[a].brightness() > scene.lights[b].brightness(); });
  for (size_t i : rest) {
    const Light& light = scene.lights[i];
    if (out.pixel.size() < size_t(scene.pixel_lights)) {
      out.pixel.push_back(i);
    } else if (light.type == LightType::Point && out.vertex.size() < kVertexLights) {
      out.vertex.push_back(i);
    } else {
      out.left_out.push_back(
          "light " + std::to_string(i + 1) + ": beyond the " + std::to_string(scene.pixel_lights) +
          " pixel lights of [unity] pixel_lights" +
          (light.type == LightType::Point ? " and the 4 vertex lights" : " (only point lights light per vertex)") +
          ": it lights nothing (Unity folds such lights into the SH ambient; xshade does not)");
    }
  }
  return out;
}

const char* additive_keyword(LightType type) {
  switch (type) {
    case LightType::Directional: return "DIRECTIONAL";
    case LightType::Point: return "POINT";
    case LightType::Spot: return "SPOT";
  }
  return "DIRECTIONAL";
}

void add_light_inputs(const Light& light, UniformValueMap& values) {
  values["_LightColor0"] = vec4_components(glm::vec4(light.color, 1.0f) * light.intensity);
  if (light.type == LightType::Directional) {
    values["_WorldSpaceLightPos0"] = vec4_components(glm::vec4(light.direction, 0.0f));
    values["unity_WorldToLight"] = hlsl_components(glm::mat4(1.0f));
    return;
  }
  values["_WorldSpaceLightPos0"] = vec4_components(glm::vec4(light.position, 1.0f));
  const glm::mat4 to_origin = glm::translate(glm::mat4(1.0f), -light.position);
  if (light.type == LightType::Point) {
    // A point light's space: the light at the origin, its range 1 (AutoLight.cginc reads the
    // falloff at dot(lightCoord, lightCoord) = (distance / range)^2).
    values["unity_WorldToLight"] =
        hlsl_components(glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / light.range)) * to_origin);
    return;
  }
  // A spot light's space: x right, y up, z along the beam (Unity's light transform), the range 1,
  // and w = 2 tan(angle / 2) z, so that AutoLight's cookie lookup at xy / w + 0.5 spans the cone
  // (xy / w = +-0.5 on its edge) and the falloff at dot(xyz, xyz) is (distance / range)^2, as for
  // a point light.
  const glm::vec3 beam = -light.direction;
  const glm::vec3 helper = std::abs(beam.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 right = glm::normalize(glm::cross(helper, beam));
  const glm::vec3 up = glm::cross(beam, right);
  glm::mat4 rotation(1.0f);  // rows: right, up, beam (glm is column-major: [column][row])
  for (int c = 0; c < 3; ++c) {
    rotation[c][0] = right[c];
    rotation[c][1] = up[c];
    rotation[c][2] = beam[c];
  }
  glm::mat4 cone(1.0f);
  cone[2][3] = 2.0f * std::tan(glm::radians(light.spot_angle) * 0.5f);  // w = 2 tan(angle / 2) z
  cone[3][3] = 0.0f;
  values["unity_WorldToLight"] =
      hlsl_components(cone * glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / light.range)) * rotation * to_origin);
}

void add_vertex_light_inputs(const Scene& scene, const std::vector<size_t>& vertex, UniformValueMap& values) {
  glm::vec4 x(0.0f), y(0.0f), z(0.0f), atten(0.0f);
  std::vector<float>& colors = values["unity_LightColor"];
  colors.assign(8 * 4, 0.0f);
  for (size_t slot = 0; slot < vertex.size() && slot < kVertexLights; ++slot) {
    const Light& light = scene.lights[vertex[slot]];
    x[int(slot)] = light.position.x;
    y[int(slot)] = light.position.y;
    z[int(slot)] = light.position.z;
    // Shade4PointLights attenuates by 1 / (1 + d^2 atten): 25 / range^2 makes it the falloff's
    // 1 / (1 + 25 (d / range)^2).
    atten[int(slot)] = 25.0f / (light.range * light.range);
    const glm::vec3 color = light.color * light.intensity;
    std::copy_n(&color.x, 3, colors.begin() + long(slot) * 4);
  }
  values["unity_4LightPosX0"] = vec4_components(x);
  values["unity_4LightPosY0"] = vec4_components(y);
  values["unity_4LightPosZ0"] = vec4_components(z);
  values["unity_4LightAtten0"] = vec4_components(atten);
}

float light_falloff(float t) {
  // Unity's built-in falloff, 1 / (1 + 25 t) over t = (distance / range)^2 (the same constant as
  // unity_4LightAtten0's 25 / range^2 for vertex lights), which would leave 1/26 at the range; the
  // texture Unity bakes ends at 0, fading linearly over the last part of t (from 0.8^2 on) so that
  // a light ends where its range does.
  t = std::clamp(t, 0.0f, 1.0f);
  constexpr float kFadeStart = 0.64f;
  const float fade = t <= kFadeStart ? 1.0f : (1.0f - t) / (1.0f - kFadeStart);
  return fade / (1.0f + 25.0f * t);
}

TextureData light_falloff_texture() {
  return float_texture(256, 1, [](float u, float) { return light_falloff(u); });
}

TextureData spot_cookie_texture() {
  // A soft disc: 1 in the cone's inner part, falling smoothly to 0 at its edge (the cookie's
  // border, uv 0 and 1). Unity's default spot cookie is a texture of this kind; its exact texels
  // are not published, so the fall is xshade's choice (docs/unity.md).
  return float_texture(64, 64, [](float u, float v) {
    const float r = 2.0f * std::hypot(u - 0.5f, v - 0.5f);
    const float s = std::clamp((1.0f - r) / 0.4f, 0.0f, 1.0f);
    return s * s * (3.0f - 2.0f * s);
  });
}

}  // namespace xshade::harness
