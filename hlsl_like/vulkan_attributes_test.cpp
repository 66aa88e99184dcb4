// Vulkan's attributes as DXC's SPIR-V back end reads them ([[vk::location]], [[vk::binding]],
// [[vk::push_constant]], [[vk::constant_id]], [[vk::builtin]]) and HLSL's user-defined semantics:
// what the parser accepts and refuses, and where reflection puts each declaration.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

std::unique_ptr<Module> compiled_with_attributes(const std::string& source) {
  return compile_text("vk.hlsl", source, {});
}

std::vector<std::string> attribute_errors_of(const std::string& source) {
  std::vector<std::string> errors;
  const std::unique_ptr<Module> module = compiled_with_attributes(source);
  for (const Diagnostic& d : module->diagnostics.diagnostics())
    if (d.severity == Severity::Error) errors.push_back(d.to_string());
  return errors;
}

const StageVariable* variable_named(const std::vector<StageVariable>& variables, const std::string& semantic) {
  for (const StageVariable& variable : variables)
    if (variable.semantic == semantic) return &variable;
  return nullptr;
}

constexpr const char* kVulkanVertex = R"(
#pragma vertex main
struct VSInput {
  [[vk::location(0)]] float3 Pos : POSITION0;
  [[vk::location(1)]] float3 Color : COLOR0;
  float3 Bitangent : BITANGENT;
};
struct VSOutput {
  float4 Pos : SV_POSITION;
  [[vk::location(0)]] float3 Color : COLOR0;
  float4 Prev : PREVPOSITION;
  float2 Extra : TEXCOORD9;
  [[vk::builtin("PointSize")]] float Size : PSIZE;
};
VSOutput main(VSInput input) {
  VSOutput o;
  o.Pos = float4(input.Pos, 1);
  o.Color = input.Color + input.Bitangent;
  o.Prev = o.Pos;
  o.Extra = input.Pos.xy;
  o.Size = 2;
  return o;
}
)";

TEST(VulkanAttributes, LocationsAreTheSourcesAndOtherSemanticsTakeTheNextFree) {
  auto module = compiled_with_attributes(kVulkanVertex);
  ASSERT_TRUE(module->ok()) << module->diagnostics.errors_with_excerpts().size();
  const Reflection& r = module->reflection;
  ASSERT_NE(variable_named(r.vertex_inputs, "COLOR0"), nullptr);
  EXPECT_EQ(variable_named(r.vertex_inputs, "POSITION0")->location, 0u);
  EXPECT_EQ(variable_named(r.vertex_inputs, "COLOR0")->location, 1u);       // not the vertex format's 5
  EXPECT_EQ(variable_named(r.vertex_inputs, "BITANGENT0")->location, 13u);  // a user semantic, after the format's
  EXPECT_EQ(variable_named(r.varyings, "COLOR0")->location, 0u);
  EXPECT_EQ(variable_named(r.varyings, "PREVPOSITION0")->location, 14u);
  EXPECT_EQ(variable_named(r.varyings, "TEXCOORD9")->location, 15u);
  // The point size is GLSL's built-in, not a varying.
  EXPECT_EQ(variable_named(r.varyings, "PSIZE0"), nullptr);
}

TEST(VulkanAttributes, AMatrixVaryingTakesALocationPerRow) {
  auto module = compiled_with_attributes(R"(
#pragma vertex v
struct O { float4 p : SV_Position; float4x4 m : MATRIX0; float3x4 n : TEXCOORD0; float4 after : NEXT; };
O v(float4 p : POSITION) { O o = (O)0; o.p = p; return o; }
)");
  ASSERT_TRUE(module->ok());
  const Reflection& r = module->reflection;
  EXPECT_EQ(variable_named(r.varyings, "TEXCOORD0")->location, 0u);  // 0 to 2
  EXPECT_EQ(variable_named(r.varyings, "MATRIX0")->location, 14u);   // 14 to 17
  EXPECT_EQ(variable_named(r.varyings, "NEXT0")->location, 18u);
}

// DX9's POSITION is the clip position only as a float4; a float POSITION0 or a POSITION1 is a
// varying, as DXC reads them (Vulkan samples pass a particle's gradient in one).
TEST(VulkanAttributes, APositionThatIsNoFloat4IsAVarying) {
  auto module = compiled_with_attributes(R"(
#pragma fragment f
float4 f(float4 p : SV_POSITION, [[vk::location(0)]] float gradient : POSITION0,
         [[vk::location(1)]] float2 centre : POSITION1) : SV_Target { return gradient + centre.x; }
)");
  ASSERT_TRUE(module->ok());
  EXPECT_EQ(variable_named(module->reflection.varyings, "POSITION0")->location, 0u);
  EXPECT_EQ(variable_named(module->reflection.varyings, "POSITION1")->location, 1u);
  EXPECT_FALSE(
      compiled_with_attributes("#pragma vertex v\nfloat v(float4 p : POSITION) : POSITION { return p.x; }\n")->ok());
}

