// The GLSL emitter's program-level rules (docs/hlsl_like.md) in both flavours: entry points and
// the stage interface, constant buffers, textures, names, #line directives, half emulation, what
// is reached, errors and determinism. Expressions and statements: emit_expressions_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "glsl/emitter_test_support.h"
#include "glsl/glsl_names.h"

namespace xshade::glsl::emitter_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// Half emulation rounds each half result once, where it is made, and leaves float alone.
TEST(GlslEmitterHalfEmulation, RoundsHalfResultsOnceAndFloatNever) {
  auto module =
      hlsl::compile_text("test.hlsl",
                         fragment_source("float _F = 1.0;",
                                         "half3 c = half3(_F, 0.5, 2.0);\nhalf h = (half)_F * 3.0;\n"
                                         "float f = _F * 3.0;\nhalf t = (half)_F * 0.1;\nreturn float4(c * h * t, f);"),
                         {});
  ASSERT_TRUE(module->ok()) << diagnostics_of(*module);
  auto plain = emit(*module, {Flavour::Gl, false});
  auto emulated = emit(*module, {Flavour::Gl, true});
  ASSERT_TRUE(plain && emulated);
  EXPECT_EQ(plain->fragment->text.find("xs_half"), std::string::npos);
  const std::string& text = emulated->fragment->text;
  EXPECT_NE(text.find("float xs_half(float x) {"), std::string::npos) << text;
  EXPECT_NE(text.find("vec3 xs_half(vec3 x) {"), std::string::npos) << text;
  EXPECT_NE(text.find("float f = _F * 3.0;"), std::string::npos) << text;
  // The conversion and the product each round once; a literal is rounded by the emitter, so that
  // it stays a constant expression (3.0 is an fp16 number, 0.1 is not).
  EXPECT_NE(text.find("float h = xs_half(xs_half(_F) * 3.0);"), std::string::npos) << text;
  EXPECT_NE(text.find("xs_half(_F) * 0.099975586"), std::string::npos) << text;
}

TEST(GlslEmitterConstantBuffers, BlocksKeepHlslOffsetsAndPacking) {
  const std::string globals =
      "cbuffer PerFrame : register(b2) { float4x4 view; row_major float4x4 proj; float4 weights[3]; };\n"
      "float4 _Color; float _A; float2 _B; float3 _C; bool _Flag;\n";
  const std::string gl = fragment(globals, "return _Color + view[0] + proj[1] + weights[2] + _A + _B.y + _C.z;");
  EXPECT_THAT(gl, HasSubstr("layout(std140, binding = 2) uniform PerFrame {"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 0, row_major) mat4 view;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 64, column_major) mat4 proj;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 128) vec4 weights[3];"));
  EXPECT_THAT(gl, HasSubstr("uniform xs_Globals {"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 0) vec4 _Color;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 16) float _A;"));
  // _B at 20 cannot be a std140 vec2 (8-byte aligned): it is two floats, rebuilt where read.
  EXPECT_THAT(gl, HasSubstr("layout(offset = 20) float _B_0;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 24) float _B_1;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 32) vec3 _C;"));
  EXPECT_THAT(gl, HasSubstr("layout(offset = 44) bool _Flag;"));
  EXPECT_THAT(gl, HasSubstr("_B_1 + _C.z"));
  const std::string vk = fragment(globals, "return _Color + float4(_B, _B);", Flavour::Vk);
  EXPECT_THAT(vk, HasSubstr("layout(std140, set = 0, binding = 2) uniform PerFrame {"));
  EXPECT_THAT(vk, HasSubstr("vec4(vec2(_B_0, _B_1), vec2(_B_0, _B_1))"));
}

TEST(GlslEmitterConstantBuffers, BlockNames) {
  EXPECT_EQ(block_name("$Globals"), "xs_Globals");
  EXPECT_EQ(block_name("PerFrame"), "PerFrame");
  EXPECT_EQ(block_name("buffer"), "buffer_");
}

