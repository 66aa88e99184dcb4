// The GLSL emitter, one test per mapping rule (docs/hlsl_like.md) in both flavours.
// Why this file is long: it is one short case per rule of the mapping, read as the list of them.
#include "glsl/glsl_emitter.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "glsl/glsl_names.h"

namespace xshade::glsl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string diagnostics_of(const hlsl::Module& module) {
  std::string text;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) text += d.to_string() + "\n";
  return text;
}

Result<EmittedProgram> try_emit(const std::string& source, Flavour flavour = Flavour::Gl) {
  auto module = hlsl::compile_text("test.hlsl", source, {});
  if (!module->ok()) {
    ADD_FAILURE() << "the front end rejected the source:\n" << diagnostics_of(*module);
    return fail("front end");
  }
  return emit(*module, {flavour});
}

EmittedProgram emit_ok(const std::string& source, Flavour flavour = Flavour::Gl) {
  auto program = try_emit(source, flavour);
  if (!program) {
    ADD_FAILURE() << program.error().to_string();
    return {};
  }
  return *program;
}

// A fragment-only shader: `globals`, then frag() with `body` as its statements.
std::string fragment_source(const std::string& globals, const std::string& body) {
  return "#pragma fragment frag\n" + globals + "\nfloat4 frag(float2 uv : TEXCOORD0) : SV_Target {\n" + body + "\n}\n";
}

std::string fragment(const std::string& globals, const std::string& body, Flavour flavour = Flavour::Gl) {
  EmittedProgram program = emit_ok(fragment_source(globals, body), flavour);
  return program.fragment ? program.fragment->text : "";
}

std::string emit_error(const std::string& source, Flavour flavour = Flavour::Gl) {
  auto program = try_emit(source, flavour);
  if (program) {
    ADD_FAILURE() << "expected an error";
    return "";
  }
  return program.error().to_string();
}

std::string without_line_directives(const std::string& text) {
  std::string result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("#line ", 0) != 0) result += line + "\n";
  return result;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

const char* const kVertexAndFragment = R"(#pragma vertex vert
#pragma fragment frag
struct appdata {
  float4 vertex : POSITION;
  float2 uv : TEXCOORD0;
};
struct v2f {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
  nointerpolation int id : TEXCOORD1;
  centroid float3 n : NORMAL;
};
float4x4 _MVP;
v2f vert(appdata v, uint vid : SV_VertexID) {
  v2f o;
  o.pos = mul(_MVP, v.vertex);
  o.uv = v.uv;
  o.id = int(vid);
  o.n = v.vertex.xyz;
  return o;
}
float4 frag(v2f i) : SV_Target {
  return float4(i.uv, i.n.x, i.pos.w);
}
)";

// ---------------------------------------------------------------------------------------------
// Matrices

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

TEST(GlslEmitterMatrices, MulOperandOrderFollowsTheTranspose) {
  const std::string text = fragment("float4x4 M; float4x4 N; float4 v; float s;",
                                    "float4 a = mul(M, v);\n"
                                    "float4 b = mul(v, M);\n"
                                    "float4x4 c = mul(M, N);\n"
                                    "float4 d = mul(s, v);\n"
                                    "float e = mul(v, v);\n"
                                    "return a + b + c[0] + d + e;");
  EXPECT_THAT(text, HasSubstr("vec4 a = v * M;"));
  EXPECT_THAT(text, HasSubstr("vec4 b = M * v;"));
  EXPECT_THAT(text, HasSubstr("mat4 c = N * M;"));
  EXPECT_THAT(text, HasSubstr("vec4 d = s * v;"));
  EXPECT_THAT(text, HasSubstr("float e = dot(v, v);"));
}

