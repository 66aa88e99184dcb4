// A struct that a variable of the same name hides (C's rule, which HLSL keeps) in GLSL, which
// refuses a global beside a struct of its name: the struct takes a name of its own.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "glsl/emitted_fragment_for_tests.h"
#include "glsl/glsl_emitter.h"

namespace xshade::glsl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

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