TEST(VulkanAttributes, BindingsAndSetsAreTheSourcesAndNothingElseLandsOnThem) {
  auto module = compiled_with_attributes(R"(
#pragma fragment main
struct UBO { float4 tint; };
[[vk::binding(2, 1)]] ConstantBuffer<UBO> ubo : register(b0);
[[vk::binding(1)]] Texture2D colorMap : register(t1);
[[vk::binding(1)]] SamplerState colorSampler : register(s1);
float4 other;  // $Globals, which would take binding 0 and must not take 1
struct Push { float4 scale; };
[[vk::push_constant]] Push push;
float4 main(float2 uv : TEXCOORD0) : SV_Target { return colorMap.Sample(colorSampler, uv) * ubo.tint * push.scale + other; }
)");
  ASSERT_TRUE(module->ok());
  const Reflection& r = module->reflection;
  const ConstantBuffer* ubo = r.find_constant_buffer("ubo");
  ASSERT_NE(ubo, nullptr);
  EXPECT_EQ(ubo->binding, 2u);
  EXPECT_EQ(ubo->set, 1u);
  ASSERT_EQ(r.textures.size(), 1u);
  EXPECT_EQ(r.textures[0].binding, 1u);
  EXPECT_EQ(r.textures[0].sampler_binding, 1u);  // one combined image sampler serves both
  const ConstantBuffer* push = r.find_constant_buffer("push");
  ASSERT_NE(push, nullptr);
  EXPECT_TRUE(push->push_constant);
  for (const ConstantBuffer& buffer : r.constant_buffers) {
    if (buffer.name != "ubo") {
      EXPECT_NE(buffer.binding, 1u) << buffer.name;
    }
  }
}

TEST(VulkanAttributes, MisuseIsAnErrorThatSaysWhat) {
  EXPECT_EQ(
      attribute_errors_of(
          "[[vk::binding(0)]] Texture2D a; [[vk::binding(0)]] Texture2D b;\n"
          "SamplerState s;\n#pragma fragment f\n"
          "float4 f(float2 uv : TEXCOORD0) : SV_Target { return a.Sample(s, uv) + b.Sample(s, uv); }\n"),
      (std::vector<std::string>{"vk.hlsl:1:35: error: 'b' is at binding 0 of set 0, which 'a' already takes; give "
                                "each resource a binding of its own"}));
  const std::vector<std::string> ext = attribute_errors_of("[[vk::ext_capability(5009)]] float x;\n");
  ASSERT_FALSE(ext.empty());
  EXPECT_NE(ext[0].find("vk.hlsl:1:3: error: SPIR-V extension instructions and types (vk::ext_capability)"),
            std::string::npos)
      << ext[0];
  // A combined image sampler needs its partner at its binding; an array's vk::offset its 16 bytes.
  EXPECT_EQ(
      attribute_errors_of("[[vk::combinedImageSampler]] [[vk::binding(2)]] Texture2D t;\n"
                          "[[vk::combinedImageSampler]] [[vk::binding(3)]] SamplerState s;\n#pragma fragment f\n"
                          "float4 f(float2 uv : TEXCOORD0) : SV_Target { return t.Sample(s, uv); }\n"),
      (std::vector<std::string>{"vk.hlsl:1:3: error: vk::combinedImageSampler on 't' needs a SamplerState with it "
                                "at the same vk::binding: the two are one combined image sampler there",
                                "vk.hlsl:2:3: error: vk::combinedImageSampler on 's' needs a texture with it at the "
                                "same vk::binding: the two are one combined image sampler there"}));
  EXPECT_EQ(
      attribute_errors_of("cbuffer C { float a; [[vk::offset(20)]] float4 b[2]; };\n#pragma fragment f\n"
                          "float4 f() : SV_Target { return b[0] * a; }\n"),
      (std::vector<std::string>{"vk.hlsl:1:48: error: vk::offset(20) of 'b': an array, matrix or struct starts at "
                                "a multiple of 16 bytes in the std140 block the targets read"}));
  const std::vector<std::string> unknown = attribute_errors_of("[[vk::locaton(0)]] float x;\n");
  ASSERT_FALSE(unknown.empty());
  EXPECT_NE(unknown[0].find("unknown Vulkan attribute 'vk::locaton'"), std::string::npos) << unknown[0];
  const std::vector<std::string> arguments = attribute_errors_of("[[vk::binding]] Texture2D t;\n");
  ASSERT_FALSE(arguments.empty());
  EXPECT_NE(arguments[0].find("vk::binding takes 1 or 2 integers"), std::string::npos) << arguments[0];
  const std::vector<std::string> constant = attribute_errors_of("[[vk::constant_id(3)]] float4 v;\n");
  ASSERT_FALSE(constant.empty());
  EXPECT_NE(constant[0].find("vk::constant_id applies to a `const` scalar with an initializer"), std::string::npos)
      << constant[0];
  const std::vector<std::string> overlap = attribute_errors_of(
      "#pragma vertex v\nstruct O { float4 p : SV_Position; [[vk::location(2)]] float4 a[2] : TEXCOORD0;\n"
      "[[vk::location(3)]] float4 b : TEXCOORD5; };\n"
      "O v(float4 p : POSITION) { O o = (O)0; o.p = p; return o; }\n");
  ASSERT_FALSE(overlap.empty());
  EXPECT_NE(overlap[0].find("varying 'TEXCOORD5' at [[vk::location(3)]] overlaps 'TEXCOORD0'"), std::string::npos)
      << overlap[0];
}