TEST(GlslEmitterMatrices, TypesRowsElementsAndConstructors) {
  const std::string text = fragment("float3x4 A; float4x4 M; float2x2 P;",
                                    "float4 row = A[1];\n"
                                    "float e = A[1][2];\n"
                                    "float f = A._m12;\n"
                                    "float g = A._11;\n"
                                    "float2 h = A._m00_m21;\n"
                                    "float2x2 k = float2x2(1, 2, 3, 4);\n"
                                    "float2x3 l = float2x3(row.xyz, row.wzy);\n"
                                    "float3x3 t = (float3x3)M;\n"
                                    "float4x3 u = transpose(A);\n"
                                    "float2x2 w = P * k;\n"
                                    "float d = determinant(M);\n"
                                    "return row + e + f + g + h.x + k[0].x + l[0].x + t[0].x + u[0].x + w[1].y + d;");
  EXPECT_THAT(text, HasSubstr("layout(offset = 0, row_major) mat3x4 A;"));
  EXPECT_THAT(text, HasSubstr("vec4 row = A[1];"));
  EXPECT_THAT(text, HasSubstr("float e = A[1][2];"));
  EXPECT_THAT(text, HasSubstr("float f = A[1][2];"));
  EXPECT_THAT(text, HasSubstr("float g = A[0][0];"));
  EXPECT_THAT(text, HasSubstr("vec2 h = vec2(A[0][0], A[2][1]);"));
  EXPECT_THAT(text, HasSubstr("mat2 k = mat2(1.0, 2.0, 3.0, 4.0);"));  // same argument order
  EXPECT_THAT(text, HasSubstr("mat2x3 l = mat2x3(row.xyz, row.wzy);"));
  EXPECT_THAT(text, HasSubstr("mat3 t = mat3(M);"));
  EXPECT_THAT(text, HasSubstr("mat4x3 u = transpose(A);"));
  EXPECT_THAT(text, HasSubstr("mat2 w = matrixCompMult(P, k);"));  // HLSL's * is component-wise
  EXPECT_THAT(text, HasSubstr("float d = determinant(M);"));
}

TEST(GlslEmitterMatrices, ScalarsSplatOverEveryComponent) {
  const std::string text = fragment("float4x4 M; float s;",
                                    "float2x2 a = 3;\n"
                                    "float4x4 b = M * 2;\n"
                                    "b *= s;\n"
                                    "b *= M;\n"
                                    "return b[0] + a[0].x;");
  EXPECT_THAT(text, HasSubstr("mat2 a = mat2(vec2(3.0), vec2(3.0));"));  // not mat2(3.0), a diagonal
  EXPECT_THAT(text, HasSubstr("mat4 b = M * 2.0;"));
  EXPECT_THAT(text, HasSubstr("b *= s;"));
  EXPECT_THAT(text, HasSubstr("b = matrixCompMult(b, M);"));
}

// ---------------------------------------------------------------------------------------------
// Constant buffers

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

// ---------------------------------------------------------------------------------------------
// Operators

TEST(GlslEmitterOperators, FloatRemainderTruncatesThroughAHelper) {
  const std::string text = fragment("float4 a; float4 b;",
                                    "float4 r = a % b;\n"
                                    "float s = fmod(a.x, b.x);\n"
                                    "float4 t = fmod(a, b);\n"
                                    "r %= 2;\n"
                                    "return r + s + t;");
  EXPECT_THAT(text, HasSubstr("vec4 r = xs_fmod(a, b);"));
  EXPECT_THAT(text, HasSubstr("float s = xs_fmod(a.x, b.x);"));
  EXPECT_THAT(text, HasSubstr("vec4 t = xs_fmod(a, b);"));
  EXPECT_THAT(text, HasSubstr("r = xs_fmod(r, vec4(2.0));"));
  EXPECT_THAT(text, HasSubstr("vec4 xs_fmod(vec4 a, vec4 b) {\n  return a - b * trunc(a / b);\n}"));
  EXPECT_THAT(text, HasSubstr("float xs_fmod(float a, float b) {"));
  // Defined once per type, before the first function.
  EXPECT_EQ(text.find("vec4 xs_fmod(vec4"), text.rfind("vec4 xs_fmod(vec4"));
  EXPECT_LT(text.find("vec4 xs_fmod(vec4"), text.find("vec4 frag("));
}

TEST(GlslEmitterOperators, SignedIntegerDivisionTruncatesThroughHelpers) {
  const std::string text = fragment("int i; int j; int3 v; uint u;",
                                    "int a = i / j;\n"
                                    "int b = i % j;\n"
                                    "int3 c = v / 2;\n"
                                    "uint d = u / 3u;\n"
                                    "a /= 2;\n"
                                    "b %= j;\n"
                                    "return float4(a, b, c.x, d);");
  EXPECT_THAT(text, HasSubstr("int a = xs_idiv(i, j);"));
  EXPECT_THAT(text, HasSubstr("int b = xs_imod(i, j);"));
  EXPECT_THAT(text, HasSubstr("ivec3 c = xs_idiv(v, ivec3(2));"));
  EXPECT_THAT(text, HasSubstr("uint d = u / 3u;"));  // unsigned: GLSL's own
  EXPECT_THAT(text, HasSubstr("a = xs_idiv(a, 2);"));
  EXPECT_THAT(text, HasSubstr("b = xs_imod(b, j);"));
  EXPECT_THAT(text, HasSubstr("int xs_idiv(int a, int b) {"));
  EXPECT_THAT(text, HasSubstr("ivec3 xs_idiv(ivec3 a, ivec3 b) {"));
  EXPECT_THAT(text, HasSubstr("int xs_imod(int a, int b) {"));
  EXPECT_THAT(text, Not(HasSubstr("xs_imod(ivec3")));  // only what is used
}

