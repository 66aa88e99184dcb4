// xshade's reflection and glslang's HLSL front end must bind every resource at the same number,
// or the vk-hlsl lane would read other resources than the vk lane.
#include <gtest/gtest.h>

#include "hlsl_like/compiler.h"
#include "spirv/hlsl_compiler.h"

namespace xshade::spirv {
namespace {

struct Case {
  const char* name;
  const char* source;
};

// Unregistered resources declared in reverse name order, explicit registers in between, a
// sampler2D with an s register, an unused texture and an implicit $Globals.
const Case kCases[] = {
    {"mixed", R"(
#pragma fragment frag
float4 _Tint;
cbuffer Material : register(b1) { float4 _Color; float _Gloss; };
Texture2D _Zeta;
Texture2D _Alpha;
Texture2D _Unused;
SamplerState sampler_Zeta;
SamplerState sampler_Alpha : register(s2);
sampler2D _Ramp : register(s4);
sampler2D _Beta;
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  return _Zeta.Sample(sampler_Zeta, uv) * _Alpha.Sample(sampler_Alpha, uv) * _Color * _Tint
       + tex2D(_Ramp, uv) * _Gloss + tex2D(_Beta, uv);
}
)"},
    {"globals_after_cbuffer", R"(
#pragma fragment frag
cbuffer First { float4 a; };
cbuffer Second : register(b0) { float4 b; };
float4 c;
float4 frag() : SV_Target { return a + b + c; }
)"},
};

TEST(ReflectionAgreement, XshadeAndGlslangBindEveryResourceAlike) {
  for (const Case& test : kCases) {
    SCOPED_TRACE(test.name);
    auto module = hlsl::compile_text(std::string(test.name) + ".hlsl", test.source, {});
    ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
    const hlsl::Reflection& ours = module->reflection;

    HlslStage stage{test.source, std::string(test.name) + ".hlsl", Stage::Fragment, "frag", {}, {}, {}, {}};
    for (const auto& macro : module->macros) stage.defines.emplace_back(macro.name, macro.value);
    auto theirs = compile_hlsl(stage);
    ASSERT_TRUE(theirs) << theirs.error().to_string();

    for (const HlslResource& resource : theirs->resources) {
      SCOPED_TRACE(resource.name);
      std::optional<uint32_t> expected;
      switch (resource.kind) {
        case HlslResource::Kind::ConstantBuffer: {
          const std::string name = resource.name == "$Global" ? hlsl::kGlobalsBufferName : resource.name;
          if (const hlsl::ConstantBuffer* buffer = ours.find_constant_buffer(name)) {
            expected = buffer->binding;
            EXPECT_EQ(resource.size, buffer->members.back().offset + buffer->members.back().size);
          }
          break;
        }
        case HlslResource::Kind::Texture:
        case HlslResource::Kind::CombinedSampler:
          for (const hlsl::TextureResource& texture : ours.textures)
            if (texture.name == resource.name) expected = texture.binding;
          break;
        case HlslResource::Kind::Sampler:
          for (const hlsl::SamplerResource& sampler : ours.samplers)
            if (sampler.name == resource.name) expected = sampler.binding;
          break;
      }
      ASSERT_TRUE(expected.has_value()) << "xshade's reflection has no " << resource.name;
      EXPECT_EQ(resource.binding, *expected);
    }
  }
}

}  // namespace
}  // namespace xshade::spirv
