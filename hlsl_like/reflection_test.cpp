#include "hlsl_like/reflection.h"

#include <map>

#include <gtest/gtest.h>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

std::unique_ptr<Module> compile(const std::string& source, std::vector<std::string> keywords = {}) {
  CompileOptions options;
  options.keywords = std::move(keywords);
  return compile_text("test.hlsl", source, options);
}

using Strings = std::vector<std::string>;

Strings errors(const Module& module) {
  Strings out;
  for (const Diagnostic& d : module.diagnostics.diagnostics())
    if (d.severity == Severity::Error) out.push_back(d.to_string());
  return out;
}

const ConstantBufferMember& member(const ConstantBuffer& buffer, const std::string& name) {
  for (const ConstantBufferMember& m : buffer.members)
    if (m.name == name) return m;
  throw std::runtime_error("no member " + name);
}

constexpr const char* kMaterial = R"(
#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ USE_RAMP
#pragma shader_feature SHADOW_TEX

struct appdata { float4 vertex : POSITION; float3 normal : NORMAL; float2 uv : TEXCOORD0; };
struct v2f { float4 pos : SV_Position; float2 uv : TEXCOORD0; float3 normal : TEXCOORD1; };

cbuffer PerObject : register(b2) {
  float4x4 _ObjectToClip;
  float _Scale;
  float3 _Offset;    // packs after _Scale: offset 68, which std140 cannot hold
};
float4 _Color <string UIName = "Base colour";> = float4(1, 0.5, 0.25, 1);
float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
Texture2D _MainTex;
SamplerState sampler_MainTex;
Texture2D _Unused;
sampler2D _Ramp : register(s3);

v2f vert(appdata v) {
  v2f o;
  o.pos = mul(_ObjectToClip, v.vertex * _Scale + float4(_Offset, 0));
  o.uv = v.uv;
  o.normal = v.normal;
  return o;
}

float4 frag(v2f i) : SV_Target {
  float4 albedo = _MainTex.Sample(sampler_MainTex, i.uv) * _Color;
  return albedo * tex2D(_Ramp, i.uv) * _Metallic;
}
)";

TEST(Reflection, ConstantBuffersFollowHlslPacking) {
  auto module = compile(kMaterial);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  const ConstantBuffer* per_object = r.find_constant_buffer("PerObject");
  ASSERT_NE(per_object, nullptr);
  EXPECT_EQ(per_object->binding, 2u);
  EXPECT_EQ(member(*per_object, "_ObjectToClip").offset, 0u);
  EXPECT_EQ(member(*per_object, "_ObjectToClip").size, 64u);
  EXPECT_EQ(member(*per_object, "_Scale").offset, 64u);
  const ConstantBufferMember& offset = member(*per_object, "_Offset");
  EXPECT_EQ(offset.offset, 68u);  // fits the rest of _Scale's register
  EXPECT_TRUE(offset.split_into_scalars);
  EXPECT_EQ(per_object->size, 80u);

  const ConstantBuffer* globals = r.find_constant_buffer(kGlobalsBufferName);
  ASSERT_NE(globals, nullptr);
  EXPECT_EQ(globals->binding, 0u);  // the lowest free b register
  EXPECT_EQ(member(*globals, "_Color").offset, 0u);
  EXPECT_EQ(member(*globals, "_Metallic").offset, 16u);
  EXPECT_EQ(globals->size, 32u);
}

