// Semantic analysis of statements, entry points and whole shaders, one test per rule, and its
// robustness against whatever the parser makes of broken text.
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

// ---------------------------------------------------------------------------------------------
// Statements

TEST(SemaStatements, BreakAndContinueNeedALoop) {
  EXPECT_EQ(messages_of("void t() {\n  break;\n  for (;;) { if (true) continue; break; }\n  continue;\n}\n"),
            (Strings{"2:3: error: 'break' is only allowed inside a loop or a switch",
                     "4:3: error: 'continue' is only allowed inside a loop"}));
}

TEST(SemaStatements, ResourcesInStructsAndLocalsButNotInLocalArraysOrGlobalStructs) {
  EXPECT_EQ(messages_of("struct S { Texture2D t; SamplerState s; };\nTexture2D g;\n"
                        "void f(Texture2D t, S p) { Texture2D u = g; S v = p; v.t = u; }\n"),
            Strings{});
  EXPECT_EQ(messages_of("void f() { Texture2D t[2]; }\n"),
            (Strings{"1:22: error: variable 't' cannot have type 'Texture2D[2]'; arrays of resources are supported as "
                     "globals of textures, samplers and constant buffers only: declare each one separately"}));
  EXPECT_EQ(messages_of("struct S { Texture2D t; };\nS g;\n"),
            (Strings{"2:3: error: variable 'g' of struct 'S' holds resources: declare each resource as a global of "
                     "its own"}));
}

// ---------------------------------------------------------------------------------------------
// Entry points

TEST(SemaEntryPoints, MissingEntryPointIsReportedAtThePragma) {
  auto a = analyze_source(
      "#pragma vertex vert\n#pragma fragment frag\nfloat4 vert(float4 p : POSITION) : SV_Position { return p; }\n");
  EXPECT_EQ(a->messages(), (Strings{"2:18: error: entry point 'frag' is not defined"}));
  EXPECT_NE(a->entry_points.vertex, nullptr);
  EXPECT_EQ(a->entry_points.fragment, nullptr);
}

TEST(SemaEntryPoints, InputsAndOutputsNeedSemantics) {
  const std::string source =
      "#pragma vertex vert\n"
      "struct appdata { float4 vertex : POSITION; float2 uv; };\n"
      "struct v2f { float4 pos : SV_Position; float2 uv; };\n"
      "v2f vert(appdata v, float3 n) { v2f o; o.pos = v.vertex; o.uv = v.uv + n.xy; return o; }\n";
  EXPECT_EQ(messages_of(source), (Strings{"2:51: error: input 'uv' of entry point 'vert' needs a semantic",
                                          "4:28: error: input 'n' of entry point 'vert' needs a semantic",
                                          "3:47: error: output 'uv' of entry point 'vert' needs a semantic"}));
}

TEST(SemaEntryPoints, VertexMustOutputAPosition) {
  EXPECT_EQ(messages_of("#pragma vertex vert\nfloat4 vert(float4 p : POSITION) : TEXCOORD0 { return p; }\n"),
            (Strings{"2:8: error: vertex entry point 'vert' does not output SV_Position"}));
  // POSITION is DX9's name for the clip position; out parameters are outputs too.
  EXPECT_EQ(messages_of("#pragma vertex vert\nvoid vert(float4 p : POSITION, out float4 o : POSITION) { o = p; }\n"),
            Strings{});
}