TEST(GlslEmitterOperators, CompoundAssignmentThroughAnotherType) {
  const std::string text = fragment("int i; float f; float3 v;",
                                    "int k = i;\n"
                                    "k *= 0.5;\n"
                                    "float3 w = v;\n"
                                    "w *= f;\n"
                                    "w += 1;\n"
                                    "return float4(w, k);");
  EXPECT_THAT(text, HasSubstr("k = int(float(k) * 0.5);"));
  EXPECT_THAT(text, HasSubstr("w *= f;"));
  EXPECT_THAT(text, HasSubstr("w += 1.0;"));
}

TEST(GlslEmitterOperators, CompoundAssignmentToATargetWithSideEffectsIsAnError) {
  const std::string error = emit_error(fragment_source("int4 a;", "int4 b = a; int i = 0;\nb[i++] %= 3;\nreturn b;"));
  EXPECT_THAT(error, HasSubstr("test.hlsl:5:"));
  EXPECT_THAT(error,
              HasSubstr("compound assignment '%=' to an expression with side effects is not supported on this target"));
}

TEST(GlslEmitterOperators, VectorComparisonsAndLogic) {
  const std::string text = fragment("float3 a; float3 b; float s; bool3 m;",
                                    "bool3 lt = a < b;\n"
                                    "bool3 ge = a >= b;\n"
                                    "bool3 eq = a == b;\n"
                                    "bool3 ne = a != b;\n"
                                    "bool c = s < 1;\n"
                                    "bool3 both = lt && m;\n"
                                    "bool3 either = lt || m;\n"
                                    "bool3 none = !m;\n"
                                    "bool d = c && s > 0 || !c;\n"
                                    "return float4(both || either || none || eq || ne || ge, d);");
  EXPECT_THAT(text, HasSubstr("bvec3 lt = lessThan(a, b);"));
  EXPECT_THAT(text, HasSubstr("bvec3 ge = greaterThanEqual(a, b);"));
  EXPECT_THAT(text, HasSubstr("bvec3 eq = equal(a, b);"));
  EXPECT_THAT(text, HasSubstr("bvec3 ne = notEqual(a, b);"));
  EXPECT_THAT(text, HasSubstr("bool c = s < 1.0;"));
  EXPECT_THAT(text, HasSubstr("bvec3 both = bvec3(uvec3(lt) & uvec3(m));"));
  EXPECT_THAT(text, HasSubstr("bvec3 either = bvec3(uvec3(lt) | uvec3(m));"));
  EXPECT_THAT(text, HasSubstr("bvec3 none = not(m);"));
  EXPECT_THAT(text, HasSubstr("bool d = c && s > 0.0 || !c;"));
}

TEST(GlslEmitterOperators, ConditionalWithAVectorConditionIsMix) {
  const std::string text = fragment("float3 a; float3 b; float s;",
                                    "float3 x = a > b ? a : b;\n"
                                    "float3 y = s > 0 ? a : b;\n"
                                    "int3 z = a > 0 ? int3(1, 2, 3) : 0;\n"
                                    "return float4(x + y + z, 1);");
  EXPECT_THAT(text, HasSubstr("vec3 x = mix(b, a, greaterThan(a, b));"));
  EXPECT_THAT(text, HasSubstr("vec3 y = s > 0.0 ? a : b;"));
  EXPECT_THAT(text, HasSubstr("ivec3 z = mix(ivec3(0), ivec3(1, 2, 3), greaterThan(a, vec3(0.0)));"));
}

TEST(GlslEmitterOperators, PrecedenceIsKept) {
  const std::string text = fragment("float a; float b; float c; int i;",
                                    "float x = (a + b) * c;\n"
                                    "float y = a - (b - c);\n"
                                    "float z = -(-a);\n"
                                    "int k = (i << 2) + 1;\n"
                                    "return float4(x, y, z, k);");
  EXPECT_THAT(text, HasSubstr("float x = (a + b) * c;"));
  EXPECT_THAT(text, HasSubstr("float y = a - (b - c);"));
  EXPECT_THAT(text, HasSubstr("float z = -(-a);"));
  EXPECT_THAT(text, HasSubstr("int k = (i << 2) + 1;"));
}

