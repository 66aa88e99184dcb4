// Vulkan HLSL drawn on every lane: a texture and its sampler at one [[vk::binding]] (one
// combined image sampler serves both on Vulkan), specialization constants at their defaults and
// given other values,
// and a user-defined semantic and [[vk::location]] between the stages of a program.
#include <cstring>
#include <string>
#include <vector>

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

// A float, an int (a loop's count) and a bool specialization constant, each read back.
constexpr const char* kSpecializedSource = R"(
#pragma fragment f
[[vk::constant_id(0)]] const float SCALE = 0.5;
[[vk::constant_id(3)]] const int COUNT = 2;
[[vk::constant_id(5)]] const bool FLIP = false;
float4 f(float2 uv : TEXCOORD0) : SV_Target {
  float sum = 0;
  for (int i = 0; i < COUNT; ++i) sum += 0.125;
  return float4(SCALE, sum, FLIP ? 1 : 0, 1);
}
)";

TEST_F(VulkanAttributesDraw, SpecializationConstantsReadTheirDefaultsOrTheValuesGivenOnEveryLane) {
  auto module = hlsl::compile_text("specialized.hlsl", kSpecializedSource, {});
  ASSERT_TRUE(module->ok());
  auto given = harness::resolve_specialization({"SCALE=0.75", "COUNT=5", "FLIP=1"}, module->reflection);
  ASSERT_TRUE(given) << given.error().to_string();
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto defaults = harness::evaluate(*module, lane, backend(lane), 1, 1);
    ASSERT_TRUE(defaults) << defaults.error().to_string();
    EXPECT_EQ(defaults->at(0, 0), glm::vec4(0.5f, 2 * 0.125f, 0.0f, 1.0f));
    auto specialized = harness::evaluate(*module, lane, backend(lane), 1, 1, {}, {.specialization = *given});
    ASSERT_TRUE(specialized) << specialized.error().to_string();
    EXPECT_EQ(specialized->at(0, 0), glm::vec4(0.75f, 5 * 0.125f, 1.0f, 1.0f));
  }
}

// Members at the byte offsets [[vk::offset]] gives (past HLSL's packing) and a texture and its
// sampler made one combined image sampler by [[vk::combinedImageSampler]].
constexpr const char* kOffsetsSource = R"(
#pragma fragment f
struct Params { float a; [[vk::offset(32)]] float4 tint; };
[[vk::binding(0)]] ConstantBuffer<Params> params;
cbuffer Extra : register(b1) { float e0; [[vk::offset(20)]] float e1; };
[[vk::combinedImageSampler]] [[vk::binding(3)]] Texture2D tex;
[[vk::combinedImageSampler]] [[vk::binding(3)]] SamplerState smp;
float4 f(float2 uv : TEXCOORD0) : SV_Target { return params.tint * params.a * tex.Sample(smp, uv) + e1; }
)";

TEST_F(VulkanAttributesDraw, MembersAtTheirVkOffsetsAndACombinedImageSamplerReadWhatTheHostWroteThere) {
  auto module = hlsl::compile_text("offsets.hlsl", kOffsetsSource, {});
  ASSERT_TRUE(module->ok());
  const hlsl::ConstantBuffer* params = module->reflection.find_constant_buffer("params");
  const hlsl::ConstantBuffer* extra = module->reflection.find_constant_buffer("Extra");
  ASSERT_TRUE(params && extra);
  ASSERT_EQ(params->members.at(1).offset, 32u);
  ASSERT_EQ(extra->members.at(1).offset, 20u);
  std::vector<std::byte> params_bytes(params->size), extra_bytes(extra->size);
  const float a = 0.5f, tint[4] = {0.2f, 0.4f, 0.6f, 0.8f}, e1 = 0.125f;
  std::memcpy(params_bytes.data(), &a, 4);
  std::memcpy(params_bytes.data() + 32, tint, 16);
  std::memcpy(extra_bytes.data() + 20, &e1, 4);
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image =
        harness::evaluate(*module, lane, backend(lane), 1, 1, {{"params", params_bytes}, {"Extra", extra_bytes}});
    ASSERT_TRUE(image) << image.error().to_string();
    for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(image->at(0, 0)[c], tint[c] * a + e1) << "channel " << c;
  }
}