TEST(GlslEmitterConstantBuffers, StructMembers) {
  const std::string text = fragment(
      "struct Light { float4 dir; float4 color; };\n"
      "cbuffer Lights { Light lights[2]; float4x4 m; };\n",
      "return lights[1].color + m[0];");
  EXPECT_THAT(text, HasSubstr("struct Light {\n  vec4 dir;\n  vec4 color;\n};"));
  EXPECT_THAT(text, HasSubstr("layout(offset = 0) Light lights[2];"));
  EXPECT_THAT(text, HasSubstr("return lights[1].color + m[0];"));
}

const char* const kTextures =
    "Texture2D _MainTex; SamplerState sampler_MainTex; sampler2D _Ramp;\n"
    "float4 Blur(Texture2D t, SamplerState s, float2 uv) { return t.SampleLevel(s, uv, 1); }\n";
const char* const kTextureBody =
    "float4 a = _MainTex.Sample(sampler_MainTex, uv) + tex2D(_Ramp, uv) + Blur(_MainTex, sampler_MainTex, uv);\n"
    "float4 b = _MainTex.Load(int3(2, 3, 0));\n"
    "uint w, h;\n"
    "_MainTex.GetDimensions(w, h);\n"
    "return a + b + tex2Dlod(_Ramp, float4(uv, 0, 1)) + w;";

TEST(GlslEmitterTextures, OpenGlCombinesTextureAndSampler) {
  const std::string text = fragment(kTextures, kTextureBody, Flavour::Gl);
  EXPECT_THAT(text, HasSubstr("layout(binding = 16) uniform sampler2D _MainTex;"));
  EXPECT_THAT(text, HasSubstr("layout(binding = 17) uniform sampler2D _Ramp;"));
  EXPECT_THAT(text, Not(HasSubstr("sampler_MainTex;")));  // sampler state belongs to the texture unit
  EXPECT_THAT(text, HasSubstr("vec4 Blur(sampler2D t, vec2 uv) {"));
  EXPECT_THAT(text, HasSubstr("return textureLod(t, uv, 1.0);"));
  EXPECT_THAT(text, HasSubstr("texture(_MainTex, uv) + texture(_Ramp, uv) + Blur(_MainTex, uv);"));
  EXPECT_THAT(text, HasSubstr("vec4 b = xs_Load(_MainTex, ivec3(2, 3, 0));"));
  EXPECT_THAT(text, HasSubstr("(w = uint(textureSize(_MainTex, 0).x), h = uint(textureSize(_MainTex, 0).y));"));
  EXPECT_THAT(text, Not(HasSubstr("#extension")));
}

TEST(GlslEmitterTextures, VulkanKeepsThemSeparate) {
  const std::string text = fragment(kTextures, kTextureBody, Flavour::Vk);
  EXPECT_THAT(text, HasSubstr("#version 450\n#extension GL_EXT_samplerless_texture_functions : require\n"));
  EXPECT_THAT(text, HasSubstr("layout(set = 0, binding = 16) uniform texture2D _MainTex;"));
  EXPECT_THAT(text, HasSubstr("layout(set = 0, binding = 17) uniform sampler2D _Ramp;"));
  EXPECT_THAT(text, HasSubstr("layout(set = 0, binding = 32) uniform sampler sampler_MainTex;"));
  EXPECT_THAT(text, HasSubstr("vec4 Blur(texture2D t, sampler s, vec2 uv) {"));
  EXPECT_THAT(text, HasSubstr("return textureLod(sampler2D(t, s), uv, 1.0);"));
  EXPECT_THAT(text, HasSubstr("texture(sampler2D(_MainTex, sampler_MainTex), uv) + texture(_Ramp, uv)"));
  EXPECT_THAT(text, HasSubstr("vec4 xs_Load(texture2D a0, ivec3 a1) {\n  return texelFetch(a0, a1.xy, a1.z);\n}"));
}

