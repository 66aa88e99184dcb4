#include "hlsl_like/resource_origins.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

using Strings = std::vector<std::string>;

std::unique_ptr<Module> compile_body(const std::string& body, const std::string& functions = "") {
  const std::string source =
      "#pragma fragment frag\n"
      "struct Pair { SamplerState smpl; Texture2D tex; };\n"
      "Texture2D _A; Texture2D _B; SamplerState s_A; SamplerState s_B;\n" +
      functions + "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n" + body + "\n}\n";
  return compile_text("test.hlsl", source, {});
}

Strings error_messages(const Module& module) {
  Strings out;
  for (const Diagnostic& d : module.diagnostics.diagnostics())
    if (d.severity == Severity::Error) out.push_back(d.to_string());
  return out;
}

TEST(ResourceOrigins, LocalsAndFieldsNameTheGlobalsTheyAreGiven) {
  auto module = compile_body("Pair p; p.tex = _B; p.smpl = s_B; Texture2D t = p.tex; return t.Sample(p.smpl, uv);");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  // Reflection pairs the texture with its sampler through the struct, as the Vulkan lanes need.
  ASSERT_EQ(module->reflection.textures.size(), 2u);
  EXPECT_EQ(module->reflection.textures[1].name, "_B");
  EXPECT_TRUE(module->reflection.textures[1].used);
  EXPECT_EQ(module->reflection.textures[1].sampler, "s_B");
  EXPECT_FALSE(module->reflection.textures[0].used);  // _A is named by nothing
}

TEST(ResourceOrigins, AStructParameterIsTracedToWhatTheCallPasses) {
  auto module = compile_body("Pair p; p.tex = _A; p.smpl = s_A; return read(p, uv);",
                             "float4 read(Pair p, float2 uv) { return p.tex.SampleLevel(p.smpl, uv, 0); }\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  EXPECT_EQ(module->reflection.textures[0].sampler, "s_A");
  EXPECT_FALSE(module->reflection.textures[1].used);
}

TEST(ResourceOrigins, AResourceNotKnownWhenCompilingIsAnErrorAtItsPlace) {
  EXPECT_EQ(error_messages(*compile_body("Texture2D t = _A; if (uv.x > 0.5) t = _B; return t.Sample(s_A, uv);")),
            (Strings{"test.hlsl:5:35: error: resource 't' is given inside a branch or a loop; its resource must be "
                     "known when compiling: give it once, before any branch"}));
  EXPECT_EQ(error_messages(*compile_body("Pair p; p.tex = _A; return p.tex.Sample(p.smpl, uv);")),
            (Strings{"test.hlsl:5:43: error: resource 'p.smpl' is read before it is given one: a local resource "
                     "names a global or a parameter, assigned before it is read"}));
  EXPECT_EQ(error_messages(*compile_body("Texture2D t = uv.x > 0.5 ? _A : _B; return t.Sample(s_A, uv);")),
            (Strings{"test.hlsl:5:26: error: '?:' cannot choose between resources here: which one is read must be "
                     "known when compiling"}));
}

TEST(ResourceOrigins, UnreachedFunctionsAreNotFollowed) {
  auto module = compile_body("return 0;", "float4 unused(float2 uv) { Texture2D t; return t.Sample(s_A, uv); }\n");
  EXPECT_TRUE(module->ok()) << module->diagnostics.render_all();
}

TEST(ResourceOrigins, ResourcePathsListEveryResourceOfAType) {
  auto module = compile_body("return 0;", "struct Outer { float scale; Pair inner; Texture2D other; };\n");
  ASSERT_TRUE(module->ok());
  const StructDecl* outer = nullptr;
  for (const auto& decl : module->unit.decls)
    if (decl && decl->name == "Outer") outer = static_cast<const StructDecl*>(decl.get());
  ASSERT_NE(outer, nullptr);
  EXPECT_EQ(resource_paths(Type::structure(outer)), (std::vector<std::vector<uint32_t>>{{1, 0}, {1, 1}, {2}}));
  EXPECT_EQ(resource_paths(Type::texture2d()), (std::vector<std::vector<uint32_t>>{{}}));
  EXPECT_TRUE(resource_paths(Type::vector(ScalarType::Float, 3)).empty());
}

}  // namespace
}  // namespace xshade::hlsl
