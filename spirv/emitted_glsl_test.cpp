// The GLSL emitter's output, compiled: every realistic shader must come out of both flavours as
// GLSL that glslang accepts, the vk flavour as valid SPIR-V (compile_vulkan_glsl runs spirv-val)
// and the gl flavour as OpenGL 4.50 core GLSL.
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <gtest/gtest.h>

#include <memory>
#include <sstream>
#include <string>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"
#include "spirv/glslang_process.h"
#include "spirv/spirv_compiler.h"

namespace xshade::spirv {
namespace {

// The text with line numbers, for failure messages.
std::string numbered(const std::string& text) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) out << number << ": " << line << "\n";
  return out.str();
}

// Compiles (and links, both stages in one program when there are two) OpenGL GLSL with glslang.
// Returns glslang's log of errors and warnings; empty on success.
std::string compile_opengl(const std::string* vertex, const std::string* fragment) {
  ensure_glslang_initialized();
  glslang::TProgram program;
  std::vector<std::unique_ptr<glslang::TShader>> shaders;
  std::string log;
  for (const std::string* text : {vertex, fragment}) {
    if (!text) continue;
    const EShLanguage stage = text == vertex ? EShLangVertex : EShLangFragment;
    auto shader = std::make_unique<glslang::TShader>(stage);
    const char* source = text->c_str();
    shader->setStrings(&source, 1);
    shader->setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientOpenGL, 100);
    shader->setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
    const bool parsed = shader->parse(GetDefaultResources(), 450, ECoreProfile, false, false, EShMsgDefault);
    const std::string info = shader->getInfoLog();
    if (!parsed || info.find("WARNING") != std::string::npos) {  // warnings count: the output must be clean
      log += info;
      continue;
    }
    program.addShader(shader.get());
    shaders.push_back(std::move(shader));
  }
  if (log.empty() && !program.link(EShMsgDefault)) log += program.getInfoLog();
  return log;
}

struct Compiled {
  glsl::EmittedProgram gl;
  glsl::EmittedProgram vk;
};

// Emits both flavours of `source` and compiles every stage; reports failures with the GLSL.
Compiled emit_and_compile(const std::string& name, const std::string& source, hlsl::CompileOptions options = {}) {
  Compiled compiled;
  auto module = hlsl::compile_text(name, source, options);
  std::string diagnostics;
  for (const Diagnostic& d : module->diagnostics.diagnostics()) diagnostics += d.to_string() + "\n";
  EXPECT_TRUE(module->ok()) << diagnostics;
  if (!module->ok()) return compiled;
  for (const glsl::Flavour flavour : {glsl::Flavour::Gl, glsl::Flavour::Vk}) {
    auto program = glsl::emit(*module, {flavour});
    EXPECT_TRUE(program) << name << " (" << glsl::flavour_name(flavour) << "): " << program.error().to_string();
    if (!program) continue;
    const std::string* vertex = program->vertex ? &program->vertex->text : nullptr;
    const std::string* fragment = program->fragment ? &program->fragment->text : nullptr;
    if (flavour == glsl::Flavour::Gl) {
      const std::string log = compile_opengl(vertex, fragment);
      EXPECT_EQ(log, "") << name << " (gl)\n"
                         << (vertex ? numbered(*vertex) : "") << "\n"
                         << (fragment ? numbered(*fragment) : "");
      compiled.gl = *program;
    } else {
      for (const std::string* text : {vertex, fragment}) {
        if (!text) continue;
        const Stage stage = text == vertex ? Stage::Vertex : Stage::Fragment;
        auto spirv = compile_vulkan_glsl(*text, stage, name);
        EXPECT_TRUE(spirv) << name << " (vk)\n" << (spirv ? "" : spirv.error().to_string()) << "\n" << numbered(*text);
        if (spirv && !spirv->warnings.empty()) ADD_FAILURE() << name << ": " << spirv->warnings.front().to_string();
      }
      compiled.vk = *program;
    }
  }
  return compiled;
}

// ---------------------------------------------------------------------------------------------
// A Unity-style PBR material: appdata/v2f structs, constant buffers with matrices (both
// packings), $Globals, Texture2D + SamplerState, sampler2D, helpers with out and inout
// parameters, overloads, loops, ternaries (scalar and vector conditions), matrices.

constexpr const char* kPbrMaterial = R"(#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _NORMALMAP

#define PI 3.14159265359

struct appdata {
  float4 vertex : POSITION;
  float3 normal : NORMAL;
  float4 tangent : TANGENT;
  float2 uv : TEXCOORD0;
  float4 color : COLOR0;
};

struct v2f {
  float4 pos : SV_Position;
  float2 uv : TEXCOORD0;
  float3 worldNormal : TEXCOORD1;
  float3 worldPos : TEXCOORD2;
  float4 worldTangent : TEXCOORD3;
  nointerpolation int id : TEXCOORD4;
  noperspective float2 screen : TEXCOORD5;
  float4 color : COLOR0;
};

cbuffer UnityPerDraw : register(b0) {
  float4x4 unity_ObjectToWorld;
  float4x4 unity_WorldToObject;
};

cbuffer UnityPerFrame : register(b1) {
  row_major float4x4 unity_MatrixVP;
  float3 _WorldSpaceCameraPos;
  float _Time;
  float4 _Weights[4];
};

struct Light {
  float4 direction;
  float4 color;
};

cbuffer Lighting {
  Light _MainLight;
  float _Exposure;
  float3x3 _Rotation;
};

float4 _Color;
float _Metallic;
float _Glossiness;
float2 _Tiling;
half4 _Tint;
float _BumpScale;
float2 _Offset;
bool _UseRamp;

Texture2D _MainTex;
SamplerState sampler_MainTex;
Texture2D _BumpMap;
sampler2D _Ramp;

static const float3 kLuminance = float3(0.2126, 0.7152, 0.0722);
static float3 s_ambient = float3(0.03, 0.03, 0.03) * _Exposure;
static int s_counter;