// glslang builds sampler2D(t, s) before the coordinate; a coordinate that branches would leave
// the OpSampledImage in another block than its use (invalid SPIR-V). A helper evaluates the
// arguments first, in the caller, and builds the sampler in its one block.
TEST(GlslEmitterTextures, VulkanSamplesThroughAHelperWhereAnArgumentBranches) {
  const std::string text = fragment("Texture2D t; SamplerState s; Texture2D<float> r; float k;",
                                    "return t.Sample(s, k > 0 ? uv : uv.yx) + r.Sample(s, k > 1 && k < 2 ? uv : 0) + "
                                    "t.Sample(s, uv);",
                                    Flavour::Vk);
  EXPECT_THAT(text, HasSubstr("vec4 xs_Sample(texture2D a0, sampler a1, vec2 a2) {\n"
                              "  return texture(sampler2D(a0, a1), a2);\n}"));
  EXPECT_THAT(text, HasSubstr("float xs_Sample_2(texture2D a0, sampler a1, vec2 a2) {\n"
                              "  return texture(sampler2D(a0, a1), a2).x;\n}"));
  EXPECT_THAT(text, HasSubstr("xs_Sample(t, s, k > 0.0 ? uv : uv.yx)"));
  EXPECT_THAT(text, HasSubstr("+ texture(sampler2D(t, s), uv)"));
  EXPECT_THAT(fragment("Texture2D t; SamplerState s; float k;", "return t.Sample(s, k > 0 ? uv : uv.yx);"),
              HasSubstr("texture(t, k > 0.0 ? uv : uv.yx)"));  // gl combines nothing: no helper
}

TEST(GlslEmitterTextures, SimpleArgumentsStayInline) {
  const std::string text = fragment("sampler2D s; Texture2D t; float4 c; int3 p;",
                                    "return tex2Dlod(s, c) + tex2Dbias(s, c) + t.Load(p) + tex2Dgrad(s, uv, uv, uv);");
  EXPECT_THAT(text, HasSubstr("textureLod(s, c.xy, c.w) + texture(s, c.xy, c.w) + texelFetch(t, p.xy, p.z) + "
                              "textureGrad(s, uv, uv, uv)"));
}

TEST(GlslEmitterEntryPoints, VertexStageMain) {
  const EmittedProgram gl = emit_ok(kVertexAndFragment, Flavour::Gl);
  ASSERT_TRUE(gl.vertex);
  const std::string& text = gl.vertex->text;
  EXPECT_THAT(text, HasSubstr("#version 450 core\n"));
  EXPECT_THAT(text, HasSubstr("layout(location = 0) in vec4 xs_in_POSITION0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 3) in vec2 xs_in_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 0) out vec2 xs_v_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 1) flat out int xs_v_TEXCOORD1;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 10) centroid out vec3 xs_v_NORMAL0;"));
  EXPECT_THAT(text, HasSubstr("v2f vert(appdata v, uint vid) {"));
  EXPECT_THAT(text, HasSubstr("void main() {\n"
                              "  appdata xs_arg0;\n"
                              "  uint xs_arg1;\n"
                              "  xs_arg0.vertex = xs_in_POSITION0;\n"
                              "  xs_arg0.uv = xs_in_TEXCOORD0;\n"
                              "  xs_arg1 = uint(gl_VertexID);\n"
                              "  v2f xs_result = vert(xs_arg0, xs_arg1);\n"
                              "  gl_Position = xs_result.pos;\n"
                              "  xs_v_TEXCOORD0 = xs_result.uv;\n"
                              "  xs_v_TEXCOORD1 = xs_result.id;\n"
                              "  xs_v_NORMAL0 = xs_result.n;\n"
                              "}\n"));
  const EmittedProgram vk = emit_ok(kVertexAndFragment, Flavour::Vk);
  ASSERT_TRUE(vk.vertex);
  EXPECT_THAT(vk.vertex->text, HasSubstr("xs_arg1 = uint(gl_VertexIndex);"));
}

TEST(GlslEmitterEntryPoints, FragmentStageMain) {
  const EmittedProgram gl = emit_ok(kVertexAndFragment, Flavour::Gl);
  ASSERT_TRUE(gl.fragment);
  const std::string& text = gl.fragment->text;
  EXPECT_THAT(text, HasSubstr("layout(location = 0) in vec2 xs_v_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 1) flat in int xs_v_TEXCOORD1;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 10) centroid in vec3 xs_v_NORMAL0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 0) out vec4 xs_target0;"));
  EXPECT_THAT(text, HasSubstr("xs_arg0.pos = vec4(gl_FragCoord.xyz, 1.0 / gl_FragCoord.w);"));
  EXPECT_THAT(text, HasSubstr("vec4 xs_result = frag(xs_arg0);\n  xs_target0 = xs_result;\n"));
}

