// What Vulkan's attributes become in GLSL: the vk flavour says them as Vulkan GLSL does
// (set and binding, push_constant, constant_id, gl_PointSize); the gl flavour keeps what
// OpenGL has (a binding point, a uniform block, a constant of the default).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "glsl/glsl_emitter.h"

namespace xshade::glsl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr const char* kVulkanAttributesShader = R"(
#pragma vertex vert
#pragma fragment frag
struct UBO { float4x4 mvp; };
[[vk::binding(3, 1)]] ConstantBuffer<UBO> ubo;
struct Push { float4 tint; };
[[vk::push_constant]] Push push;
[[vk::constant_id(4)]] const int MODE = 2;
[[vk::binding(5)]] Texture2D colorMap;
[[vk::binding(5)]] SamplerState colorSampler;
struct V { float4 pos : SV_Position; [[vk::location(6)]] float2 uv : TEXCOORD0; [[vk::builtin("PointSize")]] float size : PSIZE; };
V vert([[vk::location(2)]] float3 p : POSITION) { V v; v.pos = mul(ubo.mvp, float4(p, 1)); v.uv = p.xy; v.size = 3; return v; }
float4 frag(V v) : SV_Target { return colorMap.Sample(colorSampler, v.uv) * push.tint * (MODE == 2 ? 1 : 0.5); }
)";

std::string vulkan_attribute_stages(Flavour flavour, std::map<uint32_t, double> specialization = {}) {
  auto module = hlsl::compile_text("vk.hlsl", kVulkanAttributesShader, {});
  EXPECT_TRUE(module->ok());
  auto program = emit(*module, {.flavour = flavour, .specialization = std::move(specialization)});
  if (!program || !program->vertex || !program->fragment) {
    ADD_FAILURE() << (program ? "a stage is missing" : program.error().to_string());
    return "";
  }
  return program->vertex->text + program->fragment->text;
}

TEST(VulkanAttributesEmit, TheVkFlavourSaysWhatTheAttributesAsk) {
  const std::string text = vulkan_attribute_stages(Flavour::Vk);
  EXPECT_THAT(text, HasSubstr("layout(std140, set = 1, binding = 3) uniform ubo {"));
  EXPECT_THAT(text, HasSubstr("layout(std140, push_constant) uniform push {"));
  EXPECT_THAT(text, HasSubstr("layout(constant_id = 4) const int MODE = 2;"));
  EXPECT_THAT(text, HasSubstr("layout(set = 0, binding = 5) uniform texture2D colorMap;"));
  EXPECT_THAT(text, HasSubstr("layout(set = 0, binding = 5) uniform sampler colorSampler;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 2) in vec3 xs_in_POSITION0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 6) out vec2 xs_v_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 6) in vec2 xs_v_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("gl_PointSize = "));
  EXPECT_THAT(text, Not(HasSubstr("PSIZE")));
}

TEST(VulkanAttributesEmit, TheGlFlavourKeepsWhatOpenGlHas) {
  const std::string text = vulkan_attribute_stages(Flavour::Gl);
  EXPECT_THAT(text, HasSubstr("layout(std140, binding = 3) uniform ubo {"));
  EXPECT_THAT(text, HasSubstr(") uniform push {"));
  EXPECT_THAT(text, Not(HasSubstr("push_constant")));
  EXPECT_THAT(text, HasSubstr("const int MODE = 2;"));
  EXPECT_THAT(text, Not(HasSubstr("constant_id")));
  EXPECT_THAT(text, HasSubstr("layout(binding = 5) uniform sampler2D colorMap;"));
}

// A specialization constant's given value: written in on gl, which has no specialization; the vk
// flavour keeps the default, which the pipeline replaces.
TEST(VulkanAttributesEmit, AGivenSpecializationValueIsWrittenInOnGlOnly) {
  EXPECT_THAT(vulkan_attribute_stages(Flavour::Gl, {{4, 7.0}}), HasSubstr("const int MODE = 7;"));
  EXPECT_THAT(vulkan_attribute_stages(Flavour::Vk, {{4, 7.0}}),
              HasSubstr("layout(constant_id = 4) const int MODE = 2;"));
  EXPECT_THAT(vulkan_attribute_stages(Flavour::Gl, {{9, 7.0}}), HasSubstr("const int MODE = 2;"));  // another id
}

}  // namespace
}  // namespace xshade::glsl
