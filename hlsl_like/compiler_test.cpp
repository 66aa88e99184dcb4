#include "hlsl_like/compiler.h"

#include <algorithm>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace xshade::hlsl {
namespace {

using Strings = std::vector<std::string>;

constexpr const char* kVariants =
    "#pragma fragment frag\n"
    "#pragma multi_compile FOG_LINEAR FOG_EXP FOG_EXP2\n"
    "#pragma shader_feature _ USE_RAMP USE_TINT\n"
    "float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n";

std::unique_ptr<Module> compile_with_keywords(std::vector<std::string> keywords) {
  CompileOptions options;
  options.keywords = std::move(keywords);
  return compile_text("variants.hlsl", kVariants, options);
}

Strings rendered(const Module& module) {
  Strings out;
  for (size_t i = 0; i < module.diagnostics.diagnostics().size(); ++i) out.push_back(module.diagnostics.render(i));
  return out;
}

TEST(Compiler, OneKeywordOfEachSetIsAVariant) {
  auto module = compile_with_keywords({"FOG_EXP", "USE_TINT"});
  EXPECT_TRUE(rendered(*module).empty());
  EXPECT_EQ(module->reflection.active_keywords, (Strings{"FOG_EXP", "USE_TINT"}));
}

TEST(Compiler, TwoKeywordsOfOneSetAreAnErrorAtThatSetsPragma) {
  auto module = compile_with_keywords({"FOG_EXP2", "USE_RAMP", "FOG_LINEAR"});
  EXPECT_FALSE(module->ok());
  EXPECT_EQ(rendered(*module),
            (Strings{"variants.hlsl:2:9: error: keywords 'FOG_EXP2' and 'FOG_LINEAR' are both of this #pragma "
                     "multi_compile set; a variant can have only one keyword of each set\n"
                     "    #pragma multi_compile FOG_LINEAR FOG_EXP FOG_EXP2\n"
                     "            ^"}));
}

TEST(Compiler, EachExtraKeywordOfASetIsNamedWithTheFirst) {
  auto module = compile_with_keywords({"USE_TINT", "USE_RAMP", "USE_TINT", "FOG_EXP"});
  // USE_TINT twice is one keyword; USE_RAMP is the conflict.
  EXPECT_EQ(rendered(*module),
            (Strings{"variants.hlsl:3:9: error: keywords 'USE_TINT' and 'USE_RAMP' are both of this #pragma "
                     "shader_feature set; a variant can have only one keyword of each set\n"
                     "    #pragma shader_feature _ USE_RAMP USE_TINT\n"
                     "            ^"}));
  module = compile_with_keywords({"FOG_LINEAR", "FOG_EXP", "FOG_EXP2"});
  EXPECT_EQ(module->diagnostics.error_count(), 2u);
  ASSERT_EQ(module->diagnostics.diagnostics().size(), 2u);
  EXPECT_NE(module->diagnostics.diagnostics()[0].message.find("'FOG_LINEAR' and 'FOG_EXP'"), std::string::npos);
  EXPECT_NE(module->diagnostics.diagnostics()[1].message.find("'FOG_LINEAR' and 'FOG_EXP2'"), std::string::npos);
}

TEST(Compiler, TheVariantKeepsThePreludeMacrosForOtherCompilers) {
  CompileOptions options;
  options.keywords = {"FOG_EXP"};
  options.defines = {{"EXTRA", "2"}};
  auto module = compile_text("variants.hlsl", kVariants, options);
  ASSERT_TRUE(module->ok());
  // The prelude first (fixed is half), then the keywords, then -D defines.
  ASSERT_GE(module->macros.size(), 3u);
  EXPECT_EQ(module->macros.front().name, "fixed");
  EXPECT_EQ(module->macros.front().value, "half");
  EXPECT_EQ(module->macros[module->macros.size() - 2].name, "FOG_EXP");
  EXPECT_EQ(module->macros.back().name, "EXTRA");
}

TEST(Compiler, PreludeMacrosExpandInEveryCompile) {
  const char* source =
      "#pragma fragment frag\n"
      "fixed4 frag(float4 pos : SV_Position) : SV_Target { return fixed4(UNITY_PI, 0, 0, 1); }\n";
  for (int i = 0; i < 2; ++i) {
    auto module = compile_text("prelude.hlsl", source, {});
    EXPECT_TRUE(rendered(*module).empty()) << i;
    EXPECT_TRUE(module->ok());
  }
  // A source may redefine a prelude macro; the next compile still has the prelude's.
  auto redefined = compile_text("redefine.hlsl",
                                "#pragma fragment frag\n#undef UNITY_PI\n#define UNITY_PI pi\n"
                                "float4 frag(float4 pos : SV_Position) : SV_Target { return UNITY_PI; }\n",
                                {});
  EXPECT_EQ(redefined->diagnostics.diagnostics().at(0).message, "unknown name 'pi'");
  auto again = compile_text("prelude.hlsl", source, {});
  EXPECT_TRUE(again->ok());
}

// Unity's UnityShaderVariables.cginc defines the matrix macros the prelude has, its own way.
TEST(Compiler, ASourceRedefinesAPreludeMacroWithoutAWarning) {
  auto module =
      compile_text("unity.hlsl",
                   "#pragma fragment frag\nfloat4x4 unity_MatrixMVP;\n#define UNITY_MATRIX_MVP unity_MatrixMVP\n"
                   "float4 frag() : SV_Target { return UNITY_MATRIX_MVP[0]; }\n#define UNITY_MATRIX_MVP 0\n",
                   {});
  ASSERT_TRUE(module->ok());
  const auto& diagnostics = module->diagnostics.diagnostics();
  // The second definition replaces the source's own: that one warns, with a note.
  ASSERT_EQ(diagnostics.size(), 2u) << module->diagnostics.render_all();
  EXPECT_EQ(diagnostics[0].message, "macro 'UNITY_MATRIX_MVP' redefined");
  EXPECT_EQ(diagnostics[0].where.line, 5u);
  EXPECT_EQ(diagnostics[1].where.line, 3u);
  // Another compiler handed the variant's macros (glslang on vk-hlsl) gets the prelude less the
  // one the source defines: two definitions are an error there.
  const auto has = [&](const std::string& name) {
    return std::any_of(module->macros.begin(), module->macros.end(),
                       [&](const MacroDefinition& m) { return m.name == name; });
  };
  EXPECT_FALSE(has("UNITY_MATRIX_MVP"));
  EXPECT_TRUE(has("UNITY_MATRIX_MV"));
}

// A post pass compiles its own fragment entry with the file's vertex entry (Unity's VertDefault);
// eval's fragment-only compile has none.
TEST(Compiler, APassEntryKeepsTheVertexEntry) {
  const char* source =
      "#pragma vertex vert\n#pragma fragment frag\n"
      "float4 vert(float3 p : POSITION) : SV_Position { return float4(p, 1); }\n"
      "float4 frag() : SV_Target { return 0; }\nfloat4 other() : SV_Target { return 1; }\n";
  CompileOptions pass;
  pass.pass_fragment_entry = "other";
  auto module = compile_text("pass.hlsl", source, pass);
  ASSERT_TRUE(module->ok());
  ASSERT_NE(module->entry_points.vertex, nullptr);
  EXPECT_EQ(module->reflection.vertex_entry, "vert");
  EXPECT_EQ(module->reflection.fragment_entry, "other");
  CompileOptions alone;
  alone.fragment_only_entry = "other";
  auto fragment_only = compile_text("pass.hlsl", source, alone);
  ASSERT_TRUE(fragment_only->ok());
  EXPECT_EQ(fragment_only->entry_points.vertex, nullptr);
  CompileOptions pragma_alone;
  pragma_alone.fragment_only = true;
  auto pragma_fragment = compile_text("pass.hlsl", source, pragma_alone);
  ASSERT_TRUE(pragma_fragment->ok());
  EXPECT_EQ(pragma_fragment->entry_points.vertex, nullptr);
  EXPECT_EQ(pragma_fragment->reflection.fragment_entry, "frag");
}

// #line numbers the lines after it, and names the file, in every message from there on; the
// source line shown under a message is still the one that was compiled.
TEST(Compiler, LineDirectivesSayWhereTheTextCameFrom) {
  const auto module = compile_text("composed.hlsl",
                                   "float4 a;\n"
                                   "#line 40 \"materials/Toon.shader\"\n"
                                   "float4 b;\n"
                                   "float4 c = undefined_name;\n"
                                   "#line 7\n"
                                   "float4 d = other_name;\n",
                                   {});
  const std::vector<std::string> messages = rendered(*module);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].substr(0, messages[0].find('\n')),
            "materials/Toon.shader:41:12: error: unknown name 'undefined_name'");
  EXPECT_NE(messages[0].find("float4 c = undefined_name;"), std::string::npos) << messages[0];
  EXPECT_EQ(messages[1].substr(0, messages[1].find('\n')),
            "materials/Toon.shader:7:12: error: unknown name 'other_name'");
}

TEST(Compiler, AMalformedLineDirectiveSaysWhatItTakes) {
  const auto module = compile_text("bad_line.hlsl", "#line zero\n#line 3 notquoted\nfloat4 a;\n", {});
  const std::vector<std::string> messages = rendered(*module);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(
      messages[0].substr(0, messages[0].find('\n')),
      "bad_line.hlsl:1:7: error: #line takes a line number from 1 to 2147483647 in decimal digits, then optionally "
      "a file name in quotes");
  EXPECT_EQ(messages[1].substr(0, messages[1].find('\n')),
            "bad_line.hlsl:2:9: error: #line's file name is a string in quotes");
}

}  // namespace
}  // namespace xshade::hlsl
