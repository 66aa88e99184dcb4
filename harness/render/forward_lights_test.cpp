#include "harness/render/forward_lights.h"

#include <cmath>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

Light light_of(LightType type, float intensity, glm::vec3 position = glm::vec3(0.0f)) {
  Light light;
  light.type = type;
  light.intensity = intensity;
  light.position = position;
  return light;
}

// mul(M, v) for M in HLSL component order (row by row), as a shader computes it.
glm::vec4 hlsl_mul(const std::vector<float>& m, const glm::vec4& v) {
  glm::vec4 out(0.0f);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r] += m[size_t(r * 4 + c)] * v[c];
  return out;
}

TEST(ForwardLights, TheBrightestDirectionalLightIsMainThenPixelLightsByBrightnessThenPointLightsPerVertex) {
  Scene scene;
  scene.pixel_lights = 2;
  scene.lights = {light_of(LightType::Point, 1.0f),       light_of(LightType::Directional, 0.5f),
                  light_of(LightType::Directional, 2.0f), light_of(LightType::Spot, 3.0f),
                  light_of(LightType::Point, 0.2f),       light_of(LightType::Spot, 0.1f)};
  const ForwardLights lights = forward_lights(scene);
  EXPECT_EQ(lights.main, 2u);
  EXPECT_EQ(lights.pixel, (std::vector<size_t>{3, 0}));  // brightest first
  EXPECT_EQ(lights.vertex, (std::vector<size_t>{4}));    // only point lights light per vertex
  ASSERT_EQ(lights.left_out.size(), 2u);                 // the dimmer directional one and the last spot
  EXPECT_NE(lights.left_out[0].find("light 2"), std::string::npos) << lights.left_out[0];
  EXPECT_NE(lights.left_out[1].find("only point lights light per vertex"), std::string::npos) << lights.left_out[1];

  Scene one;
  one.lights = {light_of(LightType::Directional, 1.0f)};
  const ForwardLights single = forward_lights(one);
  EXPECT_EQ(single.main, 0u);
  EXPECT_TRUE(single.pixel.empty());  // no ForwardAdd for a scene of one light
  Scene without;
  without.lights = {light_of(LightType::Point, 1.0f)};
  EXPECT_FALSE(forward_lights(without).main);
  EXPECT_EQ(forward_lights(without).pixel, (std::vector<size_t>{0}));
}

TEST(ForwardLights, TheFalloffIsUnitysOneOverOnePlusTwentyFiveTAndEndsAtTheRange) {
  EXPECT_FLOAT_EQ(light_falloff(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(light_falloff(0.04f), 0.5f);  // 1 / (1 + 25 * 0.04)
  EXPECT_FLOAT_EQ(light_falloff(0.64f), 1.0f / 17.0f);
  EXPECT_NEAR(light_falloff(0.82f), 0.5f / (1.0f + 25.0f * 0.82f), 1e-6f);  // half way through the fade
  EXPECT_FLOAT_EQ(light_falloff(1.0f), 0.0f);
  EXPECT_FLOAT_EQ(light_falloff(4.0f), 0.0f);
}

TEST(ForwardLights, APointLightsSpaceHasItsRangeOne) {
  UniformValueMap values;
  Light point = light_of(LightType::Point, 2.0f, {1, 2, 3});
  point.range = 4.0f;
  point.color = {1.0f, 0.5f, 0.0f};
  add_light_inputs(point, values);
  EXPECT_EQ(values["_WorldSpaceLightPos0"], (std::vector<float>{1, 2, 3, 1}));
  EXPECT_EQ(values["_LightColor0"], (std::vector<float>{2, 1, 0, 2}));
  const glm::vec4 at = hlsl_mul(values["unity_WorldToLight"], {1, 2, 5, 1});  // 2 from the light along z
  EXPECT_NEAR(glm::dot(glm::vec3(at), glm::vec3(at)), 0.25f, 1e-6f);          // (2 / 4)^2
}

TEST(ForwardLights, ASpotLightsSpaceSpansItsConeWithTheCookieAndMeasuresDistanceAsAPointLights) {
  UniformValueMap values;
  Light spot = light_of(LightType::Spot, 1.0f, {0, 4, 0});
  spot.direction = {0, 1, 0};  // toward the light: the beam points down
  spot.range = 8.0f;
  spot.spot_angle = 60.0f;
  add_light_inputs(spot, values);
  const std::vector<float>& to_light = values["unity_WorldToLight"];
  const glm::vec4 centre = hlsl_mul(to_light, {0, 0, 0, 1});  // 4 below the light, on the axis
  EXPECT_NEAR(centre.x / centre.w, 0.0f, 1e-6f);
  EXPECT_NEAR(centre.y / centre.w, 0.0f, 1e-6f);
  EXPECT_GT(centre.z, 0.0f);  // in front of the light (AutoLight's lightCoord.z > 0)
  EXPECT_NEAR(glm::dot(glm::vec3(centre), glm::vec3(centre)), 0.25f, 1e-6f);  // (4 / 8)^2
  // On the cone's edge, 30 degrees off the axis: the cookie's border, xy / w at 0.5 from its centre.
  const float off = 4.0f * std::tan(glm::radians(30.0f));
  const glm::vec4 edge = hlsl_mul(to_light, {off, 0, 0, 1});
  EXPECT_NEAR(glm::length(glm::vec2(edge) / edge.w), 0.5f, 1e-5f);
  // Behind the light: z < 0, which AutoLight's spot attenuation turns to 0.
  EXPECT_LT(hlsl_mul(to_light, {0, 6, 0, 1}).z, 0.0f);
}

TEST(ForwardLights, VertexLightsFillUnitys4LightSlotsWithTheFalloffsConstant) {
  Scene scene;
  Light point = light_of(LightType::Point, 2.0f, {1, 2, 3});
  point.range = 5.0f;
  scene.lights = {point};
  UniformValueMap values;
  add_vertex_light_inputs(scene, {0}, values);
  EXPECT_EQ(values["unity_4LightPosX0"], (std::vector<float>{1, 0, 0, 0}));
  EXPECT_EQ(values["unity_4LightPosZ0"], (std::vector<float>{3, 0, 0, 0}));
  EXPECT_FLOAT_EQ(values["unity_4LightAtten0"][0], 1.0f);  // 25 / 5^2
  EXPECT_FLOAT_EQ(values["unity_LightColor"][0], 2.0f);
  EXPECT_EQ(values["unity_LightColor"].size(), 32u);
}

}  // namespace
}  // namespace xshade::harness