// ---------------------------------------------------------------------------------------------
// Swizzles, literals, conversions

TEST(GlslEmitterExpressions, Swizzles) {
  const std::string text = fragment("float4 c; float f;",
                                    "float3 a = c.rgb;\n"
                                    "float4 b = c.bgra;\n"
                                    "float3 s = f.xxx;\n"
                                    "float t = f.x;\n"
                                    "float4 w = c;\n"
                                    "w.ga = 1;\n"
                                    "return float4(a, t) + b + s.xyzz + w;");
  EXPECT_THAT(text, HasSubstr("vec3 a = c.xyz;"));
  EXPECT_THAT(text, HasSubstr("vec4 b = c.zyxw;"));
  EXPECT_THAT(text, HasSubstr("vec3 s = vec3(f);"));
  EXPECT_THAT(text, HasSubstr("float t = f;"));
  EXPECT_THAT(text, HasSubstr("w.yw = vec2(1.0);"));
}

TEST(GlslEmitterExpressions, LiteralsAndConversions) {
  const std::string text = fragment("float4 v; int i; uint u; bool b;",
                                    "float a = 1;\n"
                                    "float c = 2.5f;\n"
                                    "float d = 1e-7;\n"
                                    "half h = 0.5h;\n"
                                    "uint e = 7u + u;\n"
                                    "uint big = 0xFFFFFFFF;\n"
                                    "float3 f = v;\n"
                                    "float g = v;\n"
                                    "int3 k = v.xyz;\n"
                                    "float3 l = i;\n"
                                    "bool2 m = v.xy;\n"
                                    "float n = -1;\n"
                                    "float o = b;\n"
                                    "float3 p = (float3)v;\n"
                                    "int q = (int)v.x;\n"
                                    "return float4(f + l, a + c + d + h + e + g + k.x + m.x + n + o + p.x + q + big);");
  EXPECT_THAT(text, HasSubstr("float a = 1.0;"));
  EXPECT_THAT(text, HasSubstr("float c = 2.5;"));
  EXPECT_THAT(text, HasSubstr("float d = 1e-7;"));
  EXPECT_THAT(text, HasSubstr("float h = 0.5;"));
  EXPECT_THAT(text, HasSubstr("uint e = 7u + u;"));
  EXPECT_THAT(text, HasSubstr("uint big = 4294967295u;"));
  EXPECT_THAT(text, HasSubstr("vec3 f = v.xyz;"));
  EXPECT_THAT(text, HasSubstr("float g = v.x;"));
  EXPECT_THAT(text, HasSubstr("ivec3 k = ivec3(v.xyz);"));
  EXPECT_THAT(text, HasSubstr("vec3 l = vec3(i);"));
  EXPECT_THAT(text, HasSubstr("bvec2 m = bvec2(v.xy);"));
  EXPECT_THAT(text, HasSubstr("float n = -1.0;"));
  EXPECT_THAT(text, HasSubstr("float o = float(b);"));
  EXPECT_THAT(text, HasSubstr("vec3 p = v.xyz;"));
  EXPECT_THAT(text, HasSubstr("int q = int(v.x);"));
}

TEST(GlslEmitterExpressions, StructsArraysAndInitializerLists) {
  const std::string text = fragment(
      "struct S { float4 pos; float2 uv[2]; int id; };\n"
      "static const float2 kKernel[3] = { float2(0, 0), float2(1, 0), float2(0, 1) };\n"
      "static const float kWeights[] = { 0.25, 0.5, 0.25 };\n",
      "S s = (S)0;\n"
      "S t = { 1, 2, 3, 4, 5, 6, 7, 8, 9 };\n"
      "float4 w = { uv, 0, 1 };\n"
      "float a[2] = { 1, 2 };\n"
      "return s.pos + t.pos + w + kKernel[1].x * kWeights[2] + a[1];");
  EXPECT_THAT(text, HasSubstr("const vec2 kKernel[3] = vec2[3](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0));"));
  EXPECT_THAT(text, HasSubstr("const float kWeights[3] = float[3](0.25, 0.5, 0.25);"));
  EXPECT_THAT(text, HasSubstr("S s = S(vec4(0.0), vec2[2](vec2(0.0), vec2(0.0)), 0);"));
  EXPECT_THAT(text, HasSubstr("S t = S(vec4(1.0, 2.0, 3.0, 4.0), vec2[2](vec2(5.0, 6.0), vec2(7.0, 8.0)), 9);"));
  EXPECT_THAT(text, HasSubstr("vec4 w = vec4(uv, 0.0, 1.0);"));
  EXPECT_THAT(text, HasSubstr("float a[2] = float[2](1.0, 2.0);"));
}

