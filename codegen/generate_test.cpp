#include "codegen/generate.h"

#include <gtest/gtest.h>

#include "spirv/spirv_compiler.h"

namespace xshade::codegen {
namespace {

constexpr Target kTargets[] = {Target::Gl, Target::Vk, Target::Spirv, Target::VkHlsl};

constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
struct v2f {
  float4 pos : SV_Position;
  float3 lights[2] : TEXCOORD2;
  float3 view : TEXCOORD3;
};
v2f vert(float4 p : POSITION) {
  v2f o;
  o.pos = p;
  o.lights[0] = p.xyz;
  o.lights[1] = p.zyx;
  o.view = p.xxx;
  return o;
}
float4 frag(v2f i) : SV_Target { return float4(i.lights[0] + i.lights[1] + i.view, 1); }
)";

TEST(Generate, EveryTargetGivesEveryStageInItsForm) {
  auto module = hlsl::compile_text("lights.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Target target : kTargets) {
    auto generated = generate(*module, target, {.check_gl = true});
    ASSERT_TRUE(generated) << target_name(target) << ": " << generated.error().to_string();
    ASSERT_TRUE(generated->vertex && generated->fragment) << target_name(target);
    EXPECT_EQ(generated->fragment->glsl.empty(), makes_spirv(target)) << target_name(target);
    // vk's text was checked by compiling it: the module comes along.
    EXPECT_EQ(generated->fragment->spirv.empty(), target == Target::Gl) << target_name(target);
    if (!makes_spirv(target))
      EXPECT_NE(generated->fragment->glsl.find("#version 450"), std::string::npos);
    else
      EXPECT_EQ(generated->fragment->spirv.at(0), 0x07230203u);  // the SPIR-V magic number
  }
  // What the gl target gives, glslang accepts as OpenGL GLSL.
  auto gl = generate(*module, Target::Gl);
  ASSERT_TRUE(gl);
  EXPECT_TRUE(spirv::validate_opengl_glsl(gl->vertex->glsl, spirv::Stage::Vertex, "lights.hlsl.vert"));
}

TEST(Generate, AFileWithOneStageGivesThatStageOnEveryTarget) {
  auto module = hlsl::compile_text("vertex_only.hlsl", R"(#pragma vertex vert
float4x4 _ObjectToClip;
struct V { float4 position : SV_Position; float2 uv : TEXCOORD0; };
V vert(float3 p : POSITION, float2 uv : TEXCOORD0) { V o; o.position = mul(_ObjectToClip, float4(p, 1)); o.uv = uv; return o; }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Target target : kTargets) {
    auto generated = generate(*module, target);
    ASSERT_TRUE(generated) << target_name(target) << ": " << generated.error().to_string();
    ASSERT_TRUE(generated->vertex) << target_name(target);
    EXPECT_FALSE(generated->fragment) << target_name(target);
  }
}

TEST(Generate, WhatTheTargetCannotExpressStaysTheAuthorsError) {
  // Integer matrices: HLSL has them, GLSL does not.
  auto module = hlsl::compile_text("imatrix.hlsl", R"(#pragma fragment frag
int2x2 m;
float4 frag() : SV_Target { return float4(m[0].x, 0, 0, 1); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  auto generated = generate(*module, Target::Gl);
  ASSERT_FALSE(generated);
  EXPECT_EQ(generated.error().kind, ErrorKind::UserInput);
}

TEST(Generate, AModuleWithoutEntryPointsHasNoStages) {
  auto module = hlsl::compile_text("library.hlsl", "float twice(float x) { return 2 * x; }\n", {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Target target : kTargets) {
    auto generated = generate(*module, target);
    ASSERT_TRUE(generated) << generated.error().to_string();
    EXPECT_FALSE(generated->vertex || generated->fragment);
  }
}

TEST(Generate, VkHlslRefusesWhatOnlyXshadesGlslCanDo) {
  auto module = hlsl::compile_text("lights.hlsl", kShader, {});
  ASSERT_TRUE(module->ok());
  auto half = generate(*module, Target::VkHlsl, {.half_emulation = true});
  ASSERT_FALSE(half);
  EXPECT_NE(half.error().message.find("cannot emulate half"), std::string::npos) << half.error().message;
  auto traced = generate(*module, Target::VkHlsl, {.trace_nonfinite = true});
  ASSERT_FALSE(traced);
  EXPECT_NE(traced.error().message.find("cannot be traced"), std::string::npos) << traced.error().message;
}

// Names GLSL reserves (`sample`), the loose globals, a read-only buffer and a shadow map: the
// interface gives each the name the target's code declares it by.
constexpr const char* kResources = R"(#pragma fragment frag
float4 _Tint;
Texture2D sample : register(t0);
SamplerState sampler_sample : register(s0);
Texture2D _Shadow : register(t1);
SamplerComparisonState shadow_cmp : register(s1);
StructuredBuffer<float4> palette : register(t2);
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return _Tint * sample.Sample(sampler_sample, uv) * _Shadow.SampleCmp(shadow_cmp, uv, 0.5) * palette[0];
}
)";

TEST(Generate, TheInterfaceNamesWhatTheCodeDeclares) {
  auto module = hlsl::compile_text("resources.hlsl", kResources, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  for (const Target target : kTargets) {
    auto generated = generate(*module, target, {.filter_comparisons = true});
    ASSERT_TRUE(generated) << target_name(target) << ": " << generated.error().to_string();
    const BindingInterface& interface = generated->interface;
    ASSERT_EQ(interface.uniform_blocks.size(), 1u);
    ASSERT_EQ(interface.textures.size(), 2u);
    ASSERT_EQ(interface.storage_buffers.size(), 1u);
    const bool glslang = target == Target::VkHlsl;
    EXPECT_EQ(interface.uniform_blocks[0].name, "$Globals");
    EXPECT_EQ(interface.uniform_blocks[0].code_name, glslang ? "$Global" : "xs_Globals");
    EXPECT_EQ(interface.textures[0].name, "sample");
    EXPECT_EQ(interface.storage_buffers[0].code_name, glslang ? "palette" : "xs_buffer_palette");
    // Only the vk flavour's code filters comparisons itself; OpenGL filters, vk-hlsl cannot.
    const bool vk_glsl = target == Target::Vk || target == Target::Spirv;
    EXPECT_EQ(interface.textures[1].filtered_in_shader, vk_glsl) << target_name(target);
    // On Vulkan a texture is a sampled image with its sampler at a binding of its own; OpenGL combines them.
    EXPECT_EQ(interface.textures[0].sampler_binding.has_value(), target != Target::Gl) << target_name(target);
    if (glslang) continue;
    // The GLSL declares the names the interface gives.
    const std::string& glsl = generated->fragment->glsl;
    if (glsl.empty()) continue;  // spirv: the same GLSL as vk, compiled
    EXPECT_NE(interface.textures[0].code_name, "sample");
    EXPECT_NE(glsl.find(" " + interface.textures[0].code_name + ";"), std::string::npos) << glsl;
    EXPECT_NE(glsl.find("uniform " + interface.uniform_blocks[0].code_name + " {"), std::string::npos) << glsl;
    EXPECT_NE(glsl.find("buffer " + interface.storage_buffers[0].code_name + " {"), std::string::npos) << glsl;
  }
}

TEST(Generate, TheFullScreenTriangleComesInTheTargetsForm) {
  auto module = hlsl::compile_text("post.hlsl", R"(#pragma fragment frag
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return float4(uv, 0, 1); }
)",
                                   {});
  ASSERT_TRUE(module->ok());
  for (const Target target : kTargets) {
    auto vertex = fullscreen_vertex(target, module->reflection);
    ASSERT_TRUE(vertex) << vertex.error().to_string();
    EXPECT_EQ(vertex->glsl.empty(), makes_spirv(target));
    EXPECT_EQ(vertex->spirv.empty(), !makes_spirv(target));
  }
}

TEST(TargetNamed, KnowsEveryTargetAndNothingElse) {
  for (const Target target : kTargets) EXPECT_EQ(target_named(target_name(target)), target);
  EXPECT_EQ(target_named("vk"), Target::Vk);
  EXPECT_EQ(target_named("vk-hlsl"), Target::VkHlsl);
  EXPECT_FALSE(target_named("metal"));
}

}  // namespace
}  // namespace xshade::codegen
