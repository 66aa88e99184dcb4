// The front end on bad input, end to end: each case compiles a whole source text and pins what the
// user reads (syntax, unknown names, types, arguments, semantics and entry points, files and
// includes), so that every message stays one a user can act on.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/bad_input_test_support.h"
#include "hlsl_like/compiler.h"
#include "hlsl_like/hang_guard.h"

namespace xshade::hlsl::bad_input {
namespace {

// ---------------------------------------------------------------------------------------------
// Syntax errors

TEST(BadInput, MissingSemicolonAtEndOfLineKeepsTheDeclaration) {
  // The statement is kept as if the ';' were there: no "unknown name 'x'" follows. Where the
  // error points is MissingSemicolonPointsJustPastThePreviousToken's concern.
  auto m = compile("semi.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = 1.0\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  ASSERT_EQ(m->diagnostics.diagnostics().size(), 1u) << m->diagnostics.render_all();
  EXPECT_EQ(m->diagnostics.diagnostics()[0].severity, Severity::Error);
  EXPECT_EQ(m->diagnostics.diagnostics()[0].message, "expected ';' after declaration");
}

// The ';' is missing from the end of the line before the next token, and that is where clang,
// gcc and DXC point: just past the last token of the statement, not at the next line's token.
TEST(BadInput, MissingSemicolonPointsJustPastThePreviousToken) {
  auto m = compile("semi.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = 1.0\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(m->diagnostics.render_all(),
            "semi.hlsl:3:16: error: expected ';' after declaration\n"
            "      float x = 1.0\n"
            "                   ^\n");

  auto s = compile("struct.hlsl",
                   "#pragma fragment frag\n"
                   "struct Light { float3 dir; }\n"
                   "float4 frag() : SV_Target { return 1; }\n");
  EXPECT_EQ(s->diagnostics.render_all(),
            "struct.hlsl:2:29: error: expected ';' after struct declaration\n"
            "    struct Light { float3 dir; }\n"
            "                                ^\n");
}

TEST(BadInput, MissingSemicolonAfterAMacroPointsAtTheNextToken) {
  // The last token came from a macro: where its expansion ends is not known, so the error stays
  // at the next token rather than pointing into the macro's definition.
  auto m = compile("macro.hlsl",
                   "#pragma fragment frag\n"
                   "#define ONE 1.0\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = ONE\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(headers(*m), (Strings{"macro.hlsl:5:3: error: expected ';' after declaration"}));
}

TEST(BadInput, UnbalancedParenthesisInAnExpression) {
  auto m = compile("paren.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = (1.0 + 2.0;\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  const Strings all = all_rendered(*m);
  ASSERT_GE(all.size(), 2u);
  EXPECT_EQ(all[0],
            "paren.hlsl:3:23: error: expected ')' to match '('\n"
            "      float x = (1.0 + 2.0;\n"
            "                          ^");
  EXPECT_EQ(all[1],
            "paren.hlsl:3:13: note: to match this '('\n"
            "      float x = (1.0 + 2.0;\n"
            "                ^");
}

TEST(BadInput, UnbalancedParenthesisInAnIfCondition) {
  auto m = compile("if.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  if (uv.x > 0.5 {\n"
                   "    return 1;\n"
                   "  }\n"
                   "  return 0;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"if.hlsl:3:18: error: expected ')' to match '('\n"
                                       "      if (uv.x > 0.5 {\n"
                                       "                     ^",
                                       "if.hlsl:3:6: note: to match this '('\n"
                                       "      if (uv.x > 0.5 {\n"
                                       "         ^"}));
}

TEST(BadInput, MissingClosingBrace) {
  // The end of the input is on the empty line after the last '}': no source line to show.
  auto m = compile("brace.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  if (true) {\n"
                   "    return float4(0, 0, 0, 1);\n"
                   "}\n");
  const Strings all = all_rendered(*m);
  ASSERT_GE(all.size(), 2u);
  EXPECT_EQ(all[0], "brace.hlsl:6:1: error: expected '}' to match '{'");
  EXPECT_EQ(all[1],
            "brace.hlsl:2:27: note: to match this '{'\n"
            "    float4 frag() : SV_Target {\n"
            "                              ^");
  EXPECT_EQ(m->diagnostics.error_count(), 1u);
}

TEST(BadInput, StrayClosingBraceAtFileScope) {
  auto m = compile("stray.hlsl",
                   "#pragma fragment frag\n"
                   "float4 _Color;\n"
                   "}\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return _Color;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"stray.hlsl:3:1: error: unexpected '}'\n"
                                       "    }\n"
                                       "    ^"}));
}

TEST(BadInput, StrayCharacterInAnExpression) {
  auto m = compile("at.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = 1.0 @ 2.0;\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(first(*m),
            "at.hlsl:3:17: error: unknown character '@'\n"
            "      float x = 1.0 @ 2.0;\n"
            "                    ^");
}

TEST(BadInput, MissingOperand) {
  auto m = compile("expr.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float x = 1.0 + ;\n"
                   "  return float4(x, 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(first(*m),
            "expr.hlsl:3:19: error: expected an expression\n"
            "      float x = 1.0 + ;\n"
            "                      ^");
}

TEST(BadInput, MissingCondition) {
  auto m = compile("cond.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  if () return 1;\n"
                   "  return 0;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"cond.hlsl:3:7: error: expected an expression\n"
                                       "      if () return 1;\n"
                                       "          ^"}));
}