TEST(GlslEmitterExpressions, StaticGlobals) {
  const std::string text = fragment(
      "float4 _Color;\n"
      "static float4 s_tint = _Color * 2;\n"
      "static float s_zero;\n"
      "static int s_count = 3;\n"
      "static const float3 kLum = float3(0.2, 0.7, 0.1);\n"
      "static const float kUnused = 1;\n",
      "s_zero += 1;\n"
      "const float local = 2;\n"
      "const float runtime = s_zero;\n"
      "return s_tint * dot(kLum, 1) + s_zero + s_count + local + runtime;");
  EXPECT_THAT(text, HasSubstr("vec4 s_tint = vec4(0.0);"));  // until main() assigns it
  EXPECT_THAT(text, HasSubstr("float s_zero = 0.0;"));       // HLSL zero-initializes statics
  EXPECT_THAT(text, HasSubstr("int s_count = 3;"));
  EXPECT_THAT(text, HasSubstr("const vec3 kLum = vec3(0.2, 0.7, 0.1);"));
  EXPECT_THAT(text, Not(HasSubstr("kUnused")));
  EXPECT_THAT(text, HasSubstr("const float local = 2.0;"));
  EXPECT_THAT(text, HasSubstr("  float runtime = s_zero;"));  // not a GLSL constant expression
  EXPECT_THAT(text, HasSubstr("void main() {\n  s_tint = _Color * 2.0;\n"));
}

// ---------------------------------------------------------------------------------------------
// Intrinsics

TEST(GlslEmitterIntrinsics, TheTableMapsToGlslWithHlslSemantics) {
  const std::string text = fragment("float3 a; float3 b; float t; int3 i; uint u;",
                                    "float3 r = saturate(a) + lerp(a, b, t) + rsqrt(a) + frac(a) + round(a);\n"
                                    "r += log10(a) + rcp(a) + mad(a, b, a) + atan2(a, b) + ddx(a) + ddy(a);\n"
                                    "int3 s = sign(a);\n"
                                    "bool3 f = isfinite(a);\n"
                                    "float3 sn, cs;\n"
                                    "sincos(t, sn.x, cs.x);\n"
                                    "clip(a - 0.5);\n"
                                    "clip(t);\n"
                                    "uint c = countbits(u);\n"
                                    "float h = f16tof32(u);\n"
                                    "bool any3 = any(a);\n"
                                    "bool all3 = all(i);\n"
                                    "return float4(r + s + f + sn + cs, c + h + any3 + all3);");
  EXPECT_THAT(text, HasSubstr("clamp(a, 0.0, 1.0) + mix(a, b, vec3(t)) + inversesqrt(a) + fract(a) + roundEven(a)"));
  EXPECT_THAT(text,
              HasSubstr("(log2(a) * 0.30102999566398120) + (1.0 / a) + (a * b + a) + atan(a, b) + dFdx(a) + dFdy(a)"));
  EXPECT_THAT(text, HasSubstr("ivec3 s = ivec3(sign(a));"));
  EXPECT_THAT(text, HasSubstr("bvec3 f = xs_isfinite(a);"));
  EXPECT_THAT(text, HasSubstr("bvec3 xs_isfinite(vec3 a) {"));
  EXPECT_THAT(text, HasSubstr("(sn.x = sin(t), cs.x = cos(t));"));
  EXPECT_THAT(text, HasSubstr("if (any(lessThan(a - 0.5, vec3(0.0)))) discard;"));
  EXPECT_THAT(text, HasSubstr("if (t < 0.0) discard;"));
  EXPECT_THAT(text, HasSubstr("uint c = uint(bitCount(u));"));
  EXPECT_THAT(text, HasSubstr("float h = unpackHalf2x16(u).x;"));
  EXPECT_THAT(text, HasSubstr("bool any3 = any(bvec3(a));"));
  EXPECT_THAT(text, HasSubstr("bool all3 = all(bvec3(i));"));
}

