// Vulkan HLSL drawn on every lane: a texture and its sampler at one [[vk::binding]] (one
// combined image sampler serves both on Vulkan), a specialization constant read at its default,
// and a user-defined semantic and [[vk::location]] between the stages of a program.
#include <cstring>

#include <gtest/gtest.h>

#include "harness/render/evaluate.h"
#include "harness/render/shader_program.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

constexpr const char* kVulkanAttributesSource = R"(
#pragma fragment f
[[vk::binding(1)]] Texture2D colorMap : register(t0);
[[vk::binding(1)]] SamplerState colorSampler : register(s0);
[[vk::constant_id(0)]] const float SCALE = 0.5;
float4 f(float2 uv : TEXCOORD0, [[vk::location(3)]] float2 other : MYUV) : SV_Target {
  return colorMap.Sample(colorSampler, uv) * SCALE + float4(0, 0, other.x - uv.x, 0);
}
)";

class VulkanAttributesDraw : public LaneTest {};

TEST_F(VulkanAttributesDraw, ACombinedBindingAndASpecializationConstantReadTheSameOnEveryLane) {
  // One texel of (0.2, 0.4, 0.6, 0.8): the image is that times SCALE's default, 0.5, and the
  // user-semantic input receives uv as every float input of a full-screen pass does.
  harness::TextureData texel;
  texel.format = harness::TextureFormat::Rgba32Float;
  texel.width = texel.height = 1;
  const float value[4] = {0.2f, 0.4f, 0.6f, 0.8f};
  texel.levels.emplace_back(sizeof value);
  std::memcpy(texel.levels[0].data(), value, sizeof value);
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto module = hlsl::compile_text("vk_attributes.hlsl", kVulkanAttributesSource, {});
    ASSERT_TRUE(module->ok());
    EXPECT_EQ(module->reflection.textures.at(0).binding, 1u);
    auto uploaded = backend(lane).upload_texture(texel);
    ASSERT_TRUE(uploaded) << uploaded.error().to_string();
    auto image = harness::evaluate(*module, lane, backend(lane), 4, 4, {}, {},
                                   {{"colorMap", harness::TextureSource::texture(*uploaded)}});
    ASSERT_TRUE(image) << image.error().to_string();
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x) {
        const glm::vec4 got = image->at(x, y);
        EXPECT_FLOAT_EQ(got.x, 0.1f) << x << "," << y;
        EXPECT_FLOAT_EQ(got.y, 0.2f) << x << "," << y;
        EXPECT_FLOAT_EQ(got.z, 0.3f) << x << "," << y;
        EXPECT_FLOAT_EQ(got.w, 0.4f) << x << "," << y;
      }
  }
}

}  // namespace
}  // namespace xshade::tests