TEST(Reflection, BindingsUseRegistersThenTheLowestFreeSlotForUsedResources) {
  auto module = compile(kMaterial);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  ASSERT_EQ(r.textures.size(), 3u);
  // sampler2D _Ramp : register(s3) lands in the texture range, as glslang puts it.
  EXPECT_EQ(r.textures[2].name, "_Ramp");
  EXPECT_EQ(r.textures[2].kind, TextureKind::Sampler);
  EXPECT_EQ(r.textures[2].binding, kTextureBindingBase + 3);
  EXPECT_EQ(r.textures[0].name, "_MainTex");
  EXPECT_EQ(r.textures[0].binding, kTextureBindingBase + 0);
  EXPECT_EQ(r.textures[0].sampler, "sampler_MainTex");
  ASSERT_TRUE(r.textures[0].sampler_binding.has_value());
  EXPECT_EQ(*r.textures[0].sampler_binding, kSamplerBindingBase + 0);
  // Unused: numbered after the used ones.
  EXPECT_EQ(r.textures[1].name, "_Unused");
  EXPECT_EQ(r.textures[1].binding, kTextureBindingBase + 1);
  EXPECT_FALSE(r.textures[1].sampler_binding.has_value());
}

TEST(Reflection, StageInterfacesHaveFixedLocations) {
  auto module = compile(kMaterial);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  ASSERT_EQ(r.vertex_inputs.size(), 3u);
  EXPECT_EQ(r.vertex_inputs[0].semantic, "POSITION0");
  EXPECT_EQ(r.vertex_inputs[0].location, 0u);
  EXPECT_EQ(r.vertex_inputs[1].semantic, "NORMAL0");
  EXPECT_EQ(r.vertex_inputs[1].location, 1u);
  EXPECT_EQ(r.vertex_inputs[2].semantic, "TEXCOORD0");
  EXPECT_EQ(r.vertex_inputs[2].location, 3u);
  ASSERT_EQ(r.varyings.size(), 2u);  // SV_Position is not a varying
  EXPECT_EQ(r.varyings[0].semantic, "TEXCOORD0");
  EXPECT_EQ(r.varyings[0].location, 0u);
  EXPECT_EQ(r.varyings[1].location, 1u);
  ASSERT_EQ(r.fragment_outputs.size(), 1u);
  EXPECT_EQ(r.fragment_outputs[0].semantic, "SV_Target0");
}