// ---------------------------------------------------------------------------------------------
// Unknown names

TEST(BadInput, UnknownVariableSuggestsAClosePerName) {
  auto m = compile("var.hlsl",
                   "#pragma fragment frag\n"
                   "float4 _Color;\n"
                   "float4 frag() : SV_Target {\n"
                   "  return _Colour;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"var.hlsl:4:10: error: unknown name '_Colour'; did you mean '_Color'?\n"
                                       "      return _Colour;\n"
                                       "             ^"}));
}

TEST(BadInput, UnknownVariableWithNothingClose) {
  auto m = compile("var.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag() : SV_Target {\n"
                   "  float4 colour = 1;\n"
                   "  return zzzqqq;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"var.hlsl:4:10: error: unknown name 'zzzqqq'\n"
                                       "      return zzzqqq;\n"
                                       "             ^"}));
}

TEST(BadInput, UnknownIntrinsicSuggestsTheIntrinsic) {
  auto m = compile("fn.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return float4(saturat(uv.x), 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"fn.hlsl:3:17: error: unknown function 'saturat'; did you mean 'saturate'?\n"
                                       "      return float4(saturat(uv.x), 0, 0, 1);\n"
                                       "                    ^"}));
}

TEST(BadInput, UnknownFunctionSuggestsAUserFunction) {
  auto m = compile("fn.hlsl",
                   "#pragma fragment frag\n"
                   "float shade(float x) { return x; }\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return float4(shad(uv.x), 0, 0, 1);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"fn.hlsl:4:17: error: unknown function 'shad'; did you mean 'shade'?\n"
                                       "      return float4(shad(uv.x), 0, 0, 1);\n"
                                       "                    ^"}));
}

TEST(BadInput, UnknownType) {
  // The parser gives no suggestion for type names.
  auto m = compile("type.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  flaot3 n = float3(0, 0, 1);\n"
                   "  return float4(n, 1);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"type.hlsl:3:3: error: 'flaot3' is not a type\n"
                                       "      flaot3 n = float3(0, 0, 1);\n"
                                       "      ^"}));
}

// ---------------------------------------------------------------------------------------------
// Type mismatches

TEST(BadInput, Float2ToFloat3) {
  auto m = compile("conv.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  float3 n = uv;\n"
                   "  return float4(n, 1);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"conv.hlsl:3:14: error: cannot convert from 'float2' to 'float3'\n"
                                       "      float3 n = uv;\n"
                                       "                 ^"}));
}