TEST(SemaEntryPoints, FragmentMustOutputATarget) {
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float2 uv : TEXCOORD0) : TEXCOORD1 { return 1; }\n"),
            (Strings{"2:38: error: semantic 'TEXCOORD1' is not allowed on a fragment shader output",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
  EXPECT_EQ(
      messages_of("#pragma fragment frag\nstruct O { float4 c : SV_Target1; float d : SV_Depth; };\n"
                  "O frag(float4 p : SV_Position, bool face : SV_IsFrontFace) { O o; o.c = p; o.d = 0; return o; }\n"),
      Strings{});
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag() : color0 { return 1; }\n"), Strings{});
}

TEST(SemaEntryPoints, UnknownAndMisplacedSemantics) {
  // FOO is a user-defined semantic: a vertex input like any other; a pixel shader cannot output one.
  EXPECT_EQ(messages_of(
                "#pragma vertex vert\nfloat4 vert(float4 p : FOO, float4 q : SV_Target) : SV_Position { return p; }\n"),
            (Strings{"2:40: error: semantic 'SV_Target' is not allowed on a vertex shader input"}));
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float4 p : SV_POSITION) : FOO { return p; }\n"),
            (Strings{"2:39: error: semantic 'FOO' is not allowed on a fragment shader output",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
  EXPECT_EQ(messages_of("#pragma fragment frag\nfloat4 frag(float4 p : SV_POSITION) : SV_TARGET8 { return p; }\n"),
            (Strings{"2:39: error: unknown semantic 'SV_TARGET8': a system value's name starts SV_ and names one of "
                     "Direct3D's, any other identifier (with an index of at most two digits) names a varying",
                     "2:8: error: fragment entry point 'frag' does not output SV_Target or SV_Depth"}));
}

TEST(SemaEntryPoints, FragmentOnlyOperationsAreErrorsInTheVertexStage) {
  const std::string source =
      "#pragma vertex vert\n"
      "#pragma fragment frag\n"
      "float helper(float x) { return ddx(x); }\n"
      "float4 vert(float4 p : POSITION) : SV_Position { if (p.x < 0) discard; return p * helper(p.y); }\n"
      "float4 frag(float4 p : SV_Position) : SV_Target { clip(p.x); return helper(p.x); }\n";
  EXPECT_EQ(messages_of(source), (Strings{"4:63: error: 'discard' is only available in fragment shaders",
                                          "3:32: error: 'ddx' is only available in fragment shaders"}));
}

TEST(SemaEntryPoints, ImplicitLodSamplingIsFragmentOnly) {
  const std::string source =
      "#pragma vertex vert\n"
      "Texture2D tex; SamplerState ss; sampler2D s2;\n"
      "float4 vert(float4 p : POSITION) : SV_Position {\n"
      "  return p + tex.SampleLevel(ss, p.xy, 0) + tex2Dlod(s2, p) + tex.Sample(ss, p.xy) + tex2D(s2, p.xy);\n"
      "}\n";
  EXPECT_EQ(messages_of(source), (Strings{"4:67: error: 'Sample' is only available in fragment shaders",
                                          "4:86: error: 'tex2D' is only available in fragment shaders"}));
}

TEST(SemaEntryPoints, EntryPointsAreReturned) {
  auto a = analyze_source(
      "#pragma vertex vert\n#pragma fragment frag\n"
      "float4 vert(float4 p : POSITION, uniform float4x4 mvp) : SV_Position { return mul(mvp, p); }\n"
      "float4 frag() : SV_Target { return 1; }\n");
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(a->entry_points.vertex, &a->function("vert"));
  EXPECT_EQ(a->entry_points.fragment, &a->function("frag"));
}

// ---------------------------------------------------------------------------------------------
// A complete shader

const char* const kRealisticShader = R"(#pragma vertex vert
#pragma fragment frag

#define PI 3.14159265

struct appdata {
  float4 vertex : POSITION;
  float3 normal : NORMAL;
  float2 uv : TEXCOORD0;
};

struct v2f {
  float4 pos : SV_Position;
  float3 normal : TEXCOORD1;
  float2 uv : TEXCOORD0;
  float3 world : TEXCOORD2;
};

cbuffer PerObject : register(b0) {
  float4x4 _ObjectToWorld;
  float4x4 _MatrixVP;
  float4 _Color;
  float _Smoothness;
  float _Metallic;
};

float3 _LightDir;
float3 _LightColor;
float3 _CameraPos;

Texture2D _MainTex : register(t0);
SamplerState sampler_MainTex : register(s0);
sampler2D _RampTex;

static const float2 kOffsets[4] = { float2(-0.5, -0.5), float2(0.5, -0.5), float2(-0.5, 0.5), float2(0.5, 0.5) };

float D_GGX(float NoH, float a) {
  float a2 = a * a;
  float d = NoH * NoH * (a2 - 1) + 1;
  return a2 / (PI * d * d + 1e-7);
}

float3 fresnel(float3 f0, float LoH) {
  return f0 + (1 - f0) * pow(saturate(1 - LoH), 5);
}

void diffuse_and_specular(float3 albedo, float metallic, out float3 diff, out float3 spec, inout float reflectivity) {
  spec = lerp(0.04, albedo, metallic);
  reflectivity = 0.96 * (1 - metallic);
  diff = albedo * reflectivity;
}

v2f vert(appdata v) {
  v2f o = (v2f)0;
  float4 world = mul(_ObjectToWorld, v.vertex);
  o.pos = mul(_MatrixVP, world);
  o.world = world.xyz;
  o.normal = normalize(mul((float3x3)_ObjectToWorld, v.normal));
  o.uv = v.uv;
  return o;
}

float4 frag(v2f i, bool front : SV_IsFrontFace) : SV_Target {
  float3 n = normalize(i.normal) * (front ? 1 : -1);
  float3 v = normalize(_CameraPos - i.world);
  float3 l = normalize(-_LightDir);
  float3 h = normalize(l + v);
  float NoL = saturate(dot(n, l));
  float NoV = max(abs(dot(n, v)), 1e-4);
  float NoH = saturate(dot(n, h));
  float LoH = saturate(dot(l, h));

  float4 texel = _MainTex.Sample(sampler_MainTex, i.uv);
  float3 albedo = _Color.rgb * texel.rgb;
  float3 diff, spec;
  float reflectivity = 0;
  diffuse_and_specular(albedo, _Metallic, diff, spec, reflectivity);

  float r = max(1 - _Smoothness, 0.002);
  float D = D_GGX(NoH, r);
  float3 F = fresnel(spec, LoH);
  float G = min(1, min(2 * NoH * NoV / LoH, 2 * NoH * NoL / LoH));
  float3 direct = (diff + D * F * G * PI / (4 * NoL * NoV)) * _LightColor * NoL;

  float3 ramp = tex2D(_RampTex, float2(NoL * 0.5 + 0.5, 0.5)).rgb;
  float3 blur = 0;
  [unroll] for (int k = 0; k < 4; ++k) {
    blur += _MainTex.SampleLevel(sampler_MainTex, i.uv + kOffsets[k] * 0.01, 0).rgb;
  }
  blur *= 0.25;
  uint w, hgt;
  _MainTex.GetDimensions(w, hgt);
  float2 texel_size = 1.0 / float2(w, hgt);
  float s, c;
  sincos(texel_size.x, s, c);
  clip(texel.a - 0.01);
  float3 color = direct * ramp + blur * 0.1 + s * 0;
  return float4(color, texel.a * _Color.a);
}
)";

TEST(SemaShader, ARealisticShaderHasNoDiagnostics) {
  auto a = analyze_source(kRealisticShader);
  EXPECT_EQ(a->messages(), Strings{});
  EXPECT_EQ(a->entry_points.vertex, &a->function("vert"));
  EXPECT_EQ(a->entry_points.fragment, &a->function("frag"));
}

// Every expression of an analyzed tree without errors has a type.
void expect_typed(const Expr* e, int depth = 0) {
  if (!e || depth > 300) return;
  EXPECT_FALSE(e->type.is_error()) << dump(e);
  switch (e->kind) {
    case ExprKind::Unary: expect_typed(static_cast<const UnaryExpr*>(e)->operand.get(), depth + 1); break;
    case ExprKind::Binary:
      expect_typed(static_cast<const BinaryExpr*>(e)->lhs.get(), depth + 1);
      expect_typed(static_cast<const BinaryExpr*>(e)->rhs.get(), depth + 1);
      break;
    case ExprKind::Call:
      for (const ExprPtr& arg : static_cast<const CallExpr*>(e)->args) expect_typed(arg.get(), depth + 1);
      break;
    case ExprKind::Conversion: expect_typed(static_cast<const ConversionExpr*>(e)->operand.get(), depth + 1); break;
    default: break;
  }
}

TEST(SemaShader, EveryExpressionGetsAType) {
  auto a = analyze_source(kRealisticShader);
  for (const auto& stmt : a->function("frag").body->statements) {
    if (stmt->kind == StmtKind::Decl) {
      for (const auto& var : static_cast<const DeclStmt&>(*stmt).vars) expect_typed(var->initializer.get());
    } else if (stmt->kind == StmtKind::Expr) {
      expect_typed(static_cast<const ExprStmt&>(*stmt).expr.get());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Robustness: whatever the parser makes of broken text, analysis must not crash.

TEST(SemaRobustness, EveryPrefixOfAShaderIsAnalyzedWithoutCrashing) {
  const std::string text = kRealisticShader;
  for (size_t length = 0; length <= text.size(); length += 13) {
    auto a = analyze_source(text.substr(0, length));
    (void)a;
  }
}

TEST(SemaRobustness, MutatedShadersAreAnalyzedWithoutCrashing) {
  const std::string text = kRealisticShader;
  std::mt19937 random(1234);
  const std::string pieces[] = {"(",   ")",      "{",       "}",      ";",     ",",    "=",  "[",
                                "]",   ".",      "x",       "float4", "1",     "?",    ":",  "Texture2D",
                                "out", "return", "discard", "mul(",   "{1,2}", "_m00", "++", "S"};
  for (int round = 0; round < 150; ++round) {
    std::string mutated = text;
    for (int edit = 0; edit < 4; ++edit) {
      const size_t at = random() % mutated.size();
      const size_t length = random() % 8;
      mutated.replace(at, std::min(length, mutated.size() - at), pieces[random() % std::size(pieces)]);
    }
    auto a = analyze_source(mutated);
    (void)a;
  }
}

TEST(SemaRobustness, DeepExpressionsAreBounded) {
  // The parser stops at 256 levels; sema has its own bound for trees made otherwise.
  auto parsed = analyze_source("float t(float x) { return x" + std::string(600, '+') + "x; }\n");
  EXPECT_FALSE(parsed->messages().empty());
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  TranslationUnit unit;
  auto function = std::make_unique<FunctionDecl>(Loc{});
  function->name = "f";
  function->return_type = Type::scalar(ScalarType::Float);
  function->body = std::make_unique<BlockStmt>(Loc{});
  ExprPtr chain = std::make_unique<FloatLiteralExpr>(Loc{});
  for (int i = 0; i < 5000; ++i) {
    auto add = std::make_unique<BinaryExpr>(Loc{}, BinaryOp::Add);
    add->lhs = std::move(chain);
    add->rhs = std::make_unique<FloatLiteralExpr>(Loc{});
    chain = std::move(add);
  }
  auto ret = std::make_unique<ReturnStmt>(Loc{});
  ret->value = std::move(chain);
  function->body->statements.push_back(std::move(ret));
  unit.decls.push_back(std::move(function));
  analyze(unit, {}, diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1u);
  EXPECT_EQ(diagnostics.diagnostics()[0].message, "expression or statement is nested too deeply");
}

TEST(SemaRobustness, NestedStructsAndConstantsStayLinear) {
  // Each struct holds two of the previous one and each constant uses the previous one twice:
  // walking them naively would take 2^30 steps.
  std::string source = "struct S0 { float a; };\nstatic const int c0 = 1;\n";
  for (int i = 1; i <= 30; ++i) {
    const std::string n = std::to_string(i), p = std::to_string(i - 1);
    source += "struct S" + n + " { S" + p + " a; S" + p + " b; };\n";
    source += "static const int c" + n + " = c" + p + " + c" + p + " - c" + p + ";\n";
  }
  source +=
      "float4 arr[2];\n#pragma vertex vert\n"
      "float4 vert(S30 s) : SV_Position { S30 x = (S30)0; S30 y = {1, 2}; return arr[c30] + arr[c30 + 1]; }\n";
  auto a = analyze_source(source);
  EXPECT_EQ(a->messages(), (Strings{"65:60: error: initializer has 2 components, 'S30' needs 1073741824",
                                    "65:94: error: index 2 is out of range for 'float4[2]'",
                                    "1:19: error: input 'a' of entry point 'vert' needs a semantic",
                                    "65:8: error: entry point 'vert' has too many inputs or outputs"}));
}

TEST(SemaRobustness, ConstantFoldingDoesNotOverflow) {
  auto a = analyze_source(
      "static const int big = 2147483647;\n"
      "float t(float4 v) { return v[4294967295u * 4294967295u * 4294967295u] + v[-big - big - big] + v[(big << 31) << "
      "31]"
      " + v[~big * big] + v[1 << 40] + v[5 % 0]; }\n");
  for (const std::string& message : a->messages())
    EXPECT_EQ(message.find("out of range"), std::string::npos) << message;
}

TEST(SemaRobustness, HandBuiltTreesWithNullChildren) {
  SourceManager sources;
  DiagnosticEngine diagnostics(sources);
  TranslationUnit unit;
  auto function = std::make_unique<FunctionDecl>(Loc{});
  function->name = "f";
  function->return_type = Type::scalar(ScalarType::Float);
  function->body = std::make_unique<BlockStmt>(Loc{});
  auto ret = std::make_unique<ReturnStmt>(Loc{});
  auto binary = std::make_unique<BinaryExpr>(Loc{}, BinaryOp::Add);  // both operands null
  ret->value = std::move(binary);
  function->body->statements.push_back(std::move(ret));
  auto stmt = std::make_unique<IfStmt>(Loc{});  // no condition, no branches
  function->body->statements.push_back(std::move(stmt));
  auto call = std::make_unique<CallExpr>(Loc{});
  call->callee = "lerp";
  call->args.push_back(nullptr);
  auto expr_stmt = std::make_unique<ExprStmt>(Loc{});
  expr_stmt->expr = std::move(call);
  function->body->statements.push_back(std::move(expr_stmt));
  function->body->statements.push_back(nullptr);
  unit.decls.push_back(std::move(function));
  unit.decls.push_back(nullptr);
  analyze(unit, {}, diagnostics);
  EXPECT_EQ(diagnostics.error_count(), 0u);
}

}  // namespace
}  // namespace xshade::hlsl::sema_test
