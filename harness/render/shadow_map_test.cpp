#include "harness/render/shadow_map.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace xshade::harness {
namespace {

glm::vec4 hlsl_mul_of(const std::vector<float>& m, const glm::vec4& v, size_t first = 0) {
  glm::vec4 out(0.0f);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r] += m[first + size_t(r * 4 + c)] * v[c];
  return out;
}

TEST(ShadowMap, AWorldBoxHoldsEveryCornerOfTheTransformedBox) {
  const glm::mat4 model = glm::rotate(glm::translate(glm::mat4(1.0f), {5, 0, 0}), glm::radians(45.0f), {0, 1, 0});
  const auto [low, high] = world_box({{-1, -1, -1}, {1, 1, 1}}, model);
  EXPECT_NEAR(low.x, 5.0f - std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(high.x, 5.0f + std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(low.y, -1.0f, 1e-6f);
  EXPECT_NEAR(high.z, std::sqrt(2.0f), 1e-5f);
}

TEST(ShadowMap, TheLightsViewHoldsEveryBoxAndTheReceiversMatrixMapsItIntoTheMap) {
  Light sun;
  sun.direction = glm::normalize(glm::vec3(-0.8f, 0.6f, -0.2f));
  sun.shadow_resolution = 512;
  const std::vector<std::pair<glm::vec3, glm::vec3>> boxes = {{{-1, -1, -1}, {1, 1, 1}}, {{-3, -1.2f, -3}, {3, -1, 3}}};
  const ShadowView view = directional_shadow_view(sun, boxes);
  UniformValueMap values;
  add_shadow_receiver_inputs(sun, view, values);
  const std::vector<float>& to_shadow = values["unity_WorldToShadow"];
  ASSERT_EQ(to_shadow.size(), 64u);  // four cascades' matrices
  for (const auto& box : boxes)
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? box.second.x : box.first.x, (corner & 2) ? box.second.y : box.first.y,
                        (corner & 4) ? box.second.z : box.first.z);
      const glm::vec4 texel = hlsl_mul_of(to_shadow, glm::vec4(p, 1.0f));
      EXPECT_GE(texel.x, 0.0f);
      EXPECT_LE(texel.x, 1.0f);
      EXPECT_GE(texel.y, 0.0f);
      EXPECT_LE(texel.y, 1.0f);
      EXPECT_GT(texel.z, 0.0f);
      EXPECT_LT(texel.z, 1.0f);
    }
  // Nearer the light is a smaller depth: the comparison (LEqual) is lit for the nearest caster.
  const glm::vec4 top = hlsl_mul_of(to_shadow, glm::vec4(glm::vec3(0.0f) + sun.direction, 1.0f));
  const glm::vec4 bottom = hlsl_mul_of(to_shadow, glm::vec4(glm::vec3(0.0f) - sun.direction, 1.0f));
  EXPECT_LT(top.z, bottom.z);
  EXPECT_NEAR(top.x, bottom.x, 1e-5f);  // on one ray of the light: one texel
  EXPECT_NEAR(top.y, bottom.y, 1e-5f);
  EXPECT_EQ(values["_LightShadowData"], (std::vector<float>{0.0f, 0.0f, 0.0f, 0.0f}));  // strength 1
  // A texel is the fitted square's side over the resolution.
  EXPECT_GT(view.texel, 6.0f / 512.0f);
}

TEST(ShadowMap, ASpotLightsMapIsItsConeSeenFromItsPosition) {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0, 4, 0};
  spot.direction = {0, 1, 0};  // the beam points down
  spot.range = 8.0f;
  spot.spot_angle = 60.0f;
  spot.shadow_resolution = 256;
  const ShadowView view = spot_shadow_view(spot);
  EXPECT_TRUE(view.perspective);
  UniformValueMap values;
  add_shadow_receiver_inputs(spot, view, values);
  const auto projected = [&](const glm::vec3& p) {
    const glm::vec4 c = hlsl_mul_of(values["unity_WorldToShadow"], glm::vec4(p, 1.0f));
    return glm::vec3(c) / c.w;  // UNITY_SAMPLE_SHADOW_PROJ divides by w
  };
  const glm::vec3 axis = projected({0, 0, 0});  // 4 below the light
  EXPECT_NEAR(axis.x, 0.5f, 1e-5f);
  EXPECT_NEAR(axis.y, 0.5f, 1e-5f);
  EXPECT_LT(projected({0, 2, 0}).z, axis.z);  // nearer the light, a smaller depth
  // On the cone's edge, 30 degrees off the axis, the map's border.
  const glm::vec3 edge = projected({4.0f * std::tan(glm::radians(30.0f)), 0, 0});
  EXPECT_NEAR(std::max(std::abs(edge.x - 0.5f), std::abs(edge.y - 0.5f)), 0.5f, 1e-4f);
  UniformValueMap caster;
  add_shadow_caster_inputs(spot, view, caster);
  EXPECT_FLOAT_EQ(caster["unity_LightShadowBias"][1], 0.0f);  // no pancaking for a perspective
}

TEST(ShadowMap, TheCastersBiasesAreTheLightsTexelsInClipDepthAndWorldUnits) {
  Light sun;
  sun.shadow_bias = 2.0f;
  sun.shadow_normal_bias = 0.5f;
  ShadowView view;
  view.texel = 0.01f;
  view.depth_range = 4.0f;
  UniformValueMap values;
  add_shadow_caster_inputs(sun, view, values);
  ASSERT_EQ(values["unity_LightShadowBias"].size(), 4u);
  EXPECT_FLOAT_EQ(values["unity_LightShadowBias"][0], 2.0f * 0.01f / 4.0f);
  EXPECT_FLOAT_EQ(values["unity_LightShadowBias"][1], 1.0f);  // a directional light's depth is pancaked
  EXPECT_FLOAT_EQ(values["unity_LightShadowBias"][2], 0.5f * 0.01f);
  EXPECT_EQ(values["unity_MatrixVP"], hlsl_components(view.projection * view.view));
}

}  // namespace
}  // namespace xshade::harness