TEST(GlslEmitterEntryPoints, Dx9AndInstanceSystemValues) {
  // DEPTH is SV_Depth (Unity's HLSLSupport.cginc defines SV_Depth so), VPOS SV_Position, and
  // DX9's VFACE a float that is positive for a front face.
  const std::string source = R"(#pragma vertex vert
#pragma fragment frag
struct V { float4 pos : SV_Position; float id : TEXCOORD0; };
V vert(float3 p : POSITION, uint instance : SV_InstanceID) { V o; o.pos = float4(p, 1); o.id = instance; return o; }
float4 frag(float id : TEXCOORD0, float4 screen : VPOS, float face : VFACE, out float depth : DEPTH) : SV_Target {
  depth = 0.5; return float4(screen.xy, face, id);
}
)";
  const EmittedProgram gl = emit_ok(source, Flavour::Gl);
  EXPECT_THAT(gl.vertex->text, HasSubstr("xs_arg1 = uint(gl_InstanceID);"));
  EXPECT_THAT(emit_ok(source, Flavour::Vk).vertex->text, HasSubstr("xs_arg1 = uint(gl_InstanceIndex);"));
  EXPECT_THAT(gl.fragment->text, HasSubstr("xs_arg1 = vec4(gl_FragCoord.xyz, 1.0 / gl_FragCoord.w);"));
  EXPECT_THAT(gl.fragment->text, HasSubstr("xs_arg2 = (gl_FrontFacing ? 1.0 : -1.0);"));
  EXPECT_THAT(gl.fragment->text, HasSubstr("gl_FragDepth = xs_arg3;"));
}

TEST(GlslEmitterEntryPoints, OutputsDepthFaceAndSeveralTargets) {
  const std::string source = R"(#pragma fragment frag
struct Out { float4 a : SV_Target0; float4 b : COLOR1; float depth : SV_Depth; };
void frag(float2 uv : TEXCOORD0, bool face : SV_IsFrontFace, out Out o, out float4 extra : SV_Target2) {
  o.a = face ? 1 : 0; o.b = uv.xyxy; o.depth = 0.5; extra = 1;
}
)";
  const EmittedProgram program = emit_ok(source);
  ASSERT_TRUE(program.fragment);
  EXPECT_FALSE(program.vertex);
  const std::string& text = program.fragment->text;
  EXPECT_THAT(text, HasSubstr("layout(location = 0) in vec2 xs_v_TEXCOORD0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 0) out vec4 xs_target0;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 1) out vec4 xs_target1;"));
  EXPECT_THAT(text, HasSubstr("layout(location = 2) out vec4 xs_target2;"));
  EXPECT_THAT(text, HasSubstr("xs_arg1 = gl_FrontFacing;"));
  EXPECT_THAT(text, HasSubstr("void frag(vec2 uv, bool face, out Out o, out vec4 extra) {"));
  EXPECT_THAT(text, HasSubstr("frag(xs_arg0, xs_arg1, xs_arg2, xs_arg3);\n"
                              "  xs_target0 = xs_arg2.a;\n"
                              "  xs_target1 = xs_arg2.b;\n"
                              "  gl_FragDepth = xs_arg2.depth;\n"
                              "  xs_target2 = xs_arg3;\n"));
}

TEST(GlslEmitterEntryPoints, FragmentOnlyReadsUvAtLocationZero) {
  const std::string text = fragment("", "return float4(uv, 0, 1);");
  EXPECT_THAT(text, HasSubstr("layout(location = 0) in vec2 xs_v_TEXCOORD0;"));
}

TEST(GlslEmitterEntryPoints, TheAuthorsMainIsRenamed) {
  const std::string source =
      "#pragma fragment main\nfloat4 main(float2 uv : TEXCOORD0) : SV_Target { return uv.xyxy; }\n";
  const EmittedProgram program = emit_ok(source);
  ASSERT_TRUE(program.fragment);
  EXPECT_THAT(program.fragment->text, HasSubstr("vec4 main_(vec2 uv) {"));
  EXPECT_THAT(program.fragment->text, HasSubstr("vec4 xs_result = main_(xs_arg0);"));
}