TEST(Reflection, StructsNestedInStageStructsAreFlattened) {
  // HLSL flattens a struct field of a stage struct into its fields; their semantics are the
  // stage variables, at the fixed locations of reflection.h (NORMAL 1, TEXCOORD0 3 in the vertex
  // format; TEXCOORDn at n among the varyings).
  auto module = compile(R"(
#pragma vertex vert
#pragma fragment frag
struct Surface { float3 normal : NORMAL; float2 uv : TEXCOORD0; };
struct appdata { float4 vertex : POSITION; Surface surface; };
struct Interp { float2 uv : TEXCOORD0; nointerpolation float3 normal : TEXCOORD1; };
struct v2f { float4 pos : SV_Position; Interp data; };
v2f vert(appdata v) { v2f o; o.pos = v.vertex; o.data.uv = v.surface.uv; o.data.normal = v.surface.normal; return o; }
float4 frag(v2f i) : SV_Target { return float4(i.data.normal * i.data.uv.x, 1); }
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  ASSERT_EQ(r.vertex_inputs.size(), 3u);
  EXPECT_EQ(r.vertex_inputs[0].semantic, "POSITION0");
  EXPECT_EQ(r.vertex_inputs[0].location, 0u);
  EXPECT_EQ(r.vertex_inputs[1].semantic, "NORMAL0");
  EXPECT_EQ(r.vertex_inputs[1].location, 1u);
  EXPECT_EQ(r.vertex_inputs[1].type, Type::vector(ScalarType::Float, 3));
  EXPECT_EQ(r.vertex_inputs[2].semantic, "TEXCOORD0");
  EXPECT_EQ(r.vertex_inputs[2].location, 3u);
  ASSERT_EQ(r.varyings.size(), 2u);
  EXPECT_EQ(r.varyings[0].semantic, "TEXCOORD0");
  EXPECT_EQ(r.varyings[0].location, 0u);
  EXPECT_EQ(r.varyings[1].semantic, "TEXCOORD1");
  EXPECT_EQ(r.varyings[1].location, 1u);
  EXPECT_EQ(r.varyings[1].interpolation, Interpolation::NoInterpolation);
}

// `float3 light[2] : TEXCOORD2` takes locations 2 and 3, so the TEXCOORD3 after it cannot sit at
// 3 (GLSL rejects the overlap): it and what follows move up as far as needed, in semantic order.
TEST(Reflection, AVaryingAfterAnArrayMovesPastTheLocationsItTakes) {
  auto module = compile(R"(
#pragma vertex vert
#pragma fragment frag
struct v2f {
  float4 pos : SV_Position;
  float4 color : TEXCOORD0;
  float3 light[2] : TEXCOORD2;
  float3 view : TEXCOORD3;
  float intensity : TEXCOORD4;
  float2 offsets[3] : TEXCOORD6;
  float4 tint : COLOR0;
  float3 normal : NORMAL;
};
v2f vert(float4 p : POSITION) { v2f o = (v2f)0; o.pos = p; return o; }
float4 frag(v2f i) : SV_Target {
  return i.color + float4(i.light[1] + i.view * i.intensity + float3(i.offsets[2], 0) + i.normal, 0) + i.tint;
}
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  std::map<std::string, uint32_t> locations;
  for (const StageVariable& varying : module->reflection.varyings) locations[varying.semantic] = varying.location;
  const std::map<std::string, uint32_t> expected{{"TEXCOORD0", 0}, {"TEXCOORD2", 2}, {"TEXCOORD3", 4}, {"TEXCOORD4", 5},
                                                 {"TEXCOORD6", 6}, {"COLOR0", 9},    {"NORMAL0", 10}};
  EXPECT_EQ(locations, expected);

  // Without a vertex stage the fragment inputs are placed alike.
  auto fullscreen = compile(R"(
#pragma fragment frag
float4 frag(float4 c : TEXCOORD0, float2 offsets[3] : TEXCOORD1, float2 uv : TEXCOORD2) : SV_Target {
  return c + float4(offsets[2] + uv, 0, 0);
}
)");
  ASSERT_TRUE(fullscreen->ok()) << fullscreen->diagnostics.render_all();
  locations.clear();
  for (const StageVariable& varying : fullscreen->reflection.varyings) locations[varying.semantic] = varying.location;
  EXPECT_EQ(locations, (std::map<std::string, uint32_t>{{"TEXCOORD0", 0}, {"TEXCOORD1", 1}, {"TEXCOORD2", 4}}));
}

TEST(Reflection, AFragmentInputNestedInAStructMustBeWritten) {
  // Before nested fields were seen, the unwritten TEXCOORD2 here passed unnoticed.
  auto module = compile(R"(
#pragma vertex vert
#pragma fragment frag
struct Extra { float2 more : TEXCOORD2; };
struct v2f { float4 pos : SV_Position; Extra extra; };
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(v2f i) : SV_Target { return i.extra.more.xyxy; }
)");
  ASSERT_EQ(module->diagnostics.diagnostics().size(), 1u) << module->diagnostics.render_all();
  EXPECT_EQ(module->diagnostics.diagnostics()[0].to_string(),
            "test.hlsl:7:8: error: fragment input 'TEXCOORD2' is not written by the vertex entry point 'vert'");
}

TEST(Reflection, PropertiesCarryTheirAnnotations) {
  auto module = compile(kMaterial);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Property* metallic = nullptr;
  const Property* color = nullptr;
  for (const Property& p : module->reflection.properties) {
    if (p.name == "_Metallic") metallic = &p;
    if (p.name == "_Color") color = &p;
  }
  ASSERT_NE(metallic, nullptr);
  EXPECT_EQ(metallic->display_name, "Metallic");
  EXPECT_EQ(metallic->min, 0.0);
  EXPECT_EQ(metallic->max, 1.0);
  EXPECT_EQ(metallic->default_value, std::vector<double>{0.5});
  ASSERT_NE(color, nullptr);
  EXPECT_EQ(color->display_name, "Base colour");
  EXPECT_EQ(color->default_value, (std::vector<double>{1, 0.5, 0.25, 1}));
}

TEST(Reflection, KeywordSetsAndTheirDefaults) {
  auto plain = compile(kMaterial);
  ASSERT_TRUE(plain->ok()) << plain->diagnostics.render_all();
  ASSERT_EQ(plain->reflection.keyword_sets.size(), 2u);
  EXPECT_EQ(plain->reflection.keyword_sets[1].keywords, (std::vector<std::string>{"_", "SHADOW_TEX"}));
  EXPECT_TRUE(plain->reflection.keyword_sets[1].shader_feature);
  EXPECT_TRUE(plain->reflection.active_keywords.empty());  // both sets default to "_"

  auto ramp = compile(kMaterial, {"USE_RAMP"});
  EXPECT_EQ(ramp->reflection.active_keywords, std::vector<std::string>{"USE_RAMP"});
  auto unknown = compile(kMaterial, {"NOT_DECLARED"});
  EXPECT_NE(unknown->diagnostics.render_all().find("keyword 'NOT_DECLARED' is not declared"), std::string::npos);
}

TEST(Reflection, LayoutsGlslCannotHoldAreErrorsWithAFix) {
  auto module = compile(R"(
#pragma fragment frag
cbuffer Weights { float w[2]; float after; };
float4 frag() : SV_Target { return w[0] + after; }
)");
  EXPECT_FALSE(module->ok());
  EXPECT_NE(module->diagnostics.render_all().find(
                "test.hlsl:3:37: error: 'after' is at offset 20 of constant buffer 'Weights', inside the padding "
                "GLSL gives 'w' (up to 32)"),
            std::string::npos)
      << module->diagnostics.render_all();
}

TEST(Reflection, PackoffsetPlacesMembersAndGlslListsThemByOffset) {
  auto module = compile(
      "#pragma fragment frag\ncbuffer Light : register(b0) {\n"
      "  float3 color : packoffset(c1);\n  float intensity : packoffset(c1.w);\n"
      "  float2 uv_scale : packoffset(c0.z);\n  float after;\n};\n"
      "float4 frag() : SV_Target { return float4(color * intensity, uv_scale.x + after); }\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const ConstantBuffer& buffer = module->reflection.constant_buffers.at(0);
  std::vector<std::pair<std::string, uint32_t>> offsets;
  for (const ConstantBufferMember& member : buffer.members) offsets.push_back({member.name, member.offset});
  // `after` follows the member before it (uv_scale ends at 16: the next register starts at 16,
  // but c1 is taken up to 32, so it goes after what is placed: 32).
  EXPECT_EQ(offsets, (std::vector<std::pair<std::string, uint32_t>>{
                         {"uv_scale", 8}, {"color", 16}, {"intensity", 28}, {"after", 32}}));
  EXPECT_EQ(buffer.size, 48u);
  auto overlap = compile(
      "#pragma fragment frag\ncbuffer C { float4 a : packoffset(c0); float b : packoffset(c0.y); };\n"
      "float4 frag() : SV_Target { return a + b; }\n");
  EXPECT_EQ(errors(*overlap),
            (Strings{"test.hlsl:2:50: error: 'b' at offset 4 of constant buffer 'C' overlaps 'a' (up to 16)"}));
  auto straddle = compile(
      "#pragma fragment frag\ncbuffer C { float3 a : packoffset(c0.z); float4x4 m : packoffset(c1.y); };\n"
      "float4 frag() : SV_Target { return a.x + m[0]; }\n");
  EXPECT_EQ(errors(*straddle),
            (Strings{"test.hlsl:2:24: error: packoffset(c0.z) of 'a' puts its 12 bytes across a 16-byte register",
                     "test.hlsl:2:55: error: packoffset(c1.y) of 'm': arrays, matrices and structs start a register; "
                     "write packoffset(c1)"}));
}

TEST(Reflection, RegisterConflictsAreErrors) {
  auto module = compile(R"(
#pragma fragment frag
Texture2D a : register(t1);
Texture2D b : register(t1);
SamplerState s;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return a.Sample(s, uv) + b.Sample(s, uv); }
)");
  EXPECT_NE(module->diagnostics.render_all().find("register t1 of 'b' is already taken by 'a'"), std::string::npos)
      << module->diagnostics.render_all();
}

// As on Direct3D, an array of N resources takes N registers from its own; the next free one is
// past them all. On Vulkan the array is one binding of N descriptors at its first register's.
TEST(Reflection, AnArrayOfResourcesTakesARegisterPerElement) {
  auto module = compile(R"(
#pragma fragment frag
Texture2D layers[3] : register(t1);
Texture2D after;
SamplerState samplers[2];
SamplerState one;
struct Camera { float4x4 view; };
ConstantBuffer<Camera> cameras[2];
cbuffer Next { float4 tint; };
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return layers[2].Sample(samplers[1], uv) + after.Sample(one, uv) + cameras[1].view[0] + tint;
}
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  ASSERT_EQ(r.textures.size(), 2u);
  EXPECT_EQ(r.textures[0].count, 3u);
  EXPECT_EQ(r.textures[0].binding, kTextureBindingBase + 1);
  EXPECT_EQ(r.textures[1].count, 1u);
  EXPECT_EQ(r.textures[1].binding, kTextureBindingBase + 0);  // t0 is free before the array
  ASSERT_EQ(r.samplers.size(), 2u);
  EXPECT_EQ(r.samplers[0].count, 2u);
  EXPECT_EQ(r.samplers[0].binding, kSamplerBindingBase + 0);
  EXPECT_EQ(r.samplers[1].binding, kSamplerBindingBase + 2);
  ASSERT_EQ(r.constant_buffers.size(), 2u);
  EXPECT_EQ(r.constant_buffers[0].name, "cameras");
  EXPECT_EQ(r.constant_buffers[0].count, 2u);
  EXPECT_EQ(r.constant_buffers[0].size, 64u);  // one element's
  EXPECT_EQ(r.constant_buffers[1].binding, kConstantBufferBindingBase + 2);

  // A register inside an array is taken.
  auto clash = compile(R"(
#pragma fragment frag
Texture2D layers[3] : register(t1);
Texture2D b : register(t3);
SamplerState s;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return layers[0].Sample(s, uv) + b.Sample(s, uv); }
)");
  EXPECT_NE(clash->diagnostics.render_all().find("register t3 of 'b' is already taken by 'layers'"), std::string::npos)
      << clash->diagnostics.render_all();
}

// A read-only buffer is a shader resource view: a t register, which it shares with the textures.
TEST(Reflection, ReadOnlyBuffersTakeTextureRegistersAndTheirPackedStride) {
  auto module = compile(R"(
#pragma fragment frag
struct Light { float3 position; float radius; float4x4 m; half2 extra[3]; };
Texture2D t0 : register(t0);
StructuredBuffer<Light> lights;
ByteAddressBuffer raw : register(t4);
Buffer<float3> normals;
SamplerState s;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return t0.Sample(s, uv) + lights[0].radius + raw.Load(0) + normals[1].x;
}
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Reflection& r = module->reflection;
  ASSERT_EQ(r.buffers.size(), 3u);
  EXPECT_EQ(r.buffers[0].binding, kTextureBindingBase + 1);  // t0 is the texture's
  EXPECT_EQ(r.buffers[0].stride, 4u * (3 + 1 + 16 + 6));     // tightly packed, half as 32 bits
  EXPECT_EQ(r.buffers[1].binding, kTextureBindingBase + 4);
  EXPECT_EQ(r.buffers[1].stride, 4u);
  EXPECT_EQ(r.buffers[2].stride, 12u);

  auto clash = compile(R"(
#pragma fragment frag
Texture2D t : register(t1);
StructuredBuffer<float> b : register(t1);
SamplerState s;
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return t.Sample(s, uv) + b[0]; }
)");
  EXPECT_NE(clash->diagnostics.render_all().find("register t1 of 'b' is already taken by 't'"), std::string::npos)
      << clash->diagnostics.render_all();
}

