// The GLSL emitter's rules for expressions and statements (docs/hlsl_like.md) in both flavours:
// matrices, operators, conversions and literals, intrinsics, functions, statements and loops.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glsl/emitter_test_support.h"
#include "glsl/glsl_names.h"

namespace xshade::glsl::emitter_test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

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

TEST(GlslEmitterIntrinsics, SelectChoosesComponentByComponent) {
  const std::string text =
      fragment("float4 _A; float4 _B; float _S;", "return select(_A > _B, _A, _B) + select(_S > 0, _S, 1.0);");
  EXPECT_THAT(text, HasSubstr("mix(_B, _A, greaterThan(_A, _B))"));
  EXPECT_THAT(text, HasSubstr("((_S > 0.0) ? _S : 1.0)"));
}

}  // namespace
}  // namespace xshade::glsl::emitter_test
