#include "harness/render/shader_program.h"

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

TEST(ShaderProgram, DrawingNeedsAFragmentStage) {
  auto module = hlsl::compile_text("vertex_only.hlsl", R"(#pragma vertex vert
float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Lane lane : {Lane::Gl, Lane::Vk, Lane::VkHlsl}) {
    auto program = program_for_lane(*module, lane);
    ASSERT_FALSE(program) << lane_name(lane);
    EXPECT_NE(program.error().message.find("no fragment entry point"), std::string::npos) << program.error().message;
  }
}

// A texture GLSL reserves the name of, and the loose globals: drawn by their HLSL names on every
// lane, and on OpenGL, which binds by name, found by the names the generated GLSL gives them.
TEST(ShaderProgram, TheLayoutBindsByHlslNamesAndFindsGlslNamesOnOpenGl) {
  auto module = hlsl::compile_text("reserved.hlsl", R"(#pragma fragment frag
float4 _Tint;
Texture2D sample;
SamplerState sampler_sample;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return _Tint * sample.Sample(sampler_sample, uv); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Lane lane : {Lane::Gl, Lane::Vk, Lane::VkHlsl}) {
    auto program = program_for_lane(*module, lane);
    ASSERT_TRUE(program) << lane_name(lane) << ": " << program.error().to_string();
    const ProgramLayout& layout = program->layout;
    ASSERT_EQ(layout.uniform_blocks.size(), 1u);
    ASSERT_EQ(layout.textures.size(), 1u);
    EXPECT_EQ(layout.uniform_blocks[0].name, "$Globals");
    EXPECT_EQ(layout.textures[0].name, "sample");
    if (lane != Lane::Gl) {
      EXPECT_EQ(layout.uniform_blocks[0].glsl_block, "") << lane_name(lane);
      EXPECT_EQ(layout.textures[0].glsl_name, "") << lane_name(lane);
      continue;
    }
    const std::string& glsl = program->fragment.glsl;
    EXPECT_NE(glsl.find("uniform " + layout.uniform_blocks[0].glsl_block_name() + " {"), std::string::npos) << glsl;
    EXPECT_NE(layout.textures[0].uniform_name(), "sample");
    EXPECT_NE(glsl.find(" " + layout.textures[0].uniform_name() + ";"), std::string::npos) << glsl;
  }
}

}  // namespace
}  // namespace xshade::harness
