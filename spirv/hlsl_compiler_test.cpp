#include "spirv/hlsl_compiler.h"

#include <set>

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

namespace xshade::spirv {
namespace {

constexpr std::string_view kShader = R"(
cbuffer Material : register(b1) { float4 _Color; float _Gloss; };
Texture2D _MainTex : register(t2);
SamplerState sampler_MainTex : register(s3);
sampler2D _Ramp : register(s4);

float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return _MainTex.Sample(sampler_MainTex, uv) * _Color + tex2D(_Ramp, uv) * _Gloss;
}
)";

const HlslResource* find(const HlslModule& module, std::string_view name) {
  for (const HlslResource& resource : module.resources)
    if (resource.name == name) return &resource;
  return nullptr;
}

TEST(HlslCompiler, BindingsFollowRegistersAndShifts) {
  HlslStage stage{kShader, "material.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  auto module = compile_hlsl(stage);
  ASSERT_TRUE(module) << module.error().to_string();
  EXPECT_EQ(module->module.words[0], 0x07230203u);
  const HlslResource* material = find(*module, "Material");
  ASSERT_NE(material, nullptr);
  EXPECT_EQ(material->kind, HlslResource::Kind::ConstantBuffer);
  EXPECT_EQ(material->binding, 1u);
  EXPECT_EQ(material->size, 20u);  // HLSL packing: float4 then a float at 16
  const HlslResource* texture = find(*module, "_MainTex");
  ASSERT_NE(texture, nullptr);
  EXPECT_EQ(texture->kind, HlslResource::Kind::Texture);
  EXPECT_EQ(texture->binding, 16u + 2u);
  const HlslResource* sampler = find(*module, "sampler_MainTex");
  ASSERT_NE(sampler, nullptr);
  EXPECT_EQ(sampler->kind, HlslResource::Kind::Sampler);
  EXPECT_EQ(sampler->binding, 32u + 3u);
}

TEST(HlslCompiler, DefinesAndIncludesReachGlslang) {
  HlslStage stage;
  stage.source = "#include \"colour.hlsl\"\nfloat4 frag() : SV_Target { return float4(TINT, 1); }\n";
  stage.source_name = "main.hlsl";
  stage.entry_point = "frag";
  stage.defines = {{"USE_TINT", "1"}};
  stage.resolve_include = [](std::string_view name, std::string_view, bool) -> std::optional<IncludedFile> {
    if (name != "colour.hlsl") return std::nullopt;
    return IncludedFile{"colour.hlsl", "#if USE_TINT\n#define TINT float3(1, 0.5, 0)\n#endif\n"};
  };
  auto module = compile_hlsl(stage);
  ASSERT_TRUE(module) << module.error().to_string();

  stage.defines.clear();  // TINT is now undefined: a compile error in main.hlsl
  auto failed = compile_hlsl(stage);
  ASSERT_FALSE(failed);
  ASSERT_FALSE(failed.error().diagnostics.empty());
  EXPECT_EQ(failed.error().diagnostics[0].where.line, 2u);
}

// glslang knows no #include_with_pragmas; it reads Unity's directive, in the source and in an
// included file, as the #include it is to any compiler that takes no Unity pragma.
TEST(HlslCompiler, UnitysIncludeWithPragmasIsAnInclude) {
  HlslStage stage;
  stage.source = "  #  include_with_pragmas \"outer.hlsl\"\nfloat4 frag() : SV_Target { return float4(TINT, 1); }\n";
  stage.source_name = "main.hlsl";
  stage.entry_point = "frag";
  stage.resolve_include = [](std::string_view name, std::string_view, bool) -> std::optional<IncludedFile> {
    if (name == "outer.hlsl")
      return IncludedFile{"outer.hlsl", "#pragma multi_compile _ X\n#include_with_pragmas <inner.hlsl>\n"};
    if (name == "inner.hlsl") return IncludedFile{"inner.hlsl", "#define TINT float3(1, 0.5, 0)\n"};
    return std::nullopt;
  };
  auto module = compile_hlsl(stage);
  EXPECT_TRUE(module) << module.error().to_string();
  // Only the directive: a name that merely begins so is an unknown directive still.
  stage.source = "#include_with_pragmas_x \"outer.hlsl\"\nfloat4 frag() : SV_Target { return 1; }\n";
  EXPECT_FALSE(compile_hlsl(stage));
}

TEST(HlslCompiler, MissingIncludeAndEntryPointAreErrors) {
  HlslStage stage{"#include \"nowhere.hlsl\"\n", "main.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  EXPECT_FALSE(compile_hlsl(stage));
  HlslStage no_entry{
      "float4 other() : SV_Target { return 0; }\n", "main.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  EXPECT_FALSE(compile_hlsl(no_entry));
}

// glslang numbers resources without a register per stage: the fragment stage below does not read
// VertexOnly, so alone it would give $Global the first free number, which VertexOnly has in the
// vertex stage. The program-wide numbers in HlslStage::bindings keep the two stages apart.
TEST(HlslCompiler, ATextureInAStructNeedsGlslangsLegalization) {
  const char* source =
      "struct Pair { SamplerState s; Texture2D t; };\nTexture2D _T; SamplerState _S;\n"
      "float4 read(Pair p, float2 uv) { return p.t.Sample(p.s, uv); }\n"
      "float4 frag(float2 uv : TEXCOORD0) : SV_Target { Pair p; p.t = _T; p.s = _S; return read(p, uv); }\n";
  HlslStage stage{source, "pair.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  // As glslang translates it, the struct holds opaque values, which Vulkan's SPIR-V forbids.
  auto plain = compile_hlsl(stage);
  ASSERT_FALSE(plain);
  EXPECT_NE(plain.error().to_string().find("must not contain an opaque type"), std::string::npos)
      << plain.error().to_string();
  stage.legalize = true;
  auto legalized = compile_hlsl(stage);
  EXPECT_TRUE(legalized) << legalized.error().to_string();
}

TEST(HlslCompiler, ProgramWideBindingsOverrideGlslangsPerStageNumbering) {
  constexpr const char* kTwoStages = R"(
cbuffer VertexOnly { float4x4 _Transform; };
float4 _Tint;
float4 vert(float3 p : POSITION) : SV_Position { return mul(_Transform, float4(p, 1)); }
float4 frag() : SV_Target { return _Tint; }
)";
  HlslStage alone{kTwoStages, "two.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  auto per_stage = compile_hlsl(alone);
  ASSERT_TRUE(per_stage) << per_stage.error().to_string();
  ASSERT_NE(find(*per_stage, "$Global"), nullptr);
  EXPECT_EQ(find(*per_stage, "$Global")->binding, 0u);

  HlslStage program_wide = alone;
  program_wide.bindings = {{"VertexOnly", 0}, {"$Global", 1}};
  auto numbered = compile_hlsl(program_wide);
  ASSERT_TRUE(numbered) << numbered.error().to_string();
  ASSERT_NE(find(*numbered, "$Global"), nullptr);
  EXPECT_EQ(find(*numbered, "$Global")->binding, 1u);
}

// A stage that does not read a global texture still declares it; it must be at the program-wide
// number, not at glslang's default 0, where another resource of the program may be.
TEST(HlslCompiler, AResourceAStageDoesNotReadTakesItsProgramWideBinding) {
  constexpr const char* kSource = R"(
Texture2D _MainTex; SamplerState sampler_MainTex;
float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }
)";
  HlslStage stage{kSource, "vertex.hlsl", Stage::Vertex, "vert", {}, {}, {}, {}};
  stage.bindings = {{"_MainTex", 16}, {"sampler_MainTex", 32}};
  auto compiled = compile_hlsl(stage);
  ASSERT_TRUE(compiled) << compiled.error().to_string();
  std::string text;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  ASSERT_TRUE(tools.Disassemble(compiled->module.words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES));
  ASSERT_NE(text.find("%_MainTex = OpVariable"), std::string::npos) << "glslang keeps the texture: " << text;
  EXPECT_NE(text.find("OpDecorate %_MainTex Binding 16"), std::string::npos) << text;
  EXPECT_NE(text.find("OpDecorate %sampler_MainTex Binding 32"), std::string::npos) << text;
}

// glslang packs a declared cbuffer by HLSL's rules but the globals' block by std140's: `b` lands
// at 16 where fxc and DXC put it at 4. Given the host's offsets, the module reads HLSL's layout.
TEST(HlslCompiler, TheGlobalsTakeTheOffsetsTheHostWrites) {
  constexpr const char* kSource = "float a; float3 b;\nfloat4 frag() : SV_Target { return float4(b, a); }\n";
  HlslStage stage{kSource, "globals.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  const auto disassembly = [&](const HlslStage& request) {
    auto compiled = compile_hlsl(request);
    EXPECT_TRUE(compiled) << compiled.error().to_string();
    std::string text;
    if (compiled) tools.Disassemble(compiled->module.words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES);
    return text;
  };
  EXPECT_NE(disassembly(stage).find("OpMemberDecorate %_Global 1 Offset 16"), std::string::npos);
  stage.member_offsets = {{"$Global", {{"a", 0}, {"b", 4}}}};
  EXPECT_NE(disassembly(stage).find("OpMemberDecorate %_Global 1 Offset 4"), std::string::npos);
}

// glslang splits an array varying into a variable per element, each with the array's semantic;
// element k takes the semantic's index + k, as HLSL has it, so the locations do not collide.
TEST(HlslCompiler, AnArrayVaryingsElementsTakeConsecutiveSemantics) {
  constexpr const char* kSource =
      "struct V { float4 p : SV_Position; float4 offsets[3] : TEXCOORD1; };\n"
      "float4 frag(V v) : SV_Target { return v.offsets[0] + v.offsets[2]; }\n";
  HlslStage stage{kSource, "array.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  auto compiled = compile_hlsl(stage);
  ASSERT_TRUE(compiled) << compiled.error().to_string();
  std::string text;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  ASSERT_TRUE(tools.Disassemble(compiled->module.words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES));
  for (int k = 0; k < 3; ++k)  // TEXCOORD1..3 are locations 1..3 (hlsl::varying_location)
    EXPECT_NE(text.find("Location " + std::to_string(1 + k)), std::string::npos) << text;
}

// Given where the program places its varyings (an array's element k at the array's location + k),
// the stage takes those locations and no others: TEXCOORD3 after a two-element TEXCOORD2 array.
TEST(HlslCompiler, VaryingsTakeTheLocationsTheProgramGives) {
  constexpr const char* kSource =
      "struct V { float4 p : SV_Position; float3 light[2] : TEXCOORD2; float3 view : TEXCOORD3; };\n"
      "float4 frag(V v) : SV_Target { return float4(v.light[0] + v.light[1] + v.view, 1); }\n";
  HlslStage stage{kSource, "placed.hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
  stage.varying_locations = {{"TEXCOORD2", 2}, {"TEXCOORD3", 4}};
  auto compiled = compile_hlsl(stage);
  ASSERT_TRUE(compiled) << compiled.error().to_string();
  std::string text;
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  ASSERT_TRUE(tools.Disassemble(compiled->module.words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES));
  std::multiset<int> locations;
  for (size_t at = text.find(" Location "); at != std::string::npos; at = text.find(" Location ", at + 1))
    locations.insert(std::stoi(text.substr(at + 10)));
  // The output SV_Target at 0, the elements at 2 and 3, the TEXCOORD3 at 4.
  EXPECT_EQ(locations, (std::multiset<int>{0, 2, 3, 4})) << text;
}

}  // namespace
}  // namespace xshade::spirv