TEST(GlslEmitterEntryPoints, UniformParametersAreAnError) {
  const std::string error = emit_error(
      "#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0, uniform float4 tint) : SV_Target { return tint; }\n");
  EXPECT_THAT(error, HasSubstr("test.hlsl:2:"));
  EXPECT_THAT(error, HasSubstr("uniform parameter 'tint'"));
}

TEST(GlslEmitterNames, ReservedNamesGetATrailingUnderscore) {
  EXPECT_EQ(renamed("input"), "input_");
  EXPECT_EQ(renamed("texture"), "texture_");
  EXPECT_EQ(renamed("gl_Thing"), "xs_gl_Thing_");
  EXPECT_EQ(renamed("a__b"), "a_0b");
  EXPECT_EQ(renamed("xs_mine"), "xs_mine_");
  EXPECT_FALSE(needs_renaming("_MainTex"));
  EXPECT_TRUE(needs_renaming("sample"));
  const std::string text = fragment("float4 input; struct filter { float smooth; };",
                                    "float output = input.x;\n"
                                    "filter f;\n"
                                    "f.smooth = output;\n"
                                    "float mix_ = 1;\n"
                                    "float mix = 2;\n"
                                    "float gl_Value = 3, a__b = 4, xs_value = 5;\n"
                                    "return f.smooth + mix + mix_ + gl_Value + a__b + xs_value;");
  EXPECT_THAT(text, HasSubstr("layout(offset = 0) vec4 input_;"));
  EXPECT_THAT(text, HasSubstr("struct filter_ {\n  float smooth_;\n};"));
  EXPECT_THAT(text, HasSubstr("float output_ = input_.x;"));
  EXPECT_THAT(text, HasSubstr("filter_ f;"));
  EXPECT_THAT(text, HasSubstr("f.smooth_ = output_;"));
  EXPECT_THAT(text, HasSubstr("float mix_ = 1.0;"));
  EXPECT_THAT(text, HasSubstr("float mix_1 = 2.0;"));  // mix_ is the author's own
  EXPECT_THAT(text, HasSubstr("float xs_gl_Value_ = 3.0;"));
  EXPECT_THAT(text, HasSubstr("float a_0b = 4.0;"));
  EXPECT_THAT(text, HasSubstr("float xs_value_ = 5.0;"));
}

TEST(GlslEmitterLines, LineDirectivesPointAtTheAuthorsFile) {
  const std::string source =
      "#pragma fragment frag\n"                             // 1
      "float helper(float x) {\n"                           // 2
      "  return x * 2;\n"                                   // 3
      "}\n"                                                 // 4
      "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"  // 5
      "  float a = helper(uv.x);\n"                         // 6
      "\n"                                                  // 7
      "  return a;\n"                                       // 8
      "}\n";
  auto module = hlsl::compile_text("shader.hlsl", source, {});
  ASSERT_TRUE(module->ok()) << diagnostics_of(*module);
  auto program = emit(*module, {Flavour::Gl});
  ASSERT_TRUE(program) << program.error().to_string();
  ASSERT_EQ(program->source_files.size(), 2u);
  EXPECT_EQ(program->source_files[0], "");
  EXPECT_EQ(program->source_files[1], "shader.hlsl");
  const std::string& text = program->fragment->text;
  EXPECT_THAT(text, HasSubstr("// file 1: shader.hlsl\n"));
  EXPECT_THAT(text, HasSubstr("#line 2 1\nfloat helper(float x) {\n  return x * 2.0;\n}\n"));
  EXPECT_THAT(text, HasSubstr("}\nvec4 frag(vec2 uv) {\n  float a = helper(uv.x);\n#line 8 1\n  return vec4(a);\n"));
  // main() is generated: `#line N 0` gives it its own line numbers in the emitted text.
  const std::vector<std::string> lines = lines_of(text);
  bool found = false;
  for (size_t i = 0; i + 1 < lines.size(); ++i) {
    if (lines[i].rfind("#line ", 0) == 0 && lines[i].size() > 2 && lines[i].substr(lines[i].size() - 2) == " 0") {
      found = true;
      EXPECT_EQ(lines[i], "#line " + std::to_string(i + 2) + " 0");
      EXPECT_EQ(lines[i + 1], "void main() {");
    }
  }
  EXPECT_TRUE(found);
}

