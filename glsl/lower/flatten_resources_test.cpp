#include "glsl/lower/flatten_resources.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace xshade::glsl::lower {
namespace flatten_resources_test {

constexpr const char* kShader = R"(#pragma vertex vert
#pragma fragment frag
struct Tex { Texture2D tex; SamplerState smpl; };
struct Mixed { Texture2D tex; float scale; };
struct Outer { Tex inner; };
struct OuterMixed { Tex inner; Mixed mixed; };
Texture2D _MainTex;
SamplerState sampler_MainTex;
float4 read(Tex t, float2 uv) { return t.tex.Sample(t.smpl, uv); }
float4 vert(float4 p : POSITION) : SV_Position { return p; }
float4 frag(float4 p : SV_Position) : SV_Target {
  Tex t;
  t.tex = _MainTex;
  t.smpl = sampler_MainTex;
  return read(t, p.xy);
}
)";

const hlsl::Decl& declared(const hlsl::Module& module, const std::string& name) {
  for (const auto& decl : module.unit.decls)
    if (decl && decl->name == name) return *decl;
  throw std::runtime_error("nothing declared as " + name);
}

hlsl::Type struct_type(const hlsl::Module& module, const std::string& name) {
  return hlsl::Type::structure(&static_cast<const hlsl::StructDecl&>(declared(module, name)));
}

TEST(FlattenResources, AParameterOfResourcesIsOneParameterPerResource) {
  auto module = hlsl::compile_text("flatten.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const auto& read = static_cast<const hlsl::FunctionDecl&>(declared(*module, "read"));
  const Names vk_names(module->unit, Flavour::Vk);
  const std::vector<FlattenedParameter> vk = flattened_parameters(*read.params[0], vk_names, Flavour::Vk);
  ASSERT_EQ(vk.size(), 2u);
  EXPECT_EQ(vk[0].name, "t_tex");
  EXPECT_EQ(vk[0].type->kind(), hlsl::TypeKind::Texture);
  EXPECT_EQ(vk[1].name, "t_smpl");
  EXPECT_EQ(vk[1].path, (std::vector<uint32_t>{1}));
  // OpenGL's sampler state belongs to the texture unit: no parameter of its own.
  const Names gl_names(module->unit, Flavour::Gl);
  const std::vector<FlattenedParameter> gl = flattened_parameters(*read.params[0], gl_names, Flavour::Gl);
  ASSERT_EQ(gl.size(), 1u);
  EXPECT_EQ(gl[0].name, "t_tex");
  // A value parameter holds no resource.
  EXPECT_TRUE(flattened_parameters(*read.params[1], vk_names, Flavour::Vk).empty());
}

TEST(FlattenResources, EachReadNamesTheGlobalOrFlattenedParameterItCameFrom) {
  auto module = hlsl::compile_text("flatten.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const Names names(module->unit, Flavour::Vk);
  std::set<std::string> read_as;
  for (const auto& [expr, leaves] : module->resource_origins)
    for (const hlsl::ResourceLeaf& leaf : leaves)
      if (std::optional<std::string> name = resource_name(*module, expr, leaf.path, names)) read_as.insert(*name);
  // frag's local `t` is another name for the globals; read's `t` is its flattened parameters.
  EXPECT_EQ(read_as, (std::set<std::string>{"_MainTex", "sampler_MainTex", "t_tex", "t_smpl"}));
  EXPECT_FALSE(resource_name(*module, nullptr, {}, names));  // nothing known for it
}

TEST(FlattenResources, AStructOfResourcesMayHoldNothingElse) {
  auto module = hlsl::compile_text("flatten.hlsl", kShader, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_FALSE(mixed_struct_message(struct_type(*module, "Tex")));
  EXPECT_FALSE(mixed_struct_message(struct_type(*module, "Outer")));
  const std::optional<std::string> mixed = mixed_struct_message(struct_type(*module, "Mixed"));
  ASSERT_TRUE(mixed);
  EXPECT_NE(mixed->find("'Mixed' holds both resources and the value 'scale'"), std::string::npos) << *mixed;
  // Found inside a struct of resources too.
  EXPECT_EQ(mixed_struct_message(struct_type(*module, "OuterMixed")), mixed);
  EXPECT_EQ(leaf_type(struct_type(*module, "Outer"), {0, 1}).kind(), hlsl::TypeKind::SamplerState);
}

}  // namespace flatten_resources_test
}  // namespace xshade::glsl::lower