TEST(Reflection, Dx9SemanticsAreSystemValuesWhereSemaSaysSo) {
  auto module = compile(R"(
#pragma vertex vert
#pragma fragment frag
struct V { float4 pos : POSITION; float2 uv : TEXCOORD0; };
V vert(float4 p : POSITION, float2 uv : TEXCOORD0) { V o; o.pos = p; o.uv = uv; return o; }
float4 frag(V i) : COLOR1 { return float4(i.uv, 0, 1); }
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  ASSERT_EQ(module->reflection.varyings.size(), 1u);  // POSITION out of the vertex shader is the clip position
  EXPECT_EQ(module->reflection.varyings[0].semantic, "TEXCOORD0");
  ASSERT_EQ(module->reflection.fragment_outputs.size(), 1u);
  EXPECT_EQ(module->reflection.fragment_outputs[0].semantic, "SV_Target1");
  EXPECT_EQ(module->reflection.fragment_outputs[0].location, 1u);
}

TEST(Reflection, PreludeMacrosOutliveThePreprocessor) {
  // Tokens from the prelude's macros (fixed4, UNITY_PI) keep their text in the preprocessor.
  auto module = compile("#pragma fragment frag\nfloat4 frag() : SV_Target { fixed4 c = UNITY_PI; return c; }\n");
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
}

TEST(Reflection, SamplersArePairedThroughFunctionParameters) {
  auto module = compile(R"(
#pragma fragment frag
Texture2D tex;
SamplerState ss;
float4 sample_it(Texture2D t, SamplerState s, float2 uv) { return t.Sample(s, uv); }
float4 frag(float2 uv : TEXCOORD0) : SV_Target { return sample_it(tex, ss, uv); }
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  ASSERT_EQ(module->reflection.textures.size(), 1u);
  EXPECT_EQ(module->reflection.textures[0].sampler, "ss");
  ASSERT_TRUE(module->reflection.textures[0].sampler_binding.has_value());
  EXPECT_EQ(*module->reflection.textures[0].sampler_binding, kSamplerBindingBase);
}

TEST(Reflection, JsonHasEverySection) {
  auto module = compile(kMaterial);
  ASSERT_TRUE(module->ok());
  const std::string json = reflection_json(module->reflection);
  for (const char* key : {"\"entry_points\"", "\"vertex_inputs\"", "\"varyings\"", "\"constant_buffers\"",
                          "\"textures\"", "\"samplers\"", "\"properties\"", "\"keywords\"", "\"sampler_binding\": 32"})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST(Reflection, SpecializationConstantsAreListedWithTheirIdsAndTypes) {
  auto module = compile(R"(
#pragma fragment frag
[[vk::constant_id(3)]] const uint STEPS = 2;
[[vk::constant_id(0)]] const float SCALE = 0.5;
static const float PLAIN = 1;
float4 frag() : SV_Target { return SCALE * STEPS * PLAIN; }
)");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const auto& constants = module->reflection.specialization_constants;
  ASSERT_EQ(constants.size(), 2u);
  EXPECT_EQ(constants[0].name, "STEPS");
  EXPECT_EQ(constants[0].id, 3u);
  EXPECT_EQ(constants[0].scalar, ScalarType::Uint);
  EXPECT_EQ(constants[1].name, "SCALE");
  EXPECT_EQ(constants[1].id, 0u);
  const std::string json = reflection_json(module->reflection);
  EXPECT_NE(json.find("\"id\": 3,\n      \"name\": \"STEPS\",\n      \"type\": \"uint\""), std::string::npos) << json;
}

}  // namespace
}  // namespace xshade::hlsl