TEST(GlslEmitterNames, VariablesNamedLikeFunctionsDoNotHideThem) {
  const std::string text =
      without_line_directives(fragment("float3 fresnel(float3 f0) { return f0 * 0.5; }\n"
                                       "float shade(float fresnel) { return fresnel * 2; }\n",
                                       "float3 fresnel = fresnel(uv.xyx);\n"
                                       "return float4(fresnel(fresnel), shade(fresnel.x));"));
  EXPECT_THAT(text, HasSubstr("float shade(float fresnel_v) {\n  return fresnel_v * 2.0;\n}"));
  EXPECT_THAT(text, HasSubstr("vec3 fresnel_v = fresnel(uv.xyx);"));
  EXPECT_THAT(text, HasSubstr("return vec4(fresnel(fresnel_v), shade(fresnel_v.x));"));
}

TEST(GlslEmitterLines, IncludedFilesHaveTheirOwnNumber) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "xshade_glsl_emitter_test";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "lighting.hlsl") << "float lambert(float3 n, float3 l) {\n  return saturate(dot(n, l));\n}\n";
    std::ofstream(dir / "main.hlsl") << "#pragma fragment frag\n#include \"lighting.hlsl\"\n"
                                        "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                                        "  return lambert(uv.xyx, 1);\n}\n";
  }
  auto module = hlsl::compile_file(dir / "main.hlsl", {});
  ASSERT_TRUE(module->ok()) << diagnostics_of(*module);
  auto program = emit(*module, {Flavour::Gl});
  ASSERT_TRUE(program) << program.error().to_string();
  ASSERT_EQ(program->source_files.size(), 3u);
  EXPECT_THAT(program->source_files[1], HasSubstr("main.hlsl"));
  EXPECT_THAT(program->source_files[2], HasSubstr("lighting.hlsl"));
  const std::string& text = program->fragment->text;
  EXPECT_THAT(text, HasSubstr("// file 2: " + program->source_files[2] + "\n"));
  EXPECT_THAT(text, HasSubstr("#line 1 2\nfloat lambert(vec3 n, vec3 l) {\n"));
  EXPECT_THAT(text, HasSubstr("#line 3 1\nvec4 frag(vec2 uv) {\n"));
  std::filesystem::remove_all(dir);
}

TEST(GlslEmitterDeterminism, TheSameInputGivesTheSameBytes) {
  for (const Flavour flavour : {Flavour::Gl, Flavour::Vk}) {
    const EmittedProgram a = emit_ok(kVertexAndFragment, flavour);
    const EmittedProgram b = emit_ok(kVertexAndFragment, flavour);
    ASSERT_TRUE(a.vertex && b.vertex && a.fragment && b.fragment);
    EXPECT_EQ(a.vertex->text, b.vertex->text);
    EXPECT_EQ(a.fragment->text, b.fragment->text);
    const std::string source = fragment_source("float4 a; int3 i; float3x3 m;",
                                               "return fmod(a, 2) + float4(i / 2 % 3, 1) + mul(m, a.xyz).xyzz + "
                                               "(isfinite(a) ? 1 : 0);");
    const EmittedProgram c = emit_ok(source, flavour);
    const EmittedProgram d = emit_ok(source, flavour);
    ASSERT_TRUE(c.fragment && d.fragment);
    EXPECT_EQ(c.fragment->text, d.fragment->text);
  }
}

TEST(GlslEmitterErrors, ErrorsReadLikeTheFrontEndsDiagnostics) {
  const std::string line = "float4 frag(float2 uv : TEXCOORD0, uniform float4 tint) : SV_Target { return tint; }";
  auto program = try_emit("#pragma fragment frag\n" + line + "\n");
  ASSERT_FALSE(program);
  // 'tint' starts at column 51: after "float4 frag(" (12), "float2 uv : TEXCOORD0, " (23) and
  // "uniform float4 " (15).
  EXPECT_EQ(program.error().to_string(),
            "test.hlsl:2:51: error: uniform parameter 'tint' of an entry point is not supported on this target; "
            "declare it as a global\n"
            "    " +
                line +
                "\n"
                "    " +
                std::string(50, ' ') + "^");
  EXPECT_EQ(program.error().where.to_string(), "test.hlsl:2:51");
}