float3 ObjectToWorldNormal(float3 n) {
  return normalize(mul(n, (float3x3)unity_WorldToObject));
}

half3 tint(half3 c) { return c * _Tint.rgb; }
float3 tint(float3 c, float k) { return c * k; }

void DiffuseAndSpecularFromMetallic(float3 albedo, float metallic, out float3 specColor,
                                    out float oneMinusReflectivity, inout float3 diffuse) {
  specColor = lerp(float3(0.04, 0.04, 0.04), albedo, metallic);
  oneMinusReflectivity = 0.96 * (1 - metallic);
  diffuse *= albedo * oneMinusReflectivity;
}

float D_GGX(float NoH, float a) {
  float a2 = a * a;
  float d = NoH * NoH * (a2 - 1) + 1;
  return a2 / (PI * d * d + 1e-7f);
}

float3 F_Schlick(float3 f0, float LoH) {
  return f0 + (1 - f0) * pow(1 - LoH, 5);
}

float G_CookTorrance(float NoH, float NoV, float NoL, float VoH) {
  return min(1, min(2 * NoH * NoV / VoH, 2 * NoH * NoL / VoH));
}

int bucket(int i, int n) {
  int q = i / n;
  int r = i % n;
  q += r;
  q /= 2;
  return q;
}

float3 SampleNormal(Texture2D map, SamplerState s, float2 uv, float scale) {
  float3 n = map.Sample(s, uv).xyz * 2 - 1;
  n.xy *= scale;
  return normalize(n);
}

v2f vert(appdata v, uint vid : SV_VertexID) {
  v2f o = (v2f)0;
  float4 world = mul(unity_ObjectToWorld, v.vertex);
  o.pos = mul(unity_MatrixVP, world);
  o.uv = v.uv * _Tiling + _Offset;
  o.worldNormal = ObjectToWorldNormal(v.normal);
  o.worldPos = world.xyz;
  o.worldTangent = float4(mul((float3x3)unity_ObjectToWorld, v.tangent.xyz), v.tangent.w);
  o.id = bucket(int(vid), 3);
  o.screen = o.pos.xy / o.pos.w;
  float3x3 tbn = float3x3(v.tangent.xyz, cross(v.normal, v.tangent.xyz) * v.tangent.w, v.normal);
  float3 axis = mul(tbn, float3(0, 0, 1));
  o.color = v.color * (axis.z > 0 ? 1.0 : 0.5);
  o.color.rgb = v.tangent.w > 0 ? o.color.rgb : o.color.bgr;
  return o;
}

float4 frag(v2f i, bool facing : SV_IsFrontFace) : SV_Target {
  float3 n = normalize(i.worldNormal) * (facing ? 1 : -1);
#ifdef _NORMALMAP
  float3 tn = SampleNormal(_BumpMap, sampler_MainTex, i.uv, _BumpScale);
  float3 b = cross(n, i.worldTangent.xyz) * i.worldTangent.w;
  float3x3 tangentToWorld = float3x3(i.worldTangent.xyz, b, n);
  n = normalize(mul(tn, tangentToWorld));
#endif
  float3 v = normalize(_WorldSpaceCameraPos - i.worldPos);
  float3 l = normalize(mul(_Rotation, -_MainLight.direction.xyz));
  float3 h = normalize(l + v);
  float NoL = saturate(dot(n, l));
  float NoV = max(abs(dot(n, v)), 1e-4);
  float NoH = saturate(dot(n, h));
  float VoH = saturate(dot(v, h));
  float LoH = saturate(dot(l, h));

  float4 texel = _MainTex.Sample(sampler_MainTex, i.uv);
  float3 albedo = tint(_Color.rgb * texel.rgb);
  float3 specColor;
  float oneMinusReflectivity;
  float3 diffuse = 1;
  DiffuseAndSpecularFromMetallic(albedo, _Metallic, specColor, oneMinusReflectivity, diffuse);

  float a = max(1 - _Glossiness, 0.002);
  float D = D_GGX(NoH, a);
  float3 F = F_Schlick(specColor, LoH);
  float G = G_CookTorrance(NoH, NoV, NoL, VoH);
  float3 specular = D * F * G * PI / (4 * NoL * NoV + 1e-5);
  float3 color = (diffuse + specular) * _MainLight.color.rgb * NoL + s_ambient * albedo;

  float weight = 0;
  [unroll] for (int k = 0; k < 4; ++k) {
    weight += dot(_Weights[k], float4(1, 1, 1, 1)) * 0.25;
  }
  int steps = 0;
  while (steps < 3 && weight > 0.5) { weight *= 0.5; steps++; }
  do { weight += 0.001; } while (weight < 0);

  if (_UseRamp) {
    color *= tex2D(_Ramp, float2(NoL * 0.5 + 0.5, 0.5)).rgb;
  } else if (i.id == 2) {
    color = lerp(color, dot(color, kLuminance), 0.5);
  } else {
    color = tint(color, 1.0);
  }
  float3 mask = color > 1 ? 1 : color;
  color = (color < 0.0) ? 0.0 : mask;
  bool3 bright = color > 0.8;
  if (any(bright && color < 0.9) || all(!bright)) color *= 0.99;
  float4x4 m = unity_ObjectToWorld * 2;
  m *= unity_WorldToObject;
  color += m[0].xyz * 0.001 + m._m10_m11_m12 * 0.001 + unity_MatrixVP._11 * 0.0;
  s_counter += steps;
  float4 result = float4(color * (1 + weight), texel.a * _Color.a);
  result.rgb *= float3(i.screen * 0.5 + 0.5, 1) * i.color.rgb;
  return result;
}
)";

TEST(EmittedGlsl, PbrMaterialCompilesInBothFlavours) {
  emit_and_compile("pbr.hlsl", kPbrMaterial);
  hlsl::CompileOptions options;
  options.keywords = {"_NORMALMAP"};
  emit_and_compile("pbr_normalmap.hlsl", kPbrMaterial, options);
}