TEST(GlslEmitterIntrinsics, ComponentWiseIntrinsicsOfMatricesGoColumnByColumn) {
  // GLSL's abs, pow, mix ... take no matrices; HLSL's are component-wise on them. float2x3 is a
  // GLSL mat2x3 (two columns of vec3), so each helper applies the vector form to a0[0] and a0[1].
  const std::string text = fragment("float2x3 m; float2x3 n;",
                                    "float2x3 a = abs(m) + pow(m, n) + fmod(m, n);\n"
                                    "float2x3 whole;\n"
                                    "float2x3 f = modf(m, whole);\n"
                                    "float2x3 s, c;\n"
                                    "sincos(m, s, c);\n"
                                    "clip(m);\n"
                                    "bool b = all(m) || any(n);\n"
                                    "return float4(a[0] + f[1] + s[0] + c[1] + whole[0], b);");
  EXPECT_THAT(text, HasSubstr("mat2x3 xs_abs(mat2x3 a0) {\n  return mat2x3(abs(a0[0]), abs(a0[1]));\n}"));
  EXPECT_THAT(text, HasSubstr("mat2x3 xs_pow(mat2x3 a0, mat2x3 a1) {\n"
                              "  return mat2x3(pow(a0[0], a1[0]), pow(a0[1], a1[1]));\n}"));
  // fmod's own helper, for the column type, comes first.
  EXPECT_THAT(text, HasSubstr("vec3 xs_fmod(vec3 a, vec3 b) {"));
  EXPECT_THAT(text, HasSubstr("mat2x3 xs_fmod(mat2x3 a0, mat2x3 a1) {\n"
                              "  return mat2x3(xs_fmod(a0[0], a1[0]), xs_fmod(a0[1], a1[1]));\n}"));
  EXPECT_THAT(text, HasSubstr("mat2x3 xs_modf(mat2x3 a0, out mat2x3 a1) {\n"
                              "  return mat2x3(modf(a0[0], a1[0]), modf(a0[1], a1[1]));\n}"));
  EXPECT_THAT(text, HasSubstr("void xs_sincos(mat2x3 a0, out mat2x3 a1, out mat2x3 a2) {\n"
                              "  a1[0] = sin(a0[0]);\n  a2[0] = cos(a0[0]);\n"
                              "  a1[1] = sin(a0[1]);\n  a2[1] = cos(a0[1]);\n}"));
  EXPECT_THAT(text, HasSubstr("void xs_clip(mat2x3 a0) {\n"
                              "  if (any(lessThan(a0[0], vec3(0.0))) || any(lessThan(a0[1], vec3(0.0)))) discard;\n}"));
  EXPECT_THAT(text, HasSubstr("bool xs_all(mat2x3 a0) {\n  return all(bvec3(a0[0])) && all(bvec3(a0[1]));\n}"));
  EXPECT_THAT(text, HasSubstr("bool xs_any(mat2x3 a0) {\n  return any(bvec3(a0[0])) || any(bvec3(a0[1]));\n}"));
  EXPECT_THAT(text, HasSubstr("mat2x3 a = xs_abs(m) + xs_pow(m, n) + xs_fmod(m, n);"));
  EXPECT_THAT(text, HasSubstr("mat2x3 f = xs_modf(m, whole);"));
  EXPECT_THAT(text, HasSubstr("xs_sincos(m, s, c);"));
  EXPECT_THAT(text, HasSubstr("xs_clip(m);"));
  EXPECT_THAT(text, HasSubstr("bool b = xs_all(m) || xs_any(n);"));
}

TEST(GlslEmitterIntrinsics, EveryComponentWiseIntrinsicTakesAFloatMatrix) {
  // Whatever sema lets through with a float matrix the emitter must write; the only refusals
  // are results that are matrices of int or bool, which no GLSL type holds (§3 of the docs).
  for (const char* call :
       {"abs(m)",         "acos(m)",     "asin(m)",         "atan(m)",      "atan2(m, m)", "ceil(m)",
        "clamp(m, 0, 1)", "cos(m)",      "cosh(m)",         "ddx(m)",       "ddy(m)",      "degrees(m)",
        "exp(m)",         "exp2(m)",     "floor(m)",        "fma(m, m, m)", "fmod(m, m)",  "frac(m)",
        "fwidth(m)",      "ldexp(m, m)", "lerp(m, m, 0.5)", "log(m)",       "log10(m)",    "log2(m)",
        "mad(m, m, m)",   "max(m, m)",   "min(m, m)",       "pow(m, m)",    "radians(m)",  "rcp(m)",
        "round(m)",       "rsqrt(m)",    "saturate(m)",     "sin(m)",       "sinh(m)",     "smoothstep(m, m, m)",
        "sqrt(m)",        "step(m, m)",  "tan(m)",          "tanh(m)",      "trunc(m)",    "asfloat(m)"}) {
    SCOPED_TRACE(call);
    const std::string text = fragment("float3x3 m;", std::string("float3x3 r = ") + call + ";\nreturn r[0].xyzx;");
    EXPECT_THAT(text, HasSubstr("mat3 r = xs_"));
  }
  const std::string error = emit_error(fragment_source("float2x2 m;", "return sign(m)[0].xyxy;"));
  EXPECT_THAT(error, HasSubstr("matrices of int ('int2x2') are not supported on this target"));
}

