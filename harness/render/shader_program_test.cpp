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

}  // namespace
}  // namespace xshade::harness