// ---------------------------------------------------------------------------------------------
// A full-screen post effect without a vertex stage: a disk kernel of float2 in a static const
// array, read in a loop.

constexpr const char* kBokehPost = R"(#pragma fragment frag

Texture2D _MainTex;
SamplerState sampler_MainTex;
float4 _MainTex_TexelSize;
float _BokehRadius;

static const int kSampleCount = 16;
static const float2 kDiskKernel[kSampleCount] = {
  float2(0, 0),
  float2(0.54545456, 0), float2(0.16855472, 0.5187581), float2(-0.44128203, 0.3206101),
  float2(-0.44128197, -0.3206102), float2(0.1685548, -0.5187581),
  float2(1, 0), float2(0.809017, 0.58778524), float2(0.30901697, 0.95105654),
  float2(-0.30901703, 0.9510565), float2(-0.80901706, 0.5877852), float2(-1, 0),
  float2(-0.80901694, -0.58778536), float2(-0.30901664, -0.9510566), float2(0.30901712, -0.9510565),
  float2(0.80901694, -0.5877853),
};

float Weigh(float coc, float radius) {
  return saturate((coc - radius + 2) / 2);
}

float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  float3 color = 0;
  float weight = 0;
  [loop] for (int k = 0; k < kSampleCount; k++) {
    float2 o = kDiskKernel[k] * _BokehRadius;
    float radius = length(o);
    o *= _MainTex_TexelSize.xy;
    float4 s = _MainTex.SampleLevel(sampler_MainTex, uv + o, 0);
    float w = Weigh(s.a, radius);
    color += s.rgb * w;
    weight += w;
  }
  color *= 1.0 / max(weight, 1e-5);
  return float4(color, 1);
}
)";

TEST(EmittedGlsl, FragmentOnlyPostEffectCompilesInBothFlavours) {
  Compiled compiled = emit_and_compile("bokeh.hlsl", kBokehPost);
  EXPECT_FALSE(compiled.gl.vertex);
  ASSERT_TRUE(compiled.gl.fragment);
  // The harness's full-screen vertex shader writes uv at location 0.
  EXPECT_NE(compiled.gl.fragment->text.find("layout(location = 0) in vec2 xs_v_TEXCOORD0;"), std::string::npos);
  const std::string vertex = glsl::fullscreen_vertex_shader(glsl::Flavour::Gl);
  EXPECT_EQ(compile_opengl(&vertex, &compiled.gl.fragment->text), "");
}

// ---------------------------------------------------------------------------------------------
// Every intrinsic and texture method at least once.

constexpr const char* kEveryIntrinsic = R"(#pragma fragment frag

float4 _A;
float4 _B;
int4 _I;
uint4 _U;
float4x4 _M;
float3x3 _N;
float2x3 _R;
sampler2D _S;
Texture2D _T;
SamplerState _SS;

float4 frag(float2 uv : TEXCOORD0, float4 pos : SV_Position) : SV_Target {
  float4 a = _A, b = _B;
  float3 x = a.xyz, y = b.xyz;
  float3 r = 0;
  r += abs(x) + acos(saturate(x)) + asin(saturate(y)) + atan(x) + atan2(x, y);
  r += ceil(x) + clamp(x, 0, 1) + cos(x) + cosh(x) + cross(x, y);
  r += ddx(x) + ddy(x) + degrees(x) + radians(x);
  r += distance(x, y) + dot(a, b) + exp(x) + exp2(x);
  r += faceforward(x, y, x.zyx) + floor(x) + fmod(x, y) + fmod(a.w, b.w) + frac(x) + fwidth(x);
  r += isinf(x) ? 1 : 0;
  r += isnan(x) ? 1 : 0;
  r += isfinite(x) ? 1 : 0;
  r += isfinite(a.w) ? 1 : 0;
  r += ldexp(x, y) + length(x) + lerp(x, y, 0.5) + log(abs(x) + 1) + log10(abs(x) + 1) + log2(abs(x) + 1);
  r += mad(x, y, 1) + max(x, y) + min(x, y);
  float3 ip;
  r += modf(x, ip) + ip;
  r += mul(_M, a).xyz + mul(a, _M).xyz + mul(_N, x) + mul(x, _N) + mul(2.0, x) + mul(x, y) + mul(_M, _M)[0].xyz;
  r += mul(_R, x).xyy + mul(float2(1, 2), _R) + mul(_N, _N)._m01_m12_m20;
  r += normalize(x) + pow(abs(x), y) + rcp(x + 2) + reflect(x, y) + refract(normalize(x), normalize(y), 0.66);
  r += round(x) + rsqrt(abs(x) + 1) + saturate(x) + sign(x) + sign(_I.xyz) + sign(_U.xyz) + sin(x) + sinh(x);
  float3 s, c;
  sincos(x, s, c);
  r += s + c;
  sincos(x * 2, s, c);
  r += s + c;
  r += smoothstep(0, 1, x) + sqrt(abs(x)) + step(0.5, x) + tan(x) + tanh(x) + trunc(x);
  r += transpose(_N)[1] + determinant(_N) + fma(x, y, x.zyx);
  r += all(x) ? 1 : 0;
  r += any(_I.xyz) ? 1 : 0;
  r += all(x > 0) && any(y < 0) ? 1 : 0;
  r += asfloat(_U.xyz) + asfloat(asint(x)) + asfloat(asuint(x)) + float3(asint(_U.xyz)) + float3(asuint(_I.xyz));
  r += asfloat(_I.x) + asint(a.w) + asuint(b.w) + asfloat(a.w);
  r += f16tof32(_U.xyz) + f16tof32(_U.x) + float3(f32tof16(x)) + f32tof16(a.w);
  r += float3(countbits(_U.xyz)) + float3(reversebits(_U.xyz)) + countbits(_U.w);
  r += dot(_I.xyz, _I.zyx) + mul(_I.xy, _I.yx) + abs(_I.x) + abs(_U.y);
  clip(a.w);
  clip(x);
  float4 t = tex2D(_S, uv) + tex2Dlod(_S, float4(uv, 0, 1)) + tex2Dbias(_S, float4(uv, 0, -1)) +
             tex2Dgrad(_S, uv, ddx(uv), ddy(uv));
  float4 t4 = float4(uv, 0, 2);
  t += tex2Dlod(_S, t4) + tex2Dbias(_S, t4);
  t += _T.Sample(_SS, uv) + _T.SampleLevel(_SS, uv, 0) + _T.SampleBias(_SS, uv, 0.5) +
       _T.SampleGrad(_SS, uv, ddx(uv), ddy(uv)) + _T.Load(int3(pos.xy, 0));
  int3 texel = int3(pos.xy, 0);
  t += _T.Load(texel);
  uint w, h;
  _T.GetDimensions(w, h);
  float fw, fh;
  _T.GetDimensions(fw, fh);
  uint mw, mh, levels;
  _T.GetDimensions(1, mw, mh, levels);
  r += float3(w, h, fw + fh) + float3(mw, mh, levels);
  return float4(r, 1) + t;
}
)";