TEST(GlslEmitterIntrinsics, BitCasts) {
  const std::string text = fragment("float3 f; int3 i; uint3 u;",
                                    "uint3 a = asuint(f);\n"
                                    "int3 b = asint(f);\n"
                                    "float3 c = asfloat(u) + asfloat(i) + asfloat(f);\n"
                                    "int3 d = asint(u);\n"
                                    "uint3 e = asuint(i);\n"
                                    "return float4(a + b + c + d + e, 1);");
  EXPECT_THAT(text, HasSubstr("uvec3 a = floatBitsToUint(f);"));
  EXPECT_THAT(text, HasSubstr("ivec3 b = floatBitsToInt(f);"));
  EXPECT_THAT(text, HasSubstr("vec3 c = uintBitsToFloat(u) + intBitsToFloat(i) + f;"));
  EXPECT_THAT(text, HasSubstr("ivec3 d = ivec3(u);"));
  EXPECT_THAT(text, HasSubstr("uvec3 e = uvec3(i);"));
}

// ---------------------------------------------------------------------------------------------
// Textures

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

// ---------------------------------------------------------------------------------------------
// Entry points and the stage interface

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

// ---------------------------------------------------------------------------------------------
// Functions

TEST(GlslEmitterFunctions, OnlyReachableFunctionsInDependencyOrder) {
  const std::string text = fragment(
      "float unused(float x) { return x; }\n"
      "float leaf(float x) { return x * 2; }\n"
      "float middle(float x) { return leaf(x) + 1; }\n"
      "void twice(inout float x, out float y) { x *= 2; y = x; }\n",
      "float a = middle(uv.x), b;\ntwice(a, b);\nreturn a + b;");
  EXPECT_THAT(text, Not(HasSubstr("unused")));
  EXPECT_LT(text.find("float leaf(float x)"), text.find("float middle(float x)"));
  EXPECT_LT(text.find("float middle(float x)"), text.find("vec4 frag("));
  EXPECT_THAT(text, HasSubstr("void twice(inout float x, out float y) {"));
  EXPECT_THAT(text, HasSubstr("twice(a, b);"));
}

TEST(GlslEmitterFunctions, OverloadsThatCollideInGlslAreMangled) {
  const std::string text = fragment(
      "float f(float x) { return x; }\n"
      "half f(half x) { return x * 2; }\n"
      "float g(float x) { return x; }\n"
      "float g(float2 x) { return x.x; }\n",
      "half h = 1;\nreturn f(uv.x) + f(h) + g(uv) + g(uv.y);");
  EXPECT_THAT(text, HasSubstr("float f_float(float x) {"));
  EXPECT_THAT(text, HasSubstr("float f_half(float x) {"));
  EXPECT_THAT(text, HasSubstr("float g(float x) {"));
  EXPECT_THAT(text, HasSubstr("float g(vec2 x) {"));
  EXPECT_THAT(text, HasSubstr("return vec4(f_float(uv.x) + f_half(h) + g(uv) + g(uv.y));"));
}

TEST(GlslEmitterFunctions, DefaultArgumentsAreWrittenOut) {
  const std::string text =
      fragment("float scale(float x, float k = 2) { return x * k; }\n", "return scale(uv.x) + scale(uv.y, 3);");
  EXPECT_THAT(text, HasSubstr("return vec4(scale(uv.x, 2.0) + scale(uv.y, 3.0));"));
}

TEST(GlslEmitterFunctions, OutArgumentsNeedingAConversionAreAnError) {
  const std::string error =
      emit_error(fragment_source("void get(out float x) { x = 1; }\n", "int i;\nget(i);\nreturn i;"));
  EXPECT_THAT(error, HasSubstr("test.hlsl:6:"));  // the function's own line comes first
  EXPECT_THAT(error, HasSubstr("out parameter"));
}