TEST(GlslEmitterErrors, ModulesWithErrorsAreRefused) {
  auto module = hlsl::compile_text("bad.hlsl", "#pragma fragment frag\nfloat4 frag() : SV_Target { return x; }\n", {});
  ASSERT_FALSE(module->ok());
  auto program = emit(*module, {});
  ASSERT_FALSE(program);
  EXPECT_THAT(program.error().message, HasSubstr("errors"));
}

// A file of many shaders declares what one of its passes cannot use: that is no error until an
// entry point reaches it.
constexpr const char* kUnreachedResources = R"(
#pragma fragment frag
struct Particle { float3 position; };
struct Holder { StructuredBuffer<Particle> unused_field_type; };
StructuredBuffer<Particle> particles;
RWTexture2D<float4> output;
groupshared float shared_sum[64];
float3 simulate(uint i) {
  shared_sum[i % 64] = 1;
  output[uint2(i, 0)] = float4(particles[i].position, shared_sum[0]);
  return particles.Load(i).position;
}
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return float4(uv, 0, 1); }
)";

TEST(GlslEmitterReach, UnreachedCodeMayUseWhatTheTargetCannotExpress) {
  for (const Flavour flavour : {Flavour::Gl, Flavour::Vk}) {
    const std::string text = emit_ok(kUnreachedResources, flavour).fragment->text;
    EXPECT_THAT(text, Not(HasSubstr("simulate")));
    EXPECT_THAT(text, Not(HasSubstr("Particle")));
    EXPECT_THAT(text, Not(HasSubstr("shared_sum")));
  }
}

TEST(GlslEmitterReach, WhatTheTargetCannotExpressIsAnErrorWhereItIsReached) {
  const std::string reached =
      std::string(kUnreachedResources) +
      "float4 frag2(float4 p : SV_Position) : SV_Target { return float4(simulate(uint(p.x)), 1); }\n";
  std::string source = reached;
  source.replace(source.find("#pragma fragment frag\n"), 22, "#pragma fragment frag2\n");
  // A reached groupshared variable is named at its declaration; a resource at its first use.
  EXPECT_THAT(emit_error(source),
              HasSubstr("test.hlsl:7:19: error: groupshared variable 'shared_sum' is not supported"));
  std::string without_shared = source;
  without_shared.replace(without_shared.find("  shared_sum[i % 64] = 1;\n"), 26, "");
  without_shared.replace(without_shared.find(", shared_sum[0]"), 15, ", 0");
  EXPECT_THAT(
      emit_error(without_shared),
      HasSubstr("test.hlsl:9:3: error: 'RWTexture2D<float4>' is not supported on this target: shaders here read "
                "textures, constant buffers and read-only buffers (StructuredBuffer, ByteAddressBuffer, Buffer)"));
}

TEST(GlslEmitterConstantBuffers, AConstantBufferOfAStructIsABlockWithAnInstanceName) {
  const std::string globals =
      "struct Scene { float4x4 view; float3 light; float strength; };\n"
      "ConstantBuffer<Scene> scene : register(b3);";
  const std::string body = "return float4(scene.light * scene.strength, scene.view._m00);";
  for (const Flavour flavour : {Flavour::Gl, Flavour::Vk}) {
    const std::string text = fragment(globals, body, flavour);
    EXPECT_THAT(text,
                HasSubstr("binding = 3) uniform scene {\n  layout(offset = 0, row_major) mat4 view;\n"
                          "  layout(offset = 64) vec3 light;\n  layout(offset = 76) float strength;\n} xs_cb_scene;"));
    EXPECT_THAT(text, HasSubstr("xs_cb_scene.light * xs_cb_scene.strength"));
    EXPECT_THAT(text, Not(HasSubstr("struct Scene")));  // read through the block only
  }
}

}  // namespace
}  // namespace xshade::glsl::emitter_test