TEST(EmittedGlsl, EveryIntrinsicCompilesInBothFlavours) { emit_and_compile("intrinsics.hlsl", kEveryIntrinsic); }

// lit() with each kind of argument HLSL converts to its float parameters.
TEST(EmittedGlsl, LitInEveryFormCompilesInBothFlavours) {
  const Compiled compiled = emit_and_compile("lit.hlsl", R"(#pragma fragment frag
float4 _A;
float4 frag() : SV_Target {
  float1 l = _A.x;
  min16float h = _A.y;
  return lit(_A.x, _A.y, _A.z) + lit(half(_A.x), h, half(_A.z)) + lit(int(_A.x), uint(_A.y), 3) + lit(l, l, l) +
         lit(0.5, 0.25h, 8) + lit(_A.x * 2.0, abs(_A.y), _A.z + 1.0);
}
)");
  ASSERT_TRUE(compiled.gl.fragment);
  EXPECT_NE(compiled.gl.fragment->text.find("vec4 xs_lit(float n_dot_l, float n_dot_h, float m)"), std::string::npos)
      << compiled.gl.fragment->text;
}

// A variable, parameter or global named like a struct, as HLSL allows: the struct takes a GLSL
// name of its own, where glslang would refuse a global beside it.
TEST(EmittedGlsl, VariablesNamedLikeStructsCompileInBothFlavours) {
  const Compiled compiled = emit_and_compile("names.hlsl", R"(#pragma vertex vert
#pragma fragment frag
struct Attributes { float4 pos : POSITION; };
struct Varyings { float4 pos : SV_Position; float4 c : TEXCOORD0; };
struct VertexPositionInputs { float4 positionCS; float3 positionWS; };
struct Params { float4 tint; };
Params Params;
VertexPositionInputs GetVertexPositionInputs(float4 p) {
  VertexPositionInputs o;
  o.positionCS = p;
  o.positionWS = p.xyz;
  return o;
}
float4 shade(Varyings Varyings) { return Varyings.c * Params.tint; }
Varyings vert(Attributes v) {
  VertexPositionInputs Attributes = GetVertexPositionInputs(v.pos);
  Varyings o;
  o.pos = Attributes.positionCS;
  o.c = float4(Attributes.positionWS, 1);
  return o;
}
float4 frag(Varyings Varyings) : SV_Target { Attributes a = (Attributes)0; return shade(Varyings) + a.pos; }
)");
  ASSERT_TRUE(compiled.vk.fragment);
  EXPECT_NE(compiled.vk.fragment->text.find("struct Params_t {"), std::string::npos) << compiled.vk.fragment->text;
}

// ---------------------------------------------------------------------------------------------
// The corners of the mapping: reserved names, overloads that collide in GLSL, default
// arguments, textures as parameters, statics, integer helpers, compound assignments through
// other types, matrix swizzles, several render targets and depth, every interpolation qualifier.

constexpr const char* kCorners = R"(#pragma vertex vert
#pragma fragment main

struct input { float4 position : POSITION; float3 normal : NORMAL; float2 uv : TEXCOORD1; };
struct output {
  float4 position : SV_Position;
  float2 uv : TEXCOORD0;
  nointerpolation uint id : TEXCOORD1;
  noperspective float depth : TEXCOORD2;
  centroid float3 normal : TEXCOORD3;
  sample float4 smooth : TEXCOORD4;
  int4 bits : TEXCOORD5;
};
struct Targets { float4 color : SV_Target0; float4 extra : SV_Target1; float depth : SV_Depth; };
struct filter { float4 mix; float2x2 m; };

cbuffer common : register(b3) {
  float4x4 transform;
  float3x3 rotation;
  float4 flat;
};
float active;
float2 partition;
int4 sample_counts;
Texture2D texture_input;
SamplerState sampler_texture_input : register(s2);
sampler2D mod;

static const filter kFilters[2] = { { 1, 2, 3, 4, 1, 0, 0, 1 }, { float4(5, 6, 7, 8), float2x2(0, 1, 1, 0) } };
static float4 s_scale = flat * 2;
static int s_calls;

float weigh(float x) { return x * 0.5; }
half weigh(half x) { return x * 0.25h; }
float weigh(float x, float k) { return x * k; }

float4 blur(Texture2D t, SamplerState s, float2 uv, float radius = 1) {
  float4 sum = 0;
  for (int i = -2; i <= 2; i++) {
    for (int j = -2, k = 0; j <= 2; j++, k++) {
      sum += t.SampleLevel(s, uv + float2(i, j) * radius * 0.001, 0);
    }
  }
  return sum / 25;
}

