#include "hlsl_like/pass_declarations.h"

#include <gtest/gtest.h>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

struct Read {
  std::unique_ptr<Module> module;
  std::vector<PassDeclaration> passes;
  std::vector<std::string> messages;  // "line:col: message" of every diagnostic
};

Read read(const std::string& pragmas) {
  Read result;
  CompileOptions options;
  options.fragment_only_entry = "a";
  // The front end reads the pass declarations as it compiles; nothing else should complain.
  result.module =
      compile_text("fx.hlsl", pragmas + "float4 a(float2 uv : TEXCOORD0) : SV_Target { return 0; }\n", options);
  result.passes = result.module->passes;
  for (const Diagnostic& d : result.module->diagnostics.diagnostics())
    result.messages.push_back(std::to_string(d.where.line) + ":" + std::to_string(d.where.column) + ": " + d.message);
  return result;
}

TEST(PassDeclarations, ReadsNamesEntriesScalesAndSources) {
  Read r = read(
      "#pragma pass coc frag_coc scale=full _Depth=scene.depth\n"
      "#pragma pass blur frag_blur scale=half format=rgba32f _MainTex=scene.color _CoC=coc\n");
  ASSERT_TRUE(r.messages.empty()) << r.messages.front();
  ASSERT_EQ(r.passes.size(), 2u);
  EXPECT_EQ(r.passes[0].name, "coc");
  EXPECT_EQ(r.passes[0].entry, "frag_coc");
  EXPECT_EQ(r.passes[0].scale, PassDeclaration::Scale::Full);
  ASSERT_EQ(r.passes[0].inputs.size(), 1u);
  EXPECT_EQ(r.passes[0].inputs[0].texture, "_Depth");
  EXPECT_EQ(r.passes[0].inputs[0].kind, PassInput::Kind::SceneDepth);
  EXPECT_EQ(r.passes[1].scale, PassDeclaration::Scale::Half);
  ASSERT_EQ(r.passes[1].inputs.size(), 2u);
  EXPECT_EQ(r.passes[1].inputs[0].kind, PassInput::Kind::SceneColor);
  EXPECT_EQ(r.passes[1].inputs[1].kind, PassInput::Kind::Pass);
  EXPECT_EQ(r.passes[1].inputs[1].pass, "coc");
}

TEST(PassDeclarations, ScaleDefaultsToFull) {
  Read r = read("#pragma pass only frag\n");
  ASSERT_EQ(r.passes.size(), 1u);
  EXPECT_EQ(r.passes[0].scale, PassDeclaration::Scale::Full);
  EXPECT_TRUE(r.passes[0].inputs.empty());
}

TEST(PassDeclarations, ASourceMustBeAnEarlierPass) {
  Read r = read(
      "#pragma pass first f _A=second\n"
      "#pragma pass second g\n");
  EXPECT_EQ(
      r.messages,
      (std::vector<std::string>{"1:22: #pragma pass: 'second' is not scene.color, scene.depth or an earlier pass"}));
  ASSERT_EQ(r.passes.size(), 1u);
  EXPECT_EQ(r.passes[0].name, "second");
}

TEST(PassDeclarations, MalformedLinesAreReportedWhereTheyGoWrong) {
  Read r = read(
      "#pragma pass\n"
      "#pragma pass p f scale=quarter\n"
      "#pragma pass q f format=rgba8\n"
      "#pragma pass r f _A scene.color\n"
      "#pragma pass p f\n"
      "#pragma pass s f _A=scene.color _A=scene.depth\n"
      "#pragma pass t 42\n");
  EXPECT_EQ(r.messages, (std::vector<std::string>{
                            "1:9: #pragma pass: expected a pass name at the end of the line",
                            "2:18: #pragma pass: scale is 'full' or 'half', not 'quarter'",
                            "3:18: #pragma pass: format is 'rgba32f' (the only target format), not 'rgba8'",
                            "4:21: #pragma pass: expected '=' after '_A'",
                            "6:33: #pragma pass: texture '_A' is given twice",
                            "7:16: #pragma pass: expected the pass's fragment function, not '42'",
                        }));
  // Line 5 redeclares nothing: line 2's 'p' was malformed and never declared.
  ASSERT_EQ(r.passes.size(), 1u);
  EXPECT_EQ(r.passes[0].name, "p");
}

TEST(PassDeclarations, ANameCannotBeDeclaredTwice) {
  Read r = read("#pragma pass p f\n#pragma pass p g\n");
  EXPECT_EQ(r.messages, (std::vector<std::string>{"2:14: #pragma pass: pass 'p' is already declared"}));
}

}  // namespace
}  // namespace xshade::hlsl
