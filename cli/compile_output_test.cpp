#include "cli/compile_output.h"

#include <gtest/gtest.h>

#include "cli/commands.h"
#include "spirv/spirv_compiler.h"

namespace xshade::cli {
namespace {

using codegen::Target;

constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
float4 vert(float4 p : POSITION, out float2 uv : TEXCOORD0) : SV_Position { uv = p.xy; return p; }
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return float4(uv, 0, 1); }
)";

TEST(CompileOutput, EveryTargetGivesEveryStageValidatedAndReadable) {
  auto module = hlsl::compile_text("uv.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Target target : {Target::Gl, Target::Vk, Target::Spirv, Target::VkHlsl}) {
    auto output = compile_output(*module, {.target = target});
    ASSERT_TRUE(output) << output.error().to_string();
    ASSERT_TRUE(output->vertex && output->fragment);
    const bool spirv = target == Target::Spirv || target == Target::VkHlsl;
    EXPECT_EQ(output->fragment->words.empty(), !spirv);
    EXPECT_NE(output->fragment->text.find(spirv ? "OpEntryPoint" : "#version 450"), std::string::npos);
    // What the gl target writes, glslang accepts: compile_output had it checked.
    if (target == Target::Gl) {
      EXPECT_TRUE(spirv::validate_opengl_glsl(output->vertex->text, spirv::Stage::Vertex, "uv.hlsl.vert"));
    }
  }
}

// The vk-hlsl target compiles the source with glslang: what only xshade's GLSL can do, asked of it,
// is the command line's mistake (--precision half, --trace-nonfinite), not the shader's.
TEST(CompileOutput, WhatVkHlslCannotDoIsTheCommandLinesMistake) {
  auto module = hlsl::compile_text("uv.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const OutputOptions& options : {OutputOptions{.target = Target::VkHlsl, .half_emulation = true},
                                       OutputOptions{.target = Target::VkHlsl, .trace_nonfinite = true}}) {
    auto output = compile_output(*module, options);
    ASSERT_FALSE(output);
    EXPECT_EQ(output.error().kind, ErrorKind::Usage) << output.error().message;
    EXPECT_EQ(exit_code_of(output.error().kind), kBadInput);
  }
}

TEST(ExitCodeOf, WhoseFaultDecides) {
  EXPECT_EQ(exit_code_of(ErrorKind::UserInput), 2);
  EXPECT_EQ(exit_code_of(ErrorKind::Usage), 2);
  EXPECT_EQ(exit_code_of(ErrorKind::CheckFailed), 1);
  EXPECT_EQ(exit_code_of(ErrorKind::Backend), 3);
  EXPECT_EQ(exit_code_of(ErrorKind::Internal), 3);
}

}  // namespace
}  // namespace xshade::cli
