// Semantic analysis of calls, one test per rule: constructors, overloads (DXC's costs as a
// table), intrinsics, texture methods, constant buffers and switch.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/intrinsics.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/sema.h"
#include "hlsl_like/sema_internal.h"
#include "hlsl_like/sema_test_support.h"

namespace xshade::hlsl::sema_test {
namespace {

TEST(SemaCalls, ConstructorsCountComponents) {
  EXPECT_EQ(type_of("float2 p;", "float4(p, 0, 1)"), "float4");
  EXPECT_EQ(probe("float2 p;", "float4(p, 0, 1)").tree, "(float4 p (to float 0) (to float 1))");
  EXPECT_EQ(probe("", "float3(1)").tree, "(float3 (to float3 1))");
  EXPECT_EQ(type_of("", "float2x2(1, 0, 0, 1)"), "float2x2");
  EXPECT_EQ(type_of("float2 a; float2 b;", "float2x2(a, b)"), "float2x2");
  EXPECT_EQ(probe("", "float3(1, 2)").messages,
            (Strings{"2:12: error: 'float3' constructor needs 3 components, 2 given"}));
  EXPECT_EQ(probe("float3 v;", "float4(v, 1, 2)").messages,
            (Strings{"2:12: error: 'float4' constructor needs 4 components, 5 given"}));
}

// DXC's pick among user overloads, case by case: the candidates, the arguments' declarations,
// the call's arguments, and the signature DXC calls (or "ambiguous"). DXC sums a cost per
// argument (truncation >> int -> float >> float -> int >> int <-> uint >> half -> float >> splat;
// literals fit their family exactly) and an equal lowest sum is ambiguous.
struct OverloadCase {
  const char* overloads;
  const char* locals;
  const char* args;
  const char* dxc_pick;
};

std::string pick_of(const OverloadCase& c) {
  auto a = analyze_source(std::string(c.overloads) + "\nvoid t() { " + c.locals + " f(" + c.args + "); }\n");
  for (const std::string& message : a->messages())
    if (message.find("ambiguous call") != std::string::npos) return "ambiguous";
  for (const std::string& message : a->messages())
    if (message.find("error") != std::string::npos) return message;
  const FunctionDecl& t = a->function("t");
  const auto& call = static_cast<const CallExpr&>(*static_cast<const ExprStmt&>(*t.body->statements.back()).expr);
  return call.function ? sema_detail::function_signature(*call.function) : "none";
}

TEST(SemaCalls, OverloadsAreRankedAsDxcRanksThem) {
  const OverloadCase cases[] = {
      // Unity's PositivePow(float3, float): a splat costs less than a truncation.
      {"void f(float a, float b) {}\nvoid f(float3 a, float3 b) {}", "float3 v; float s;", "v, s",
       "void f(float3, float3)"},
      {"void f(float a) {}\nvoid f(int a) {}", "bool b;", "b", "ambiguous"},
      {"void f(float a) {}\nvoid f(int a) {}", "half h;", "h", "void f(float)"},
      {"void f(float a) {}\nvoid f(int a) {}", "uint u;", "u", "void f(int)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "1", "void f(int)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "1.0", "void f(float)"},
      {"void f(float a) {}\nvoid f(int a) {}", "", "-2.5", "void f(float)"},
      {"void f(float2 a) {}\nvoid f(float4 a) {}", "float3 v;", "v", "void f(float2)"},
      {"void f(float a) {}\nvoid f(float4 a) {}", "float2 v;", "v", "void f(float)"},
      {"void f(half a) {}\nvoid f(float a) {}", "int i;", "i", "void f(float)"},
      {"void f(half a) {}\nvoid f(float a) {}", "", "1.0", "ambiguous"},
      {"void f(half a) {}\nvoid f(float a) {}", "half h;", "h", "void f(half)"},
      {"void f(int2 a) {}\nvoid f(float2 a) {}", "uint2 u;", "u", "void f(int2)"},
      {"void f(int2 a) {}\nvoid f(float2 a) {}", "half2 h;", "h", "void f(float2)"},
      {"void f(float3x3 a) {}\nvoid f(float4x4 a) {}", "float4x3 m;", "m", "void f(float3x3)"},
      {"void f(float a) {}\nvoid f(float2x2 a) {}", "float1x1 m;", "m", "void f(float)"},
      {"void f(int a, float b) {}\nvoid f(float a, int b) {}", "int i;", "i, i", "ambiguous"},
      {"void f(float3 a) {}\nvoid f(half3 a) {}", "", "1", "ambiguous"},
      {"void f(float3 a) {}\nvoid f(half3 a) {}", "", "1.0", "ambiguous"},
      // Two splats cost less than one int -> float conversion (DXC's own example).
      {"void f(int a, float b) {}\nvoid f(float2 a, float2 b) {}", "float x;", "x, x", "void f(float2, float2)"},
      // An int -> float conversion costs more than a float -> int one.
      {"void f(float a) {}\nvoid f(uint a) {}", "int i;", "i", "void f(uint)"},
      // float -> int and float -> half are both casts on the parameter's side.
      {"void f(int a) {}\nvoid f(half a) {}", "float x;", "x", "ambiguous"},
      // Out parameters are costed for the copy back too.
      {"void f(out float a) {}\nvoid f(out int a) {}", "float x;", "x", "void f(out float)"},
  };
  for (const OverloadCase& c : cases) EXPECT_EQ(pick_of(c), c.dxc_pick) << c.overloads << " with f(" << c.args << ")";
}

TEST(SemaCalls, AmbiguousCallsListTheCandidates) {
  EXPECT_EQ(messages_of("void f(float a, int b) {}\nvoid f(int a, float b) {}\nvoid t() { f(1, 1); }\n"),
            (Strings{"3:12: error: ambiguous call to 'f' with (int, int)", "1:6: note: candidate 'void f(float, int)'",
                     "2:6: note: candidate 'void f(int, float)'"}));
}

TEST(SemaCalls, NoViableOverloadListsTheCandidates) {
  EXPECT_EQ(messages_of("struct S { float a; };\nvoid f(S s) {}\nvoid f(float2 a, float2 b) {}\n"
                        "void t(float3 v, S s) { f(v, s); }\n"),
            (Strings{"4:25: error: no overload of 'f' takes (float3, S)", "2:6: note: candidate 'void f(S)'",
                     "3:6: note: candidate 'void f(float2, float2)'"}));
}

TEST(SemaCalls, ASingleFunctionConvertsItsArguments) {
  auto a = analyze_source(
      "float f(float3 v, out float o) { o = 1; return v.x; }\n"
      "void t(float4 p) {\n  float r;\n  f(p, r);\n  f(p);\n  f(p, 1);\n}\n");
  EXPECT_EQ(a->messages(),
            (Strings{"4:5: warning: implicit truncation of vector type from 'float4' to 'float3'",
                     "5:3: error: 'f' takes 2 arguments, 1 given",
                     "6:5: warning: implicit truncation of vector type from 'float4' to 'float3'",
                     "6:8: error: argument 2 of 'f' is an out parameter and needs an assignable expression"}));
}

TEST(SemaCalls, DefaultArgumentsMayBeLeftOut) {
  auto a = analyze_source("float f(float a, float b = 2) { return a * b; }\nvoid t() { f(1); f(1, 2); f(); }\n");
  EXPECT_EQ(a->messages(), (Strings{"2:27: error: 'f' takes 1 to 2 arguments, 0 given"}));
}

TEST(SemaCalls, FunctionsMustBeDeclaredBeforeUse) {
  EXPECT_EQ(messages_of("void t() { g(); }\nvoid g() {}\n"),
            (Strings{"1:12: error: function 'g' is used before its declaration"}));
  auto a = analyze_source("void g();\nvoid t() { g(); }\nvoid g() {}\n");
  EXPECT_EQ(a->messages(), Strings{});
  const auto& call = static_cast<const CallExpr&>(a->expression("t", 0));
  EXPECT_EQ(call.function, &a->function("g"));  // the definition, not the prototype
  EXPECT_EQ(static_cast<const FunctionDecl&>(*a->unit.decls[0]).definition, &a->function("g"));
  EXPECT_EQ(messages_of("void g();\nvoid t() { g(); }\n"),
            (Strings{"2:12: error: function 'g' is called but never defined"}));
}

TEST(SemaCalls, RedefinitionOfAFunction) {
  EXPECT_EQ(messages_of("void g() {}\nvoid g() {}\nvoid g(int a) {}\n"),
            (Strings{"2:6: error: redefinition of 'g'", "1:6: note: previous definition of 'g' is here"}));
}

TEST(SemaCalls, RecursionIsAnError) {
  EXPECT_EQ(messages_of("float f(float x) { return f(x - 1); }\n"),
            (Strings{"1:27: error: recursive call to 'f' is not supported"}));
  EXPECT_EQ(messages_of("float b(float x);\nfloat a(float x) { return b(x); }\nfloat b(float x) { return a(x); }\n"),
            (Strings{"2:27: error: recursive call to 'b' is not supported"}));
}

TEST(SemaCalls, UnknownFunctions) {
  EXPECT_EQ(messages_of("void t() { foo(1); }\n"), (Strings{"1:12: error: unknown function 'foo'"}));
  EXPECT_EQ(messages_of("void t() { float x = lerpp(0, 1, 0.5); }\n"),
            (Strings{"1:22: error: unknown function 'lerpp'; did you mean 'lerp'?"}));
}

// ---------------------------------------------------------------------------------------------
// Intrinsics

TEST(SemaIntrinsics, LerpSplatsItsScalarWeight) {
  Probe p = probe("float3 a; float3 b; float s;", "lerp(a, b, s)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float3");
  EXPECT_EQ(p.tree, "(lerp a b (to float3 s))");
  EXPECT_EQ(probe("float3 a;", "lerp(0.04, a, 0.5)").tree, "(lerp (to float3 0.04) a (to float3 0.5))");
  EXPECT_EQ(probe("float3 a;", "lerp(a, 1)").messages, (Strings{"2:12: error: 'lerp' takes 3 arguments, 2 given"}));
}

TEST(SemaIntrinsics, GenericTypesFollowHlsl) {
  const std::string g = "half3 h; float3 f; int i; int3 i3; uint u; float x; half hs;";
  EXPECT_EQ(type_of(g, "lerp(h, h, 0.5)"), "half3");
  EXPECT_EQ(type_of(g, "lerp(h, f, 0.5)"), "float3");
  EXPECT_EQ(type_of(g, "sqrt(i)"), "float");
  EXPECT_EQ(probe(g, "sqrt(i)").tree, "(sqrt (to float i))");
  EXPECT_EQ(type_of(g, "max(i, 0)"), "int");
  EXPECT_EQ(type_of(g, "max(f, 0)"), "float3");
  EXPECT_EQ(type_of(g, "clamp(i3, 0, 4)"), "int3");
  EXPECT_EQ(type_of(g, "abs(i3)"), "int3");
  EXPECT_EQ(type_of(g, "saturate(h)"), "half3");
  EXPECT_EQ(type_of(g, "pow(x, 5)"), "float");
  EXPECT_EQ(type_of(g, "smoothstep(0, 1, f)"), "float3");
  EXPECT_EQ(type_of(g, "step(0.5, f)"), "float3");
  EXPECT_EQ(type_of(g, "sign(f)"), "int3");
  EXPECT_EQ(type_of(g, "frac(hs)"), "half");
  EXPECT_EQ(type_of(g, "fmod(x, 2)"), "float");
}

TEST(SemaIntrinsics, VectorIntrinsics) {
  const std::string g = "float3 a; float3 b; float4 c; int3 i; float2 p;";
  EXPECT_EQ(type_of(g, "dot(a, b)"), "float");
  EXPECT_EQ(type_of(g, "dot(i, i)"), "int");
  EXPECT_EQ(type_of(g, "length(c)"), "float");
  EXPECT_EQ(type_of(g, "distance(a, b)"), "float");
  EXPECT_EQ(type_of(g, "normalize(a)"), "float3");
  EXPECT_EQ(type_of(g, "cross(a, b)"), "float3");
  EXPECT_EQ(type_of(g, "reflect(-a, b)"), "float3");
  EXPECT_EQ(type_of(g, "refract(a, b, 0.66)"), "float3");
  EXPECT_EQ(probe(g, "cross(p, p)").messages, (Strings{"2:12: error: no overload of 'cross' takes (float2, float2)"}));
  Probe q = probe(g, "dot(c, a)");
  EXPECT_EQ(q.type, "float");
  EXPECT_EQ(q.messages, (Strings{"2:16: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
}

TEST(SemaIntrinsics, MulCoversEveryHlslOverload) {
  const std::string g =
      "float s; float3 v3; float4 v4; float4x4 m44; float3x4 m34; float4x3 m43; float2x3 m23; float3x4 n34;";
  EXPECT_EQ(type_of(g, "mul(v4, m44)"), "float4");  // row vector
  EXPECT_EQ(type_of(g, "mul(m44, v4)"), "float4");  // column vector
  EXPECT_EQ(type_of(g, "mul(m34, v4)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v4, m43)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v3, m34)"), "float4");
  EXPECT_EQ(type_of(g, "mul(m44, m44)"), "float4x4");
  EXPECT_EQ(type_of(g, "mul(m23, n34)"), "float2x4");
  EXPECT_EQ(type_of(g, "mul(s, v3)"), "float3");
  EXPECT_EQ(type_of(g, "mul(v3, s)"), "float3");
  EXPECT_EQ(type_of(g, "mul(s, m44)"), "float4x4");
  EXPECT_EQ(type_of(g, "mul(v3, v3)"), "float");
  EXPECT_EQ(type_of(g, "mul(s, s)"), "float");
  EXPECT_EQ(probe(g, "mul(m44, m23)").messages,
            (Strings{"2:12: error: no overload of 'mul' takes (float4x4, float2x3)"}));
  EXPECT_EQ(probe(g, "mul(v3, m44)").messages, (Strings{"2:12: error: no overload of 'mul' takes (float3, float4x4)"}));
  Probe p = probe(g, "mul(v4, m34)");
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(p.tree, "(mul (to float3 v4) m34)");
  EXPECT_EQ(p.messages, (Strings{"2:16: warning: implicit truncation of vector type from 'float4' to 'float3'"}));
  const auto a = analyze_source("float4x4 m; float4 v;\nfloat4 t() { return mul(m, v); }\n");
  const auto& call = static_cast<const CallExpr&>(a->expression("t", 0));
  EXPECT_EQ(call.call_kind, CallKind::Intrinsic);
  EXPECT_EQ(call.intrinsic, uint16_t(IntrinsicId::Mul));
}

TEST(SemaIntrinsics, PredicatesBitCastsAndMatrices) {
  const std::string g = "float3 f; int2 i; uint u; float3x4 m; float3x3 n; bool3 b;";
  EXPECT_EQ(type_of(g, "all(b)"), "bool");
  EXPECT_EQ(type_of(g, "any(f)"), "bool");
  EXPECT_EQ(type_of(g, "isnan(f)"), "bool3");
  EXPECT_EQ(type_of(g, "isfinite(f)"), "bool3");
  EXPECT_EQ(type_of(g, "asuint(f)"), "uint3");
  EXPECT_EQ(type_of(g, "asfloat(i)"), "float2");
  EXPECT_EQ(type_of(g, "asint(u)"), "int");
  EXPECT_EQ(type_of(g, "f16tof32(u)"), "float");
  EXPECT_EQ(type_of(g, "f32tof16(f)"), "uint3");
  EXPECT_EQ(type_of(g, "countbits(u)"), "uint");
  EXPECT_EQ(type_of(g, "reversebits(i)"), "uint2");
  EXPECT_EQ(type_of(g, "transpose(m)"), "float4x3");
  EXPECT_EQ(type_of(g, "determinant(n)"), "float");
  EXPECT_EQ(probe(g, "determinant(m)").messages,
            (Strings{"2:12: error: no overload of 'determinant' takes (float3x4)"}));
  EXPECT_EQ(type_of(g, "mad(f, f, 1)"), "float3");
  EXPECT_EQ(type_of(g, "ldexp(f, 2)"), "float3");
  EXPECT_EQ(type_of(g, "exp2(log10(f))"), "float3");
  EXPECT_EQ(type_of(g, "degrees(radians(1))"), "float");
  EXPECT_EQ(type_of(g, "trunc(round(ceil(floor(f))))"), "float3");
  EXPECT_EQ(type_of(g, "rcp(rsqrt(f))"), "float3");
}

TEST(SemaIntrinsics, OutParametersNeedAssignableArguments) {
  auto a = analyze_source(
      "void t(float3 x) {\n  float3 s, c;\n  sincos(x, s, c);\n  sincos(x, 1.0, c);\n"
      "  float3 ip;\n  float3 fr = modf(x, ip);\n}\n");
  EXPECT_EQ(a->messages(),
            (Strings{"4:13: error: argument 2 of 'sincos' is an out parameter and needs an assignable expression"}));
  EXPECT_EQ(dump(&a->expression("t", 1)), "(sincos x s c)");
  EXPECT_EQ(a->expression("t", 1).type.name(), "void");
}

TEST(SemaIntrinsics, ClipAndDerivatives) {
  EXPECT_EQ(type_of("float f; float2 p;", "clip(f - 0.5)"), "void");
  EXPECT_EQ(type_of("float f; float2 p;", "ddx(p)"), "float2");
  EXPECT_EQ(type_of("float f; float2 p;", "fwidth(f)"), "float");
}

TEST(SemaIntrinsics, Dx9Samplers) {
  const std::string g = "sampler2D s; float2 uv; float4 q; Texture2D tex;";
  Probe p = probe(g, "tex2D(s, uv)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(type_of(g, "tex2Dlod(s, float4(uv, 0, 2))"), "float4");
  EXPECT_EQ(type_of(g, "tex2Dbias(s, q)"), "float4");
  EXPECT_EQ(type_of(g, "tex2Dgrad(s, uv, ddx(uv), ddy(uv))"), "float4");
  EXPECT_EQ(probe(g, "tex2D(tex, uv)").messages,
            (Strings{"2:12: error: no overload of 'tex2D' takes (Texture2D, float2)"}));
}

TEST(SemaIntrinsics, Texture2DMethods) {
  const std::string g = "Texture2D tex; SamplerState ss; sampler2D s2; float2 uv; float4 v; int3 px;";
  Probe p = probe(g, "tex.Sample(ss, uv)");
  EXPECT_EQ(p.messages, Strings{});
  EXPECT_EQ(p.type, "float4");
  EXPECT_EQ(type_of(g, "tex.SampleLevel(ss, uv, 0)"), "float4");
  EXPECT_EQ(probe(g, "tex.SampleLevel(ss, uv, 0)").tree, "(.SampleLevel tex ss uv (to float 0))");
  EXPECT_EQ(type_of(g, "tex.SampleBias(ss, uv, -1)"), "float4");
  EXPECT_EQ(type_of(g, "tex.SampleGrad(ss, uv, uv, uv)"), "float4");
  EXPECT_EQ(type_of(g, "tex.Load(px)"), "float4");
  EXPECT_EQ(type_of(g, "tex.Load(int3(1, 2, 0)).rgb"), "float3");
  EXPECT_EQ(type_of(g, "uint w, h; tex.GetDimensions(w, h)"), "void");
  EXPECT_EQ(type_of(g, "float fw, fh; tex.GetDimensions(fw, fh)"), "void");
  EXPECT_EQ(probe(g, "tex.Sample(s2, uv)").messages,
            (Strings{"2:16: error: no overload of 'Sample' of 'Texture2D' takes (sampler2D, float2)"}));
  EXPECT_EQ(probe(g, "v.Sample(ss, uv)").messages, (Strings{"2:14: error: 'float4' has no method 'Sample'"}));
  EXPECT_EQ(probe(g, "tex.Blur(ss, uv)").messages, (Strings{"2:16: error: 'Texture2D' has no method 'Blur'"}));
  auto a = analyze_source("Texture2D tex; SamplerState ss;\nfloat4 f(float2 uv) { return tex.Sample(ss, uv); }\n");
  const auto& call = static_cast<const CallExpr&>(a->expression("f", 0));
  EXPECT_EQ(call.call_kind, CallKind::Method);
  EXPECT_EQ(call.intrinsic, uint16_t(IntrinsicId::Sample));
}

TEST(SemaTextures, EachShapeTakesItsCoordinatesOffsetsAndGivesItsTexels) {
  const std::string g =
      "Texture1D t1; Texture2DArray t2a; Texture3D t3; TextureCube tc; TextureCubeArray tca; Texture2DMS<float4> tms;"
      "Texture2D<float> depth; Texture2D<uint2> ids; SamplerState s; SamplerComparisonState c; float2 uv; float3 p;";
  EXPECT_EQ(type_of(g, "t1.Sample(s, 0.5)"), "float4");
  EXPECT_EQ(type_of(g, "t2a.SampleLevel(s, p, 0, int2(1, 0))"), "float4");
  EXPECT_EQ(type_of(g, "t3.SampleGrad(s, p, p, p, int3(0, 0, 1))"), "float4");
  EXPECT_EQ(type_of(g, "tc.SampleBias(s, p, 1)"), "float4");
  EXPECT_EQ(type_of(g, "tca.SampleLevel(s, float4(p, 2), 0)"), "float4");
  EXPECT_EQ(type_of(g, "depth.Sample(s, uv)"), "float");  // the texel type
  EXPECT_EQ(type_of(g, "ids.Load(int3(0, 0, 0))"), "uint2");
  EXPECT_EQ(type_of(g, "ids[uint2(1, 2)]"), "uint2");
  EXPECT_EQ(type_of(g, "tms.Load(int2(1, 2), 3)"), "float4");
  EXPECT_EQ(type_of(g, "t3.Load(int4(1, 2, 3, 0), int3(1, 1, 1))"), "float4");
  EXPECT_EQ(type_of(g, "depth.SampleCmp(c, uv, 0.5)"), "float");
  EXPECT_EQ(type_of(g, "depth.SampleCmpLevelZero(c, uv, 0.5, int2(1, 1))"), "float");
  EXPECT_EQ(type_of(g, "depth.GatherRed(s, uv)"), "float4");
  EXPECT_EQ(type_of(g, "ids.GatherGreen(s, uv, int2(1, 0))"), "uint4");
  EXPECT_EQ(type_of(g, "tc.CalculateLevelOfDetail(s, p)"), "float");
  EXPECT_EQ(type_of(g, "uint w, h, l, n; tms.GetDimensions(w, h, n); t2a.GetDimensions(0, w, h, n, l)"), "void");
  // What a shape does not have.
  EXPECT_EQ(probe(g, "tc.Load(int4(0, 0, 0, 0))").messages,
            (Strings{"2:15: error: 'TextureCube' has no method 'Load'"}));
  EXPECT_EQ(probe(g, "tc.SampleLevel(s, p, 0, int3(1, 0, 0))").messages,
            (Strings{"2:15: error: 'SampleLevel' of 'TextureCube' takes 3 arguments, 4 given"}));
  EXPECT_EQ(probe(g, "tms.Sample(s, uv)").messages, (Strings{"2:16: error: 'Texture2DMS' has no method 'Sample'"}));
  EXPECT_EQ(probe(g, "t3.Gather(s, p)").messages, (Strings{"2:15: error: 'Texture3D' has no method 'Gather'"}));
  EXPECT_EQ(
      probe(g, "depth.SampleCmp(s, uv, 0.5)").messages,
      (Strings{"2:18: error: no overload of 'SampleCmp' of 'Texture2D<float>' takes (SamplerState, float2, float)"}));
  EXPECT_EQ(probe(g, "t2a.Sample(s, uv)").messages,
            (Strings{"2:16: error: no overload of 'Sample' of 'Texture2DArray' takes (SamplerState, float2)"}));
}

TEST(SemaTextures, Dx9SamplersOfEveryShape) {
  const std::string g = "sampler1D d1; sampler3D d3; samplerCUBE dc; float3 p;";
  EXPECT_EQ(type_of(g, "tex1D(d1, p.x)"), "float4");
  EXPECT_EQ(type_of(g, "tex3Dlod(d3, float4(p, 2))"), "float4");
  EXPECT_EQ(type_of(g, "texCUBE(dc, p)"), "float4");
  EXPECT_EQ(type_of(g, "texCUBEbias(dc, float4(p, -1))"), "float4");
  EXPECT_EQ(probe(g, "texCUBE(d3, p)").messages,
            (Strings{"2:12: error: no overload of 'texCUBE' takes (sampler3D, float3)"}));
}

TEST(SemaTextures, ResourcesNoTargetHereBindsAreTypedAsHlslDefinesThem) {
  // Checked as HLSL, so that a file that declares them compiles where its entry points do not
  // read them (the emitter refuses them where they are reached).
  auto a = analyze_source(
      "struct Light { float3 color; };\n"
      "StructuredBuffer<Light> lights; RWTexture2D<float4> output; ByteAddressBuffer raw; Buffer<float2> coords;\n"
      "float3 shade(uint i) { uint n, stride; lights.GetDimensions(n, stride);\n"
      "  output[uint2(i, 0)] = float4(lights[i].color, 1);\n"
      "  return lights.Load(i).color + float3(raw.Load2(4 * i), 0) + coords[i].xyy; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(messages_of("StructuredBuffer<float> b;\nvoid f() { b[0] = 1; }\n"),
            (Strings{"2:12: error: cannot assign to 'b': uniforms are read-only"}));
  EXPECT_EQ(messages_of("ByteAddressBuffer b;\nvoid f() { b.Store(0, 1); }\n"),
            (Strings{"2:14: error: 'ByteAddressBuffer' has no method 'Store'"}));
}

TEST(SemaConstantBuffers, AConstantBufferOfAStructIsReadByItsFields) {
  auto a = analyze_source(
      "struct Scene { float4x4 view; float3 light; };\nConstantBuffer<Scene> scene : register(b1);\n"
      "float3 f() { return scene.light + scene.view[0].xyz; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(
      messages_of("struct Scene { float3 light; };\nConstantBuffer<Scene> scene;\nvoid f() { scene.light = 1; }\n"),
      (Strings{"3:12: error: cannot assign to 'scene': uniforms are read-only"}));
  EXPECT_EQ(
      messages_of("struct Scene { float3 light; };\nConstantBuffer<Scene> scene;\nfloat f() { return scene.dark; }\n"),
      (Strings{"3:26: error: 'ConstantBuffer<Scene>' has no member 'dark'"}));
}

TEST(SemaStatements, SwitchTakesIntegerConstantsAndBreaks) {
  EXPECT_EQ(messages_of("int f(int m) { switch (m) { case 0: return 1; case 1 + 1: m = 2; break; default: break; }\n"
                        "  return m; }\n"),
            Strings{});
  EXPECT_EQ(messages_of("float f(uint m) { switch (m) { case 0: case 1: return 1; default: return 2; } }\n"),
            Strings{});
  EXPECT_EQ(messages_of("void f(float x) { switch (x) { default: break; } }\n"),
            (Strings{"1:27: warning: the condition of a switch is 'float': converted to int toward zero, as fxc does "
                     "(DXC refuses it); write (int)(...) to say so"}));
  EXPECT_EQ(messages_of("void f(float2 x) { switch (x) { default: break; } }\n"),
            (Strings{"1:28: error: the condition of a switch must be an integer scalar, not 'float2'"}));
  EXPECT_EQ(messages_of("void f(int m, int n) { switch (m) { case 1: break; case n: break; case 1: break; } }\n"),
            (Strings{"1:57: error: a case value must be an integer constant", "1:67: error: case value 1 appears twice",
                     "1:37: note: the first is here"}));
  EXPECT_EQ(messages_of("void f(int m) { switch (m) { default: break; default: break; } }\n"),
            (Strings{"1:46: error: a switch has one 'default'"}));
  EXPECT_EQ(messages_of("void f() { continue; }\nvoid g() { break; }\n"),
            (Strings{"1:12: error: 'continue' is only allowed inside a loop",
                     "2:12: error: 'break' is only allowed inside a loop or a switch"}));
}

TEST(SemaIntrinsics, SelectIsAComponentWiseChoice) {
  EXPECT_EQ(type_of("float3 a; float3 b;", "select(a > b, a, b)"), "float3");
  EXPECT_EQ(type_of("float a; int b;", "select(a > 0, a, b)"), "float");
  EXPECT_EQ(probe("float3 a; float3 b;", "select(a > b, a, b)").tree, "(select (> a b) a b)");
}

TEST(SemaIntrinsics, UserFunctionsNamedLikeIntrinsicsAreCalledWhenTheyFit) {
  auto a = analyze_source(
      "struct S { float a; };\nfloat saturate(S s) { return s.a; }\n"
      "void t(S s, float3 v) { saturate(s); saturate(v); }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(static_cast<const CallExpr&>(a->expression("t", 0)).call_kind, CallKind::Function);
  EXPECT_EQ(static_cast<const CallExpr&>(a->expression("t", 1)).call_kind, CallKind::Intrinsic);
}

}  // namespace
}  // namespace xshade::hlsl::sema_test