TEST_F(VulkanAttributesDraw, ASpecializationValueMustNameAConstantAndFitItsType) {
  auto module = hlsl::compile_text("specialized.hlsl", kSpecializedSource, {});
  ASSERT_TRUE(module->ok());
  const auto message = [&](const std::string& text) {
    auto resolved = harness::resolve_specialization({text}, module->reflection);
    return resolved ? std::string("(resolved)") : resolved.error().message;
  };
  EXPECT_EQ(message("SCALX=1"),
            "--specialize SCALX=1: expected NAME=VALUE naming a [[vk::constant_id]] constant of the "
            "shader (it has SCALE, COUNT, FLIP)");
  EXPECT_EQ(message("COUNT=1.5"),
            "--specialize COUNT=1.5: 'COUNT' is of type int; give it a whole number in its range");
  EXPECT_EQ(message("FLIP=2"), "--specialize FLIP=2: 'FLIP' is of type bool; give it 0 or 1");
  EXPECT_EQ(message("SCALE=x"), "--specialize SCALE=x: 'SCALE' is of type float; give it a finite number");
}

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

// A push-constant block given like any constant buffer: push constants on the Vulkan lanes, a
// uniform block on gl. glslang's HLSL front end (vk-hlsl) keeps only ConstantBuffer<T>'s form.
constexpr const char* kPushConstantsSource = R"(
#pragma fragment f
struct Tint { float4 color; float scale; };
[[vk::push_constant]] ConstantBuffer<Tint> tint;
float4 f(float2 uv : TEXCOORD0) : SV_Target { return tint.color * tint.scale; }
)";
constexpr const char* kPushConstantGlobalSource = R"(
#pragma fragment f
struct Tint { float4 color; float scale; };
[[vk::push_constant]] Tint tint;
float4 f(float2 uv : TEXCOORD0) : SV_Target { return tint.color * tint.scale; }
)";

TEST_F(VulkanAttributesDraw, APushConstantBlockReadsWhatTheHostGivesOnEveryLane) {
  struct Tint {
    float color[4];
    float scale;
    float pad[3];  // HLSL rounds a buffer up to 16 bytes
  } given{{0.25f, 0.5f, 0.75f, 1.0f}, 0.5f, {}};
  for (const char* source : {kPushConstantsSource, kPushConstantGlobalSource}) {
    for (Lane lane : harness::all_lanes()) {
      SCOPED_TRACE(std::string(harness::lane_name(lane)) +
                   (source == kPushConstantsSource ? " ConstantBuffer" : " struct"));
      auto module = hlsl::compile_text("push.hlsl", source, {});
      ASSERT_TRUE(module->ok());
      ASSERT_TRUE(module->reflection.constant_buffers.at(0).push_constant);
      auto image = harness::evaluate(*module, lane, backend(lane), 2, 2, {{"tint", harness::uniform_bytes(given)}});
      if (lane == Lane::VkHlsl && source == kPushConstantGlobalSource) {
        ASSERT_FALSE(image);
        EXPECT_NE(image.error().to_string().find("reads a [[vk::push_constant]] struct global as a member of $Global"),
                  std::string::npos)
            << image.error().to_string();
        continue;
      }
      ASSERT_TRUE(image) << image.error().to_string();
      const glm::vec4 got = image->at(1, 1);
      EXPECT_FLOAT_EQ(got.x, 0.125f);
      EXPECT_FLOAT_EQ(got.y, 0.25f);
      EXPECT_FLOAT_EQ(got.z, 0.375f);
      EXPECT_FLOAT_EQ(got.w, 0.5f);
    }
  }
}

}  // namespace
}  // namespace xshade::tests
