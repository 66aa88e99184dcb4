#include "glsl/lower/compared_textures.h"

#include <gtest/gtest.h>

#include <string>

namespace xshade::glsl::lower {
namespace {

const hlsl::Decl* global_named(const hlsl::Module& module, const std::string& name) {
  for (const auto& decl : module.unit.decls)
    if (decl && decl->name == name) return decl.get();
  return nullptr;
}

TEST(ComparedTextures, TheObjectOfAComparisonAndWhatIsPassedForAComparedParameter) {
  auto module = hlsl::compile_text("shadow.hlsl", R"(#pragma vertex vert
#pragma fragment frag
Texture2D _Shadow;
Texture2D _Albedo;
Texture2D _Unused;
SamplerComparisonState shadow_cmp;
SamplerState linear_clamp;
float lit(Texture2D map, float3 p) { return map.SampleCmpLevelZero(shadow_cmp, p.xy, p.z); }
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(float4 p : SV_Position) : SV_Target {
  return _Albedo.Sample(linear_clamp, p.xy) * lit(_Shadow, p.xyz) * _Unused.Sample(linear_clamp, p.xy).x;
}
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const auto compared = compared_textures(*module);
  const hlsl::FunctionDecl* lit = nullptr;
  for (const auto& decl : module->unit.decls)
    if (decl && decl->name == "lit") lit = static_cast<const hlsl::FunctionDecl*>(decl.get());
  ASSERT_NE(lit, nullptr);
  EXPECT_TRUE(compared.count(lit->params[0].get()));               // the parameter compared
  EXPECT_TRUE(compared.count(global_named(*module, "_Shadow")));   // what is passed for it
  EXPECT_FALSE(compared.count(global_named(*module, "_Albedo")));  // sampled without comparison
  EXPECT_EQ(compared.size(), 2u);
}

TEST(ComparedTextures, ATextureOnlyTheOtherStageComparesIsComparedInBoth) {
  // The vertex stage never compares _Shadow; the fragment stage does: one uniform, one type.
  auto module = hlsl::compile_text("both.hlsl", R"(#pragma vertex vert
#pragma fragment frag
Texture2D _Shadow;
SamplerComparisonState shadow_cmp;
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(float4 p : SV_Position) : SV_Target { return _Shadow.SampleCmp(shadow_cmp, p.xy, 0.5); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_TRUE(compared_textures(*module).count(global_named(*module, "_Shadow")));
}

TEST(ComparedTextures, ComparisonMethods) {
  using I = hlsl::IntrinsicId;
  for (const I id : {I::SampleCmp, I::SampleCmpLevelZero, I::GatherCmp, I::GatherCmpRed, I::GatherCmpAlpha})
    EXPECT_TRUE(is_comparison_method(id));
  for (const I id : {I::Sample, I::SampleLevel, I::Gather, I::GatherAlpha, I::Load})
    EXPECT_FALSE(is_comparison_method(id));
}

}  // namespace
}  // namespace xshade::glsl::lower