TEST(BadInput, StructToFloat) {
  auto m = compile("conv.hlsl",
                   "#pragma fragment frag\n"
                   "struct Light { float3 dir; float power; };\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  Light l = (Light)0;\n"
                   "  float x = l;\n"
                   "  return x;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"conv.hlsl:5:13: error: cannot convert from 'Light' to 'float'\n"
                                       "      float x = l;\n"
                                       "                ^"}));
}

TEST(BadInput, ArithmeticOnATexture) {
  auto m = compile("res.hlsl",
                   "#pragma fragment frag\n"
                   "Texture2D _MainTex;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return _MainTex * 2.0;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"res.hlsl:4:19: error: cannot apply '*' to 'Texture2D' and 'float'\n"
                                       "      return _MainTex * 2.0;\n"
                                       "                      ^"}));
}

// ---------------------------------------------------------------------------------------------
// Argument counts

TEST(BadInput, IntrinsicArgumentCount) {
  auto m = compile("args.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  float x = lerp(uv.x, uv.y);\n"
                   "  return x;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"args.hlsl:3:13: error: 'lerp' takes 3 arguments, 2 given\n"
                                       "      float x = lerp(uv.x, uv.y);\n"
                                       "                ^"}));
}

TEST(BadInput, UserFunctionArgumentCount) {
  auto m = compile("args.hlsl",
                   "#pragma fragment frag\n"
                   "float shade(float a, float b) { return a * b; }\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return shade(uv.x);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"args.hlsl:4:10: error: 'shade' takes 2 arguments, 1 given\n"
                                       "      return shade(uv.x);\n"
                                       "             ^"}));
}

TEST(BadInput, ConstructorComponentCount) {
  auto m = compile("ctor.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return float4(uv, 1.0);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"ctor.hlsl:3:10: error: 'float4' constructor needs 4 components, 3 given\n"
                                       "      return float4(uv, 1.0);\n"
                                       "             ^"}));
}

// ---------------------------------------------------------------------------------------------
// Semantics and entry points

// Any identifier is a semantic in HLSL, so a misspelt one compiles: with a warning that names
// the semantic it is closest to.
TEST(BadInput, MisspeltSemanticIsAUserSemanticWithAWarning) {
  auto m = compile("sem.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCORD0) : SV_Target {\n"
                   "  return float4(uv, 0, 1);\n"
                   "}\n");
  EXPECT_TRUE(m->ok());
  EXPECT_EQ(all_rendered(*m), (Strings{"sem.hlsl:2:25: warning: 'TEXCORD0' is a user-defined semantic; did you mean "
                                       "'TEXCOORD0'?\n"
                                       "    float4 frag(float2 uv : TEXCORD0) : SV_Target {\n"
                                       "                            ^"}));
}

TEST(BadInput, UnknownSystemValue) {
  auto m = compile("sem.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : SV_Texcoord) : SV_Target {\n"
                   "  return float4(uv, 0, 1);\n"
                   "}\n");
  ASSERT_EQ(all_rendered(*m).size(), 1u);
  EXPECT_NE(all_rendered(*m)[0].find("sem.hlsl:2:25: error: unknown semantic 'SV_Texcoord': a system value's name "
                                     "starts SV_"),
            std::string::npos)
      << all_rendered(*m)[0];
}

TEST(BadInput, EntryInputWithoutSemantic) {
  auto m = compile("sem.hlsl",
                   "#pragma vertex vert\n"
                   "#pragma fragment frag\n"
                   "struct v2f { float4 pos : SV_Position; float2 uv : TEXCOORD0; };\n"
                   "v2f vert(float4 vertex : POSITION, float2 uv) {\n"
                   "  v2f o;\n"
                   "  o.pos = vertex;\n"
                   "  o.uv = uv;\n"
                   "  return o;\n"
                   "}\n"
                   "float4 frag(v2f i) : SV_Target { return float4(i.uv, 0, 1); }\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"sem.hlsl:4:43: error: input 'uv' of entry point 'vert' needs a semantic\n"
                                       "    v2f vert(float4 vertex : POSITION, float2 uv) {\n"
                                       "                                              ^"}));
}

