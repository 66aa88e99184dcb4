// lit() in GLSL, as HLSL's documentation defines it, for every form of its arguments.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "glsl/emitted_fragment_for_tests.h"
#include "glsl/glsl_emitter.h"

namespace xshade::glsl {
namespace {

using ::testing::HasSubstr;

TEST(LitInGlsl, IsTheDocumentedFormulaOnFloatScalars) {
  for (Flavour flavour : {Flavour::Gl, Flavour::Vk}) {
    const std::string text = emitted_fragment(
        "#pragma fragment frag\nfloat4 _A;\n"
        "float4 frag() : SV_Target { return lit(_A.x, _A.y, _A.z); }\n",
        flavour);
    EXPECT_THAT(text, HasSubstr("vec4 xs_lit(float n_dot_l, float n_dot_h, float m) {\n"
                                "  float specular = (n_dot_l < 0.0 || n_dot_h < 0.0) ? 0.0 : pow(n_dot_h, m);\n"
                                "  return vec4(1.0, max(n_dot_l, 0.0), specular, 1.0);\n}\n"));
    EXPECT_THAT(text, HasSubstr("xs_lit(_A.x, _A.y, _A.z)"));
  }
}

TEST(LitInGlsl, EveryArgumentBecomesAFloat) {
  const std::string text = emitted_fragment(
      "#pragma fragment frag\nfloat4 _A;\nint _I;\nuint _U;\n"
      "float4 frag() : SV_Target {\n"
      "  float1 one = _A.x;\n"
      "  return lit(_I, _U, 3) + lit(one, half(_A.y), 0.5h) + lit(_A.x > 0, true, 2.0);\n"
      "}\n",
      Flavour::Gl);
  EXPECT_THAT(text, HasSubstr("xs_lit(float(_I), float(_U), 3.0)"));
  EXPECT_THAT(text, HasSubstr("xs_lit(one, _A.y, 0.5)"));
  EXPECT_THAT(text, HasSubstr("xs_lit(float(_A.x > 0.0), 1.0, 2.0)"));
  // One helper, whatever the arguments were.
  EXPECT_EQ(text.find("vec4 xs_lit("), text.rfind("vec4 xs_lit("));
}

}  // namespace
}  // namespace xshade::glsl