TEST(VulkanAttributes, ASubpassInputNamesItsInputAttachmentAndNothingElseHasOne) {
  EXPECT_EQ(attribute_errors_of("#pragma fragment f\n[[vk::input_attachment_index(2)]] SubpassInput<float2> g;\n"
                                "[[vk::input_attachment_index(3)]] SubpassInputMS ms;\n"
                                "float4 f() : SV_Target { return g.SubpassLoad().x + ms.SubpassLoad(1); }\n"),
            std::vector<std::string>{});
  EXPECT_EQ(attribute_errors_of("SubpassInput a;\n[[vk::input_attachment_index(0)]] Texture2D t;\n"),
            (std::vector<std::string>{
                "vk.hlsl:1:14: error: 'SubpassInput' 'a' needs [[vk::input_attachment_index(N)]]: the input attachment "
                "of the subpass it reads",
                "vk.hlsl:2:3: error: vk::input_attachment_index belongs on a SubpassInput, not on 't'"}));
  // A subpass input has SubpassLoad and nothing else, and only a pixel shader reads one.
  const std::vector<std::string> sampled = attribute_errors_of(
      "[[vk::input_attachment_index(0)]] SubpassInput a;\nSamplerState s;\n#pragma fragment f\n"
      "float4 f() : SV_Target { return a.Sample(s, float2(0, 0)); }\n");
  ASSERT_FALSE(sampled.empty());
  EXPECT_EQ(sampled[0], "vk.hlsl:4:35: error: 'SubpassInput' has no method 'Sample'");
  const std::vector<std::string> vertex = attribute_errors_of(
      "[[vk::input_attachment_index(0)]] SubpassInput a;\n#pragma vertex v\n"
      "float4 v() : SV_Position { return a.SubpassLoad(); }\n");
  ASSERT_FALSE(vertex.empty());
  EXPECT_NE(vertex[0].find("'SubpassLoad' is only available in fragment shaders"), std::string::npos) << vertex[0];
}

TEST(VulkanAttributes, PrintfTakesAFormatLiteralThenScalarsAndVectors) {
  EXPECT_EQ(attribute_errors_of("#pragma fragment f\nstruct S { float a; };\n"
                                "float4 f(float2 uv : TEXCOORD0) : SV_Target {\n"
                                "  S s = (S)0; printf(\"%f %v2f\", uv.x, uv); printf(\"%f\", s);\n  return 0; }\n"),
            (std::vector<std::string>{"vk.hlsl:4:57: error: printf prints scalars and vectors, not 'S'"}));
  // Anywhere else a string literal is still an error.
  const std::vector<std::string> elsewhere = attribute_errors_of("void g() { float x = \"s\"; }\n");
  ASSERT_FALSE(elsewhere.empty());
  EXPECT_NE(elsewhere[0].find("string literals are only allowed in annotations"), std::string::npos) << elsewhere[0];
}

TEST(VulkanAttributes, ASpecializationConstantIsAConstantOfItsDefault) {
  auto module = compiled_with_attributes(
      "[[vk::constant_id(7)]] const int MODE = 2;\n#pragma fragment f\n"
      "float4 f(float2 uv : TEXCOORD0) : SV_Target { return MODE == 2 ? 1 : 0; }\n");
  ASSERT_TRUE(module->ok());
  // Not a member of $Globals: the host specializes it, it gives it no bytes.
  EXPECT_EQ(module->reflection.find_constant_buffer(kGlobalsBufferName), nullptr);
}

}  // namespace
}  // namespace xshade::hlsl
