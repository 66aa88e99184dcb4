// Renaming: the names themselves, and in the emitted GLSL a struct that a variable of the same name
// hides (C's rule, which HLSL keeps), which GLSL refuses beside a global of its name.
#include "glsl/lower/rename.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "glsl/emitted_fragment_for_tests.h"
#include "glsl/glsl_emitter.h"

namespace xshade::glsl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const hlsl::Decl* declared(const hlsl::Module& module, const std::string& name) {
  for (const auto& decl : module.unit.decls)
    if (decl && decl->name == name) return decl.get();
  return nullptr;
}

TEST(Rename, AReservedNameIsRenamedPastTheAuthorsOwnNames) {
  auto module = hlsl::compile_text("names.hlsl", R"(#pragma fragment frag
static float sample = 1;
static float sample_ = 2;
float f(float x) { return x; }
half f(half x) { return x * 2; }
float4 frag(float2 uv : TEXCOORD0) : SV_Target { half h = 1; return float4(sample, sample_, f(uv.x), f(h)); }
)",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const lower::Names names(module->unit, Flavour::Gl);
  EXPECT_EQ(names.of("_MainTex"), "_MainTex");  // not reserved: as written
  EXPECT_EQ(names.of("sample"), "sample_1");    // sample_ is the author's
  EXPECT_EQ(names.variable(declared(*module, "sample")), "sample_1");
  // Overloads whose parameters are one GLSL type (half is float there) are told apart.
  std::vector<std::string> overloads;
  for (const auto& decl : module->unit.decls)
    if (decl && decl->name == "f")
      overloads.push_back(names.function(static_cast<const hlsl::FunctionDecl*>(decl.get())));
  EXPECT_EQ(overloads, (std::vector<std::string>{"f_float", "f_half"}));
}

TEST(StructNamesInGlsl, AStructAVariableIsNamedLikeTakesANameOfItsOwn) {
  const std::string text = emitted_fragment(
      "#pragma fragment frag\n"
      "struct Light { float4 color; };\n"
      "struct Surface { float4 albedo; };\n"
      "Light Light;\n"
      "float4 frag() : SV_Target { Surface s = (Surface)0; return s.albedo + Light.color; }\n",
      Flavour::Vk);
  EXPECT_THAT(text, HasSubstr("struct Light_t {"));
  EXPECT_THAT(text, HasSubstr("Light_t Light;"));
  // A struct no variable is named like keeps its name.
  EXPECT_THAT(text, HasSubstr("struct Surface {"));
  EXPECT_THAT(text, Not(HasSubstr("Surface_t")));
}

TEST(StructNamesInGlsl, TheNewNameAvoidsTheAuthorsNames) {
  const std::string text = emitted_fragment(
      "#pragma fragment frag\n"
      "struct S { float4 a; };\n"
      "float4 S_t;\n"
      "float4 frag() : SV_Target { S S; S.a = S_t; return S.a; }\n",
      Flavour::Gl);
  EXPECT_THAT(text, HasSubstr("struct S_t1 {"));
  EXPECT_THAT(text, HasSubstr("S_t1 S;"));
}

}  // namespace
}  // namespace xshade::glsl