TEST(BadInput, VertexEntryWithoutSvPosition) {
  auto m = compile("pos.hlsl",
                   "#pragma vertex vert\n"
                   "#pragma fragment frag\n"
                   "struct v2f { float4 color : COLOR0; float2 uv : TEXCOORD0; };\n"
                   "v2f vert(float4 vertex : POSITION, float2 uv : TEXCOORD0) {\n"
                   "  v2f o;\n"
                   "  o.color = vertex;\n"
                   "  o.uv = uv;\n"
                   "  return o;\n"
                   "}\n"
                   "float4 frag(v2f i) : SV_Target { return i.color; }\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"pos.hlsl:4:5: error: vertex entry point 'vert' does not output SV_Position\n"
                                       "    v2f vert(float4 vertex : POSITION, float2 uv : TEXCOORD0) {\n"
                                       "        ^"}));
}

TEST(BadInput, MissingEntryPoint) {
  auto m = compile("entry.hlsl",
                   "#pragma vertex vert\n"
                   "#pragma fragment nope\n"
                   "struct v2f { float4 pos : SV_Position; };\n"
                   "v2f vert(float4 vertex : POSITION) { v2f o; o.pos = vertex; return o; }\n"
                   "float4 frag(v2f i) : SV_Target { return 1; }\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"entry.hlsl:2:18: error: entry point 'nope' is not defined\n"
                                       "    #pragma fragment nope\n"
                                       "                     ^"}));
}

TEST(BadInput, UnknownPragmaIsOnlyAWarning) {
  auto m = compile("pragma.hlsl",
                   "#pragma fragmnet frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return 1;\n"
                   "}\n");
  EXPECT_TRUE(m->ok());
  EXPECT_EQ(all_rendered(*m), (Strings{"pragma.hlsl:1:9: warning: unknown pragma 'fragmnet'\n"
                                       "    #pragma fragmnet frag\n"
                                       "            ^"}));
}

// ---------------------------------------------------------------------------------------------
// Files and includes

TEST(BadInput, MissingSourceFile) {
  TempDir dir;
  const fs::path missing = dir.path() / "missing.hlsl";
  auto m = compile_file(missing, {});
  EXPECT_FALSE(m->ok());
  EXPECT_EQ(m->diagnostics.render_all(), "error: cannot open '" + missing.string() + "'\n");
}

TEST(BadInput, IncludeNotFoundListsTheSearchedFolders) {
  TempDir dir;
  const fs::path main = dir.write("main.hlsl",
                                  "#pragma fragment frag\n"
                                  "#include \"Lighting.hlsl\"\n"
                                  "float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n");
  CompileOptions options;
  options.include_dirs = {dir.path() / "a", dir.path() / "b"};
  auto m = compile_file(main, options);
  EXPECT_EQ(all_rendered(*m),
            (Strings{main.string() + ":2:10: error: cannot find include file 'Lighting.hlsl' (searched: " +
                     dir.path().string() + ", " + (dir.path() / "a").string() + ", " + (dir.path() / "b").string() +
                     ")\n"
                     "    #include \"Lighting.hlsl\"\n"
                     "             ^"}));

  // A source with no folder of its own searches the include folders only, and says so when
  // there are none.
  auto text = compile("text.hlsl", "#include <Lighting.hlsl>\n", options);
  EXPECT_EQ(first(*text), "text.hlsl:1:10: error: cannot find include file 'Lighting.hlsl' (searched: " +
                              (dir.path() / "a").string() + ", " + (dir.path() / "b").string() +
                              ")\n"
                              "    #include <Lighting.hlsl>\n"
                              "             ^");
  auto bare = compile("text.hlsl", "#include \"Lighting.hlsl\"\n");
  EXPECT_EQ(first(*bare),
            "text.hlsl:1:10: error: cannot find include file 'Lighting.hlsl' (no directories to search)\n"
            "    #include \"Lighting.hlsl\"\n"
            "             ^");
}