float4 ramp(sampler2D s, float x) { return tex2D(s, float2(x, 0.5)); }

int3 integer_math(int3 a, int b) {
  int3 q = a / b;
  int3 r = a % b;
  q /= 2;
  r %= int3(3, 5, 7);
  uint u = uint(b) / 3u;
  return q + r + int(u) + (a << 1) + (a >> 2) + (a & 3) + (a | 4) + (a ^ 5) + ~a;
}

output vert(input v, uint id : SV_VertexID) {
  output o = (output)0;
  o.position = mul(transform, v.position);
  o.uv = v.uv;
  o.id = id % 3;
  o.depth = o.position.z / o.position.w;
  o.normal = mul(rotation, v.normal);
  o.smooth = float4(v.normal, 1);
  o.bits = int4(integer_math(int3(id, id + 1, id + 2), 3), -1);
  return o;
}

void main(output i, bool front : SV_IsFrontFace, out Targets o) {
  float4 screen = i.position;
  s_calls++;
  float4 output_color = blur(texture_input, sampler_texture_input, i.uv) + blur(texture_input, sampler_texture_input, i.uv, 2);
  output_color += ramp(mod, i.uv.x);
  half h = 0.5;
  float w = weigh(i.uv.x) + weigh(h) + weigh(i.uv.y, 2);
  int k = 3;
  k *= 0.5;
  k += i.id;
  float3 n = normalize(i.normal) * (front ? 1 : -1);
  filter f = kFilters[i.id % 2];
  f.m._m01 = 0.5;
  f.m[1] *= 2;
  f.mix.xy = f.m._m00_m11;
  float2 m2 = mul(f.m, partition);
  float4 bits = i.bits;
  bits %= 4;
  bits = bits < 0 ? -bits : bits;
  o.color = output_color * w * s_scale + float4(n, 1) * active + float4(m2, k, i.depth) + f.mix + bits + sample_counts;
  o.extra = i.smooth * (screen.x > 10 && screen.y > 10 ? 1 : 0) + s_calls;
  o.depth = saturate(screen.z + i.depth * 0.001);
  if (o.color.a < 0) discard;
}
)";

TEST(EmittedGlsl, CornersCompileInBothFlavours) { emit_and_compile("corners.hlsl", kCorners); }

// The fragment stage may read fewer components than the vertex stage writes, as in Direct3D:
// both stages declare the vertex stage's type, and the fragment stage truncates where it reads.
constexpr const char* kNarrowerVaryings = R"(#pragma vertex vert
#pragma fragment frag
struct VOut { float4 pos : SV_Position; float4 uv : TEXCOORD0; int4 id : TEXCOORD1; };
VOut vert(float4 p : POSITION, float2 uv : TEXCOORD0) {
  VOut o;
  o.pos = p;
  o.uv = float4(uv, 0, 1);
  o.id = int4(1, 2, 3, 4);
  return o;
}
float4 frag(float2 uv : TEXCOORD0, nointerpolation int id : TEXCOORD1) : SV_Target {
  return float4(uv, id, 1);
}
)";

TEST(EmittedGlsl, NarrowerFragmentInputsLink) {
  Compiled compiled = emit_and_compile("narrow.hlsl", kNarrowerVaryings);
  ASSERT_TRUE(compiled.gl.fragment);
  EXPECT_NE(compiled.gl.fragment->text.find("layout(location = 0) in vec4 xs_v_TEXCOORD0;"), std::string::npos);
  EXPECT_NE(compiled.gl.fragment->text.find("xs_arg0 = xs_v_TEXCOORD0.xy;"), std::string::npos);
  EXPECT_NE(compiled.gl.fragment->text.find("xs_arg1 = xs_v_TEXCOORD1.x;"), std::string::npos);
}

// Every texture shape with every method it has, offsets and DX9 samplers included, in a vertex
// stage (explicit levels only) and a fragment stage: the text real shaders reach (Unity's
// colour-grading LUTs are Texture3D, its reflection probes TextureCube, shadow maps compare).
const char* kEveryTextureMethod = R"(
#pragma vertex vert
#pragma fragment frag
Texture1D t1; Texture1DArray t1a; Texture2D t2; Texture2DArray t2a; Texture3D t3;
TextureCube tc; TextureCubeArray tca; Texture2DMS<float4, 4> tms; Texture2DMSArray<float4> tmsa;
Texture2D<float> depth; TextureCube<float> depth_cube; Texture2DArray<float> depth_array;
Texture2D<uint4> ids; Texture2D<int2> offsets; Texture3D<half3> lut;
SamplerState s; SamplerComparisonState cmp;
static const int2 kOffset = int2(1, -1);