TEST(GlslEmitterFunctions, StatementsAndLoops) {
  const std::string text = without_line_directives(fragment("",
                                                            "float s = 0;\n"
                                                            "[unroll] for (int i = 0, j = 4; i < j; ++i) { s += i; }\n"
                                                            "int k = 0;\n"
                                                            "while (k < 3) { k++; if (k == 2) continue; }\n"
                                                            "do { s *= 0.5; } while (s > 1);\n"
                                                            "if (s > 0) s = 1; else if (s < 0) s = -1; else discard;\n"
                                                            "return s;"));
  EXPECT_THAT(text, HasSubstr("/* [unroll] */ for (int i = 0, j = 4; i < j; ++i) {\n    s += float(i);\n  }"));
  EXPECT_THAT(text, HasSubstr("while (k < 3) {\n    k++;\n    if (k == 2) {\n      continue;\n    }\n  }"));
  EXPECT_THAT(text, HasSubstr("do {\n    s *= 0.5;\n  } while (s > 1.0);"));
  EXPECT_THAT(text, HasSubstr("if (s > 0.0) {\n    s = 1.0;\n  } else if (s < 0.0) {\n    s = -1.0;\n  } else {\n"
                              "    discard;\n  }"));
}

// ---------------------------------------------------------------------------------------------
// Names, #line, determinism

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

// ---------------------------------------------------------------------------------------------
// What the entry points reach

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

TEST(GlslEmitterStatements, SwitchKeepsItsLabelsAndFallThrough) {
  std::string text = fragment("int _Mode; uint _Index;",
                              "float4 c = 0;\n"
                              "switch (_Mode) { case 0: case 1: c.r = 1; break; case -2: c.g = 1; default: c.b = 1; }\n"
                              "switch (_Index) { case 3: c.a = 1; }\n"
                              "return c;");
  for (size_t at = text.find("#line"); at != std::string::npos; at = text.find("#line"))
    text.erase(at, text.find('\n', at) + 1 - at);
  EXPECT_THAT(text, HasSubstr("switch (_Mode) {\n  case 0:\n  case 1:\n    c.x = 1.0;\n    break;\n  case -2:\n"));
  EXPECT_THAT(text, HasSubstr("  default:\n    c.z = 1.0;\n  }\n"));
  // A uint condition takes uint labels; GLSL converts neither.
  EXPECT_THAT(text, HasSubstr("switch (_Index) {\n  case 3u:\n    c.w = 1.0;\n  }\n"));
}

TEST(GlslEmitterStatements, ALoopWhoseVariableIsATexelOffsetIsUnrolled) {
  // A blur's taps: fxc unrolls the loop so that each offset is a constant, as GLSL needs.
  const std::string globals = "Texture2D _MainTex; SamplerState s; static const int kBegin = -1;";
  std::string text = fragment(globals,
                              "float4 c = 0;\n"
                              "[unroll] for (int x = kBegin; x <= 1; ++x) c += _MainTex.Sample(s, uv, int2(x, 0));\n"
                              "for (int i = 0; i < 2; i++) { c *= 0.5; }\n"
                              "return c;");
  for (size_t at = text.find("#line"); at != std::string::npos; at = text.find("#line"))
    text.erase(at, text.find('\n', at) + 1 - at);
  EXPECT_THAT(text, HasSubstr("/* [unroll] */ {  // unrolled: x = -1\n    const int x = -1;\n"
                              "    c += textureOffset(_MainTex, uv, ivec2(x, 0));\n  }\n"));
  EXPECT_THAT(text, HasSubstr("const int x = 1;\n"));
  EXPECT_THAT(text, Not(HasSubstr("const int x = 2;")));
  // A loop that needs no constant stays a loop.
  EXPECT_THAT(text, HasSubstr("for (int i = 0; i < 2; i++) {"));
  // A loop that breaks cannot be unrolled; its offset is then not constant.
  EXPECT_THAT(
      emit_error(fragment_source(
          globals,
          "float4 c = 0;\n"
          "for (int j = 0; j < 4; j++) { if (c.x > 1) break; c += _MainTex.Sample(s, uv, int2(j, 0)); }\n"
          "return c;")),
      HasSubstr("test.hlsl:5:79: error: the texel offset of 'Sample' must be a constant expression on this target"));
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

TEST(GlslEmitterIntrinsics, SelectChoosesComponentByComponent) {
  const std::string text =
      fragment("float4 _A; float4 _B; float _S;", "return select(_A > _B, _A, _B) + select(_S > 0, _S, 1.0);");
  EXPECT_THAT(text, HasSubstr("mix(_B, _A, greaterThan(_A, _B))"));
  EXPECT_THAT(text, HasSubstr("((_S > 0.0) ? _S : 1.0)"));
}

}  // namespace
}  // namespace xshade::glsl