// An include may not leave the folders the compile was given (the main file's and the include
// directories), by `..`, an absolute path or a symbolic link: the file outside is not read.
TEST(BadInput, IncludeOutsideTheGivenFoldersIsRefused) {
  TempDir dir;
  dir.write("secret.txt", "float secret_value;\n");
  dir.write("shaders/include/common.hlsl", "#include \"../../secret.txt\"\n");
  const fs::path main = dir.write("shaders/materials/main.hlsl",
                                  "#include \"include/common.hlsl\"\n"
                                  "#include \"" +
                                      (dir.path() / "secret.txt").string() +
                                      "\"\n"
                                      "#include \"../include/link.hlsl\"\n"
                                      "float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n");
  fs::create_symlink(dir.path() / "secret.txt", dir.path() / "shaders" / "include" / "link.hlsl");
  CompileOptions options;
  options.include_dirs = {dir.path() / "shaders"};
  auto m = compile_file(main, options);
  const std::string folders =
      (dir.path() / "shaders").string() + ", " + (dir.path() / "shaders" / "materials").string();
  const Strings rendered = all_rendered(*m);
  ASSERT_EQ(rendered.size(), 3u) << m->diagnostics.render_all();
  EXPECT_EQ(rendered[0], (dir.path() / "shaders" / "include" / "common.hlsl").string() +
                             ":1:10: error: include file '../../secret.txt' is outside the folders this shader was "
                             "given (" +
                             folders +
                             "); an include may not leave them\n"
                             "    #include \"../../secret.txt\"\n"
                             "             ^");
  EXPECT_NE(rendered[1].find("error: include file '" + (dir.path() / "secret.txt").string() + "' is outside"),
            std::string::npos)
      << rendered[1];
  EXPECT_NE(rendered[2].find("error: include file '../include/link.hlsl' is outside"), std::string::npos)
      << rendered[2];
  EXPECT_EQ(m->diagnostics.render_all().find("secret_value"), std::string::npos);
}

// The chain is read a second time before the cycle shows; that second reading is dropped, so
// its declarations are not reported as redefinitions of themselves. The cycle is the one error.
TEST(BadInput, IncludeCycleIsTheOnlyError) {
  TempDir dir;
  dir.write("a.hlsl", "#include \"b.hlsl\"\nfloat a_value;\n");
  dir.write("b.hlsl", "#include \"c.hlsl\"\nfloat b_value;\n");
  const fs::path c = dir.write("c.hlsl", "#include \"a.hlsl\"\nfloat c_value;\n");
  const fs::path main = dir.write("main.hlsl",
                                  "#pragma fragment frag\n"
                                  "#include \"a.hlsl\"\n"
                                  "float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n");
  const auto start = std::chrono::steady_clock::now();
  auto m = compile_file(main, {});
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  // A file may be on the include stack twice (a deliberate re-inclusion); the third time is a cycle.
  EXPECT_EQ(all_rendered(*m),
            (Strings{c.string() + ":1:2: error: #include cycle: a.hlsl -> b.hlsl -> c.hlsl -> a.hlsl -> ...\n"
                                  "    #include \"a.hlsl\"\n"
                                  "     ^"}));
}

TEST(BadInput, ErrorInsideAnIncludedFileNamesThatFile) {
  TempDir dir;
  const fs::path common = dir.write("Common.hlsl",
                                    "float3 helper(float3 n) {\n"
                                    "  return normalise(n);\n"
                                    "}\n");
  const fs::path main =
      dir.write("main.hlsl",
                "#pragma fragment frag\n"
                "#include \"Common.hlsl\"\n"
                "float4 frag(float4 pos : SV_Position) : SV_Target { return float4(helper(pos.xyz), 1); }\n");
  auto m = compile_file(main, {});
  EXPECT_EQ(all_rendered(*m),
            (Strings{common.string() + ":2:10: error: unknown function 'normalise'; did you mean 'normalize'?\n"
                                       "      return normalise(n);\n"
                                       "             ^"}));
}

}  // namespace
}  // namespace xshade::hlsl::bad_input
