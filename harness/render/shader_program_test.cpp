#include "harness/render/shader_program.h"

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

constexpr const char* kVertexOnly = R"(#pragma vertex vert
float4x4 _ObjectToClip;
struct V { float4 position : SV_Position; float2 uv : TEXCOORD0; };
V vert(float3 p : POSITION, float2 uv : TEXCOORD0) { V o; o.position = mul(_ObjectToClip, float4(p, 1)); o.uv = uv; return o; }
)";

TEST(ShaderProgram, AFileWithOneStageCompilesToThatStageOnEveryLane) {
  auto module = hlsl::compile_text("vertex_only.hlsl", kVertexOnly, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Lane lane : {Lane::Gl, Lane::Vk, Lane::VkHlsl}) {
    auto stages = stages_for_lane(*module, lane);
    ASSERT_TRUE(stages) << lane_name(lane) << ": " << stages.error().to_string();
    ASSERT_TRUE(stages->vertex) << lane_name(lane);
    EXPECT_FALSE(stages->fragment) << lane_name(lane);
    if (lane == Lane::Gl) EXPECT_NE(stages->vertex->glsl.find("gl_Position"), std::string::npos);
    else EXPECT_FALSE(stages->vertex->spirv.empty()) << lane_name(lane);
  }
  // Drawing needs a fragment stage: a program says so.
  auto program = program_for_lane(*module, Lane::Vk);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("no fragment entry point"), std::string::npos) << program.error().message;
}

// HLSL packs a float3 after a float into the same 16-byte register (byte 4); glslang's HLSL front
// end (12.0) does so in a declared cbuffer (the conformance rule constant_buffer) but starts it at
// the next register in $Globals. The harness writes HLSL's layout, so the vk-hlsl lane refuses
// such a buffer rather than read the wrong bytes; gl and vk keep HLSL's offsets.
TEST(ShaderProgram, TheVkHlslLaneRefusesABufferGlslangLaysOutOtherwise) {
  auto module = hlsl::compile_text("packing.hlsl", R"(#pragma fragment frag
float _Phase;
float3 _NoiseParameters;
float4 frag() : SV_Target { return float4(_NoiseParameters, _Phase); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  ASSERT_EQ(module->reflection.constant_buffers.at(0).members.at(1).offset, 4u);
  EXPECT_TRUE(program_for_lane(*module, Lane::Gl));
  EXPECT_TRUE(program_for_lane(*module, Lane::Vk));
  auto hlsl_lane = program_for_lane(*module, Lane::VkHlsl);
  ASSERT_FALSE(hlsl_lane);
  EXPECT_EQ(hlsl_lane.error().message,
            "vk-hlsl lane: glslang's HLSL front end puts '_NoiseParameters' of '$Globals' at byte 16, HLSL's packing "
            "(fxc, DXC and xshade) at byte 4: the lane would read another member's bytes");
}

}  // namespace
}  // namespace xshade::harness