float4 explicit_levels(float3 p) {
  float4 r = t1.SampleLevel(s, p.x, 0) + t1a.SampleLevel(s, p.xy, 1) + t2.SampleLevel(s, p.xy, 0, int2(1, 0));
  r += t2a.SampleLevel(s, p, 0, kOffset) + t3.SampleLevel(s, p, 0, int3(0, 1, 0)) + tc.SampleLevel(s, p, 2);
  r += tca.SampleLevel(s, float4(p, 1), 0) + t2.SampleGrad(s, p.xy, p.xy, p.yx, int2(-1, 0));
  r += tc.SampleGrad(s, p, p, p) + lut.SampleLevel(s, p, 0).rgbb;
  r += t1.Load(int2(3, 0)) + t1a.Load(int3(1, 2, 0), 1) + t2.Load(int3(1, 2, 0)) + t2.Load(int3(1, 2, 0), int2(1, 1));
  r += t2a.Load(int4(1, 2, 3, 0)) + t3.Load(int4(1, 2, 3, 0), int3(1, 0, 0));
  r += tms.Load(int2(1, 2), 3) + tms.Load(int2(1, 2), 0, int2(1, 0)) + tmsa.Load(int3(1, 2, 1), 2);
  r += float4(ids.Load(int3(0, 0, 0))) + float4(offsets.Load(int3(0, 0, 0)), 0, 0) + t2[uint2(4, 5)];
  r += t2.Gather(s, p.xy) + t2.GatherRed(s, p.xy, int2(1, 1)) + t2.GatherGreen(s, p.xy) + t2.GatherBlue(s, p.xy);
  r += t2.GatherAlpha(s, p.xy) + t2a.Gather(s, p) + tc.GatherRed(s, p) + tca.GatherAlpha(s, float4(p, 0));
  r += float4(ids.GatherRed(s, p.xy)) + depth.GatherCmp(cmp, p.xy, 0.5) + depth.GatherCmpRed(cmp, p.xy, 0.5, int2(0, 1));
  r += depth.SampleCmpLevelZero(cmp, p.xy, 0.5) + depth.SampleCmpLevelZero(cmp, p.xy, 0.5, int2(1, 0));
  r += depth_cube.SampleCmpLevelZero(cmp, p, 0.5) + depth_array.SampleCmpLevelZero(cmp, p, 0.5);
  uint w, h, e, l, n;
  float fw, fh, fe, fl;
  t1.GetDimensions(w); t1.GetDimensions(1, w, l); t1a.GetDimensions(w, e); t2.GetDimensions(w, h);
  t2.GetDimensions(0, fw, fh, fl); t2a.GetDimensions(w, h, e); t2a.GetDimensions(1, w, h, e, l);
  t3.GetDimensions(w, h, e); t3.GetDimensions(0, fw, fh, fe, fl); tc.GetDimensions(w, h); tca.GetDimensions(w, h, e);
  tms.GetDimensions(w, h, n); tmsa.GetDimensions(w, h, e, n);
  return r + float4(w + h + e + l + n, fw + fh + fe + fl, 0, 0);
}

float4 vert(float3 p : POSITION) : SV_Position { return explicit_levels(p); }

float4 frag(float4 position : SV_Position) : SV_Target {
  const float3 p = position.xyz;
  float4 r = explicit_levels(p) + t1.Sample(s, p.x) + t2.Sample(s, p.xy, int2(0, 1)) + t2a.Sample(s, p);
  r += t3.Sample(s, p) + tc.Sample(s, p) + tca.Sample(s, float4(p, 2)) + t2.SampleBias(s, p.xy, -1, int2(1, 1));
  r += tc.SampleBias(s, p, 0.5) + depth.SampleCmp(cmp, p.xy, 0.5) + depth.SampleCmp(cmp, p.xy, 0.5, int2(1, 0));
  r += depth_cube.SampleCmp(cmp, p, 0.5) + depth_array.SampleCmp(cmp, p, 0.5);
  r += t2.CalculateLevelOfDetail(s, p.xy) + t3.CalculateLevelOfDetailUnclamped(s, p) + tc.CalculateLevelOfDetail(s, p);
  return r;
}
)";

// The DX9 samplers and their tex* functions, in both stages.
const char* kEveryDx9Sampling = R"(
#pragma vertex vert
#pragma fragment frag
sampler1D d1; sampler2D d2; sampler3D d3; samplerCUBE dc;
float4 explicit_levels(float3 p) {
  float4 r = tex1Dlod(d1, float4(p, 1)) + tex2Dlod(d2, float4(p, 1)) + tex3Dlod(d3, float4(p, 1)) + texCUBElod(dc, float4(p, 1));
  return r + tex1Dgrad(d1, p.x, p.y, p.z) + tex2Dgrad(d2, p.xy, p.xy, p.xy) + tex3Dgrad(d3, p, p, p) + texCUBEgrad(dc, p, p, p);
}
float4 vert(float3 p : POSITION) : SV_Position { return explicit_levels(p); }
float4 frag(float4 position : SV_Position) : SV_Target {
  const float3 p = position.xyz;
  float4 r = explicit_levels(p) + tex1D(d1, p.x) + tex2D(d2, p.xy) + tex2D(d2, p.xy, p.xy, p.xy) + tex3D(d3, p) + texCUBE(dc, p);
  r += tex1Dbias(d1, float4(p, 1)) + tex2Dbias(d2, float4(p, 1)) + tex3Dbias(d3, float4(p, 1)) + texCUBEbias(dc, float4(p, 1));
  return r + tex1Dproj(d1, float4(p, 2)) + tex2Dproj(d2, float4(p, 2)) + tex3Dproj(d3, float4(p, 2)) + texCUBEproj(dc, float4(p, 2));
}
)";

TEST(EmittedGlsl, EveryDx9SamplingFunctionCompilesInBothFlavours) {
  Compiled compiled = emit_and_compile("dx9.hlsl", kEveryDx9Sampling);
  ASSERT_TRUE(compiled.vk.fragment);
  EXPECT_NE(compiled.vk.fragment->text.find("uniform samplerCube dc;"), std::string::npos);
}

TEST(EmittedGlsl, EveryTextureShapeAndMethodCompilesInBothFlavours) {
  Compiled compiled = emit_and_compile("textures.hlsl", kEveryTextureMethod);
  ASSERT_TRUE(compiled.gl.fragment && compiled.vk.fragment);
  // OpenGL declares the compared textures as shadow samplers; Vulkan compares through the sampler.
  EXPECT_NE(compiled.gl.fragment->text.find("uniform sampler2DShadow depth;"), std::string::npos);
  EXPECT_NE(compiled.gl.fragment->text.find("uniform samplerCubeShadow depth_cube;"), std::string::npos);
  EXPECT_NE(compiled.vk.fragment->text.find("uniform texture2D depth;"), std::string::npos);
  EXPECT_NE(compiled.vk.fragment->text.find("uniform samplerShadow cmp;"), std::string::npos);
  EXPECT_NE(compiled.vk.fragment->text.find("uniform utexture2D ids;"), std::string::npos);
  EXPECT_NE(compiled.gl.fragment->text.find("uniform sampler2DMS tms;"), std::string::npos);
}

// A texture only the fragment stage compares is one uniform of one type in the linked program:
// where the vertex stage declares it too, it is a shadow sampler there as well (OpenGL refuses to
// link a uniform of two types), as Unity's screen-space shadows have it.
TEST(EmittedGlsl, ATextureOneStageComparesIsAShadowSamplerInBothStages) {
  Compiled compiled = emit_and_compile("shadow.hlsl", R"(
#pragma vertex vert
#pragma fragment frag
Texture2D shadow_map; SamplerComparisonState cmp;
float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
float4 frag(float4 position : SV_Position) : SV_Target { return shadow_map.SampleCmpLevelZero(cmp, position.xy, 0.5); }
)");
  ASSERT_TRUE(compiled.gl.vertex && compiled.gl.fragment);
  EXPECT_NE(compiled.gl.fragment->text.find("uniform sampler2DShadow shadow_map;"), std::string::npos);
  const std::string& vertex = compiled.gl.vertex->text;
  EXPECT_TRUE(vertex.find("shadow_map") == std::string::npos ||
              vertex.find("uniform sampler2DShadow shadow_map;") != std::string::npos)
      << vertex;
}

// FXAA keeps a texture and its sampler in a struct; a local of it names the globals.
const char* kStructOfResources = R"(
#pragma fragment frag
struct FxaaTex { SamplerState smpl; Texture2D tex; };
struct Pair { FxaaTex a; FxaaTex b; };
Texture2D _MainTex; SamplerState sampler_MainTex; Texture2D _Other; SamplerState sampler_Other;
float4 fetch(FxaaTex t, float2 uv) { return t.tex.SampleLevel(t.smpl, uv, 0.0) + t.tex.GatherGreen(t.smpl, uv, int2(1, 0)); }
float4 both(Pair p, float2 uv) { return fetch(p.a, uv) + fetch(p.b, uv); }
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  FxaaTex main_tex;
  main_tex.tex = _MainTex;
  main_tex.smpl = sampler_MainTex;
  Texture2D alias = main_tex.tex;
  Pair pair;
  pair.a = main_tex;
  pair.b.tex = _Other;
  pair.b.smpl = sampler_Other;
  return both(pair, uv) + alias.Sample(main_tex.smpl, uv);
}
)";

TEST(EmittedGlsl, StructsOfResourcesAreFlattenedToTheGlobalsTheyName) {
  Compiled compiled = emit_and_compile("fxaa.hlsl", kStructOfResources);
  ASSERT_TRUE(compiled.gl.fragment && compiled.vk.fragment);
  const std::string& vk = compiled.vk.fragment->text;
  EXPECT_EQ(vk.find("struct FxaaTex"), std::string::npos);
  EXPECT_NE(vk.find("vec4 fetch(sampler t_smpl, texture2D t_tex, vec2 uv)"), std::string::npos) << vk;
  EXPECT_NE(vk.find("vec4 both(sampler p_a_smpl, texture2D p_a_tex, sampler p_b_smpl, texture2D p_b_tex, vec2 uv)"),
            std::string::npos)
      << vk;
  EXPECT_NE(vk.find("both(sampler_MainTex, _MainTex, sampler_Other, _Other, uv) + texture(sampler2D(_MainTex, "
                    "sampler_MainTex), uv)"),
            std::string::npos)
      << vk;
  const std::string& gl = compiled.gl.fragment->text;
  EXPECT_NE(gl.find("vec4 fetch(sampler2D t_tex, vec2 uv)"), std::string::npos) << gl;
}

// ---------------------------------------------------------------------------------------------
// Arrays of resources (one binding of N descriptors on vk, N consecutive bindings on gl) and clip
// and cull distances (packed into GLSL's built-in arrays in the order of their index).
constexpr const char* kArraysAndDistances = R"(
#pragma vertex vert
#pragma fragment frag
Texture2D layers[3] : register(t1);
SamplerState samplers[2];
struct Camera { float4x4 view; float4 tint; };
ConstantBuffer<Camera> cameras[2];
cbuffer Select { int layer; int camera; };
struct V {
  float4 pos : SV_Position;
  float clip_far : SV_ClipDistance1;
  float2 clip_near : SV_ClipDistance0;
  float cull : SV_CullDistance0;
  float2 uv : TEXCOORD0;
};
V vert(float3 p : POSITION, float2 uv : TEXCOORD0) {
  V v;
  v.pos = mul(cameras[camera].view, float4(p, 1));
  v.clip_near = float2(p.x, p.y);
  v.clip_far = p.z;
  v.cull = 1;
  v.uv = uv;
  return v;
}
float4 frag(V v) : SV_Target {
  return layers[layer].Sample(samplers[1], v.uv) * cameras[camera].tint + v.clip_near.y + v.clip_far;
}
)";

TEST(EmittedGlsl, ArraysOfResourcesAndClipDistancesCompileInBothFlavours) {
  const Compiled compiled = emit_and_compile("arrays.hlsl", kArraysAndDistances);
  ASSERT_TRUE(compiled.gl.vertex && compiled.vk.fragment);
  const std::string gl = compiled.gl.vertex->text + compiled.gl.fragment->text;
  const std::string vk = compiled.vk.vertex->text + compiled.vk.fragment->text;
  EXPECT_NE(gl.find("layout(binding = 17) uniform sampler2D layers[3];"), std::string::npos) << gl;
  EXPECT_NE(vk.find("layout(set = 0, binding = 17) uniform texture2D layers[3];"), std::string::npos) << vk;
  EXPECT_NE(vk.find("uniform sampler samplers[2];"), std::string::npos) << vk;
  EXPECT_NE(vk.find("texture(sampler2D(layers[layer], samplers[1]), v.uv)"), std::string::npos) << vk;
  EXPECT_NE(gl.find("} xs_cb_cameras[2];"), std::string::npos) << gl;
  // SV_ClipDistance0 (two components) first, then SV_ClipDistance1, whatever the struct's order.
  EXPECT_NE(gl.find("out float gl_ClipDistance[3];"), std::string::npos) << gl;
  EXPECT_NE(gl.find("gl_ClipDistance[1] = float(xs_result.clip_near.y);"), std::string::npos) << gl;
  EXPECT_NE(gl.find("gl_ClipDistance[2] = float(xs_result.clip_far);"), std::string::npos) << gl;
  EXPECT_NE(gl.find("out float gl_CullDistance[1];"), std::string::npos) << gl;
  EXPECT_NE(vk.find("in float gl_ClipDistance[3];"), std::string::npos) << vk;
}

// Subpass inputs: Vulkan's input attachments on vk; on gl the texture at the binding read at the
// fragment's pixel.
constexpr const char* kSubpassInputs = R"(
#pragma fragment frag
[[vk::input_attachment_index(0)]] [[vk::binding(1)]] SubpassInput albedo;
[[vk::input_attachment_index(1)]] SubpassInputMS<int4> samples;
float4 frag() : SV_Target { return albedo.SubpassLoad() + samples.SubpassLoad(2).x; }
)";

TEST(EmittedGlsl, SubpassInputsCompileInBothFlavours) {
  const Compiled compiled = emit_and_compile("subpass.hlsl", kSubpassInputs);
  ASSERT_TRUE(compiled.gl.fragment && compiled.vk.fragment);
  const std::string& gl = compiled.gl.fragment->text;
  const std::string& vk = compiled.vk.fragment->text;
  EXPECT_NE(vk.find("layout(input_attachment_index = 0, set = 0, binding = 1) uniform subpassInput albedo;"),
            std::string::npos)
      << vk;
  EXPECT_NE(vk.find("subpassLoad(albedo) + float(subpassLoad(samples, 2).x)"), std::string::npos) << vk;
  EXPECT_NE(gl.find("layout(binding = 1) uniform sampler2D albedo;"), std::string::npos) << gl;
  EXPECT_NE(gl.find("texelFetch(samples, ivec2(gl_FragCoord.xy), 2)"), std::string::npos) << gl;
}

// Read-only buffers: storage buffers of words on both flavours, each element assembled as
// Direct3D packs it (a float3 then a float share 16 bytes; a matrix column by column).
constexpr const char* kReadOnlyBuffers = R"(
#pragma fragment frag
struct Light { float3 position; float radius; float2x2 m; int kind; };
StructuredBuffer<Light> lights : register(t2);
ByteAddressBuffer raw;
Buffer<float4> colors;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  uint count, stride, bytes;
  lights.GetDimensions(count, stride);
  raw.GetDimensions(bytes);
  Light l = lights[1];
  uint3 w = raw.Load3(12);
  return float4(l.position, l.radius) + l.m[1].y + float(w.z + raw.Load(4)) + colors.Load(2) + count + stride + bytes;
}
)";

TEST(EmittedGlsl, ReadOnlyBuffersCompileInBothFlavours) {
  const Compiled compiled = emit_and_compile("buffers.hlsl", kReadOnlyBuffers);
  ASSERT_TRUE(compiled.gl.fragment && compiled.vk.fragment);
  const std::string& gl = compiled.gl.fragment->text;
  const std::string& vk = compiled.vk.fragment->text;
  EXPECT_NE(gl.find("layout(std430, binding = 18) readonly buffer xs_buffer_lights { uint xs_words[]; } lights;"),
            std::string::npos)
      << gl;
  EXPECT_NE(vk.find("layout(std430, set = 0, binding = 18) readonly buffer xs_buffer_lights"), std::string::npos) << vk;
  // Nine words an element: position 0-2, radius 3, m (column-major) 4-7, kind 8; m[1].y is
  // element (1, 1), word 4 + 1 * 2 + 1.
  EXPECT_NE(gl.find("uint base = index * 9u;"), std::string::npos) << gl;
  EXPECT_NE(gl.find("mat2(uintBitsToFloat(xs_word_lights(base + 4u)), uintBitsToFloat(xs_word_lights(base + 6u)), "
                    "uintBitsToFloat(xs_word_lights(base + 5u)), uintBitsToFloat(xs_word_lights(base + 7u)))"),
            std::string::npos)
      << gl;
  // A word past the bound buffer's end reads 0, as Direct3D reads past a view's end.
  EXPECT_NE(gl.find("return at < uint(lights.xs_words.length()) ? lights.xs_words[at] : 0u;"), std::string::npos) << gl;
  EXPECT_NE(gl.find("uint base = address >> 2u;"), std::string::npos) << gl;
  EXPECT_NE(gl.find("(count = ((uint(lights.xs_words.length()) * 4u) / 36u), stride = 36u)"), std::string::npos) << gl;
}

// DXC's printf for Vulkan: GL_EXT_debug_printf on vk; OpenGL has no debug printf, so the
// statement is left out there.
constexpr const char* kDebugPrintf = R"(
#pragma fragment frag
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  printf("uv = %v2f, %d", uv, 7);
  return float4(uv, 0, 1);
}
)";

TEST(EmittedGlsl, DebugPrintfIsVulkansAndLeftOutOnOpenGl) {
  const Compiled compiled = emit_and_compile("printf.hlsl", kDebugPrintf);
  ASSERT_TRUE(compiled.gl.fragment && compiled.vk.fragment);
  const std::string& vk = compiled.vk.fragment->text;
  EXPECT_NE(vk.find("#extension GL_EXT_debug_printf : require"), std::string::npos) << vk;
  EXPECT_NE(vk.find("debugPrintfEXT(\"uv = %v2f, %d\", uv, 7);"), std::string::npos) << vk;
  EXPECT_EQ(compiled.gl.fragment->text.find("debugPrintfEXT"), std::string::npos) << compiled.gl.fragment->text;
}

}  // namespace
}  // namespace xshade::spirv
