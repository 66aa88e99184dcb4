// The front end on bad input, end to end: each case compiles a whole source through
// compile_text or compile_file and pins what a user sees, the rendered diagnostic
// ("file:line:col: severity: message", the source line and a caret).
// Why this file is long: it is a catalogue, one short case per kind of bad input, read as a
// list of what a user sees; splitting it would only scatter the list.

#include "hlsl_like/compiler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/hang_guard.h"

namespace xshade::hlsl {
namespace {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;
using namespace std::string_literals;

// No single hostile input may take longer than this (optimised build). The largest are 1 MiB, which
// a linear pass reads in 0.15-0.2 s here, and the suite runs two tests at once on two cores, which
// can double that; a pass quadratic in the input would take minutes (10^12 steps). 1 s tells the
// two apart with room, where 0.25 s failed under a loaded run.
constexpr double kFastSeconds = 1.0;
// The whole rendered output of a hostile input stays readable.
constexpr size_t kShortRender = 4096;

std::unique_ptr<Module> compile(const std::string& name, const std::string& text, const CompileOptions& options = {}) {
  return compile_text(name, text, options);
}

// Diagnostic `index` as rendered; "" when there is none, so that a missing one fails readably.
std::string rendered(const Module& module, size_t index) {
  return index < module.diagnostics.diagnostics().size() ? module.diagnostics.render(index) : std::string();
}
std::string first(const Module& module) { return rendered(module, 0); }

Strings all_rendered(const Module& module) {
  Strings out;
  for (size_t i = 0; i < module.diagnostics.diagnostics().size(); ++i) out.push_back(module.diagnostics.render(i));
  return out;
}

// The errors only, rendered (warnings and notes left out).
Strings errors_rendered(const Module& module) {
  Strings out;
  const auto& diagnostics = module.diagnostics.diagnostics();
  for (size_t i = 0; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) out.push_back(module.diagnostics.render(i));
  return out;
}

// "file:line:col: severity: message" of every diagnostic, without the source excerpt.
Strings headers(const Module& module) {
  Strings out;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) out.push_back(d.to_string());
  return out;
}

// A fresh folder under the system's temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::random_device random;
    for (;;) {
      const fs::path candidate =
          fs::temp_directory_path() / ("xshade_bad_input_" + std::to_string(random()) + "_" + std::to_string(random()));
      if (fs::create_directory(candidate)) {
        path_ = fs::canonical(candidate);  // the front end names included files by canonical path
        return;
      }
    }
  }
  ~TempDir() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

 private:
  fs::path path_;
};

// True when every byte is printable ASCII or a line break: what a terminal can show as it is.
bool printable(const std::string& text) {
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c != '\n' && (byte < 0x20 || byte >= 0x7f)) return false;
  }
  return true;
}

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
                                   "#include \"" + (dir.path() / "secret.txt").string() + "\"\n"
                                   "#include \"../include/link.hlsl\"\n"
                                   "float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }\n");
  fs::create_symlink(dir.path() / "secret.txt", dir.path() / "shaders" / "include" / "link.hlsl");
  CompileOptions options;
  options.include_dirs = {dir.path() / "shaders"};
  auto m = compile_file(main, options);
  const std::string folders = (dir.path() / "shaders").string() + ", " + (dir.path() / "shaders" / "materials").string();
  const Strings rendered = all_rendered(*m);
  ASSERT_EQ(rendered.size(), 3u) << m->diagnostics.render_all();
  EXPECT_EQ(rendered[0], (dir.path() / "shaders" / "include" / "common.hlsl").string() +
                             ":1:10: error: include file '../../secret.txt' is outside the folders this shader was "
                             "given (" + folders + "); an include may not leave them\n"
                             "    #include \"../../secret.txt\"\n"
                             "             ^");
  EXPECT_NE(rendered[1].find("error: include file '" + (dir.path() / "secret.txt").string() + "' is outside"),
            std::string::npos) << rendered[1];
  EXPECT_NE(rendered[2].find("error: include file '../include/link.hlsl' is outside"), std::string::npos) << rendered[2];
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
  EXPECT_EQ(all_rendered(*m), (Strings{c.string() +
                                       ":1:2: error: #include cycle: a.hlsl -> b.hlsl -> c.hlsl -> a.hlsl -> ...\n"
                                       "    #include \"a.hlsl\"\n"
                                       "     ^"}));
}

TEST(BadInput, ErrorInsideAnIncludedFileNamesThatFile) {
  TempDir dir;
  const fs::path common = dir.write("Common.hlsl",
                                    "float3 helper(float3 n) {\n"
                                    "  return normalise(n);\n"
                                    "}\n");
  const fs::path main = dir.write("main.hlsl",
                                  "#pragma fragment frag\n"
                                  "#include \"Common.hlsl\"\n"
                                  "float4 frag(float4 pos : SV_Position) : SV_Target { return float4(helper(pos.xyz), 1); }\n");
  auto m = compile_file(main, {});
  EXPECT_EQ(all_rendered(*m), (Strings{common.string() +
                                       ":2:10: error: unknown function 'normalise'; did you mean 'normalize'?\n"
                                       "      return normalise(n);\n"
                                       "             ^"}));
}

// ---------------------------------------------------------------------------------------------
// The preprocessor

TEST(BadInput, MutuallyRecursiveMacros) {
  // A expands to B, B to A, and A is not expanded again (as in C): the name A is left over.
  auto m = compile("macro.hlsl",
                   "#pragma fragment frag\n"
                   "#define A B\n"
                   "#define B A\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  float x = A;\n"
                   "  return x;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"macro.hlsl:5:13: warning: macro 'A' refers to itself; it is not expanded again\n"
                                       "      float x = A;\n"
                                       "                ^",
                                       "macro.hlsl:5:13: error: unknown name 'A'\n"
                                       "      float x = A;\n"
                                       "                ^"}));
}

TEST(BadInput, ErrorInsideAMacroExpansionPointsAtTheInvocation) {
  auto m = compile("macro.hlsl",
                   "#pragma fragment frag\n"
                   "#define SCALE(v) ((v) * undefinedScale)\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  float x = SCALE(pos.x);\n"
                   "  return x;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"macro.hlsl:4:13: error: unknown name 'undefinedScale'\n"
                                       "      float x = SCALE(pos.x);\n"
                                       "                ^"}));
}

TEST(BadInput, MacroArgumentCount) {
  auto m = compile("macro.hlsl",
                   "#pragma fragment frag\n"
                   "#define MAD(a, b, c) ((a) * (b) + (c))\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return MAD(uv.x, uv.y);\n"
                   "}\n");
  EXPECT_EQ(first(*m),
            "macro.hlsl:4:10: error: macro 'MAD' takes 3 arguments, 2 given\n"
            "      return MAD(uv.x, uv.y);\n"
            "             ^");
}

TEST(BadInput, UnterminatedIfdef) {
  // The skipped block held the entry point, so that is missing too.
  auto m = compile("if.hlsl",
                   "#pragma fragment frag\n"
                   "#ifdef USE_FOG\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return 1;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"if.hlsl:2:2: error: unterminated #ifdef\n"
                                       "    #ifdef USE_FOG\n"
                                       "     ^",
                                       "if.hlsl:1:18: error: entry point 'frag' is not defined\n"
                                       "    #pragma fragment frag\n"
                                       "                     ^"}));
}

// ---------------------------------------------------------------------------------------------
// The lexer

TEST(BadInput, UnterminatedBlockComment) {
  auto m = compile("comment.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  return 1; /* the rest\n"
                   "  of the file is a comment\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"comment.hlsl:3:13: error: unterminated comment\n"
                                       "      return 1; /* the rest\n"
                                       "                ^",
                                       "comment.hlsl:6:1: error: expected '}' to match '{'",
                                       "comment.hlsl:2:51: note: to match this '{'\n"
                                       "    float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                                       "                                                      ^"}));
}

TEST(BadInput, UnterminatedString) {
  auto m = compile("string.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  float x = \"abc;\n"
                   "  return 1;\n"
                   "}\n");
  EXPECT_EQ(first(*m),
            "string.hlsl:3:13: error: unterminated string literal\n"
            "      float x = \"abc;\n"
            "                ^");
}

// One error per token: the lexer reports the unterminated string, and the parser does not add
// "string literals are only allowed in annotations" at the same place.
TEST(BadInput, UnterminatedStringIsReportedOnce) {
  auto m = compile("string.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  float x = \"abc;\n"
                   "  return 1;\n"
                   "}\n");
  EXPECT_EQ(errors_rendered(*m), (Strings{"string.hlsl:3:13: error: unterminated string literal\n"
                                          "      float x = \"abc;\n"
                                          "                ^"}));
}

TEST(BadInput, UnterminatedStringInAnInclude) {
  auto m = compile("include.hlsl", "#include \"Common.hlsl\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"include.hlsl:1:10: error: unterminated string literal\n"
                                       "    #include \"Common.hlsl\n"
                                       "             ^"}));
}

TEST(BadInput, BinaryGarbage) {
  // One error per byte that cannot start a token; a valid byte run ("garbage") is a name.
  auto m = compile("garbage.hlsl", "#pragma fragment frag\n\x01\x02\xff\xfe\x80garbage\x00\x7f\n"s);
  EXPECT_EQ(headers(*m), (Strings{"garbage.hlsl:2:1: error: unknown character '\\x01'",
                                  "garbage.hlsl:2:2: error: unknown character '\\x02'",
                                  "garbage.hlsl:2:3: error: unknown character '\\xFF'",
                                  "garbage.hlsl:2:4: error: unknown character '\\xFE'",
                                  "garbage.hlsl:2:5: error: unknown character '\\x80'",
                                  "garbage.hlsl:2:13: error: unknown character '\\x00'",
                                  "garbage.hlsl:2:14: error: unknown character '\\x7F'",
                                  "garbage.hlsl:1:18: error: entry point 'frag' is not defined"}));
  EXPECT_EQ(rendered(*m, 7),
            "garbage.hlsl:1:18: error: entry point 'frag' is not defined\n"
            "    #pragma fragment frag\n"
            "                     ^");

  // A binary file (a PNG's first bytes) is stopped by the error limit, whatever its size.
  std::string png = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR"s;
  for (int i = 0; i < 200; ++i) png += "\0\x01\x08\x06"s;
  auto binary = compile("image.png", png);
  EXPECT_EQ(binary->diagnostics.error_count(), DiagnosticEngine::kErrorLimit);
  EXPECT_EQ(headers(*binary).front(), "image.png:1:1: error: unknown character '\\x89'");
  EXPECT_EQ(headers(*binary).back(), "note: too many errors; stopping here");
}

TEST(BadInput, NulByteInTheMiddleOfTheSource) {
  auto m = compile("nul.hlsl", std::string("#pragma fragment frag\n"
                                           "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                                           "  float x = 1.0;\0  return x;\n"
                                           "}\n"s));
  ASSERT_FALSE(headers(*m).empty());
  EXPECT_EQ(headers(*m)[0], "nul.hlsl:3:17: error: unknown character '\\x00'");
  EXPECT_EQ(m->diagnostics.error_count(), 1u);
}

// NUL, control and invalid UTF-8 bytes (and a bare '\r') in the source line under a diagnostic
// would be mangled by a terminal and cut a C string short: the excerpt escapes them as the
// message does ('\x00'), with the caret under the escaped byte.
TEST(BadInput, RenderedTextIsPrintableForBinaryInput) {
  auto nul = compile("nul.hlsl", std::string("#pragma fragment frag\n"
                                             "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                                             "  float x = 1.0;\0  return x;\n"
                                             "}\n"s));
  EXPECT_TRUE(printable(nul->diagnostics.render_all())) << nul->diagnostics.render_all();
  auto garbage = compile("garbage.hlsl", "#pragma fragment frag\n\x01\x02\xff\xfe\x80garbage\x00\x7f\n"s);
  EXPECT_TRUE(printable(garbage->diagnostics.render_all()));
  auto png = compile("image.png", "\x89PNG\r\n\x1a\n\0\0\0\rIHDR"s);
  EXPECT_TRUE(printable(png->diagnostics.render_all()));
}

TEST(BadInput, WindowsLineEndingsStayOutOfTheExcerpt) {
  auto m = compile("crlf.hlsl",
                   "#pragma fragment frag\r\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\r\n"
                   "  return undefinedThing;\r\n"
                   "}\r\n");
  EXPECT_EQ(m->diagnostics.render_all(),
            "crlf.hlsl:3:10: error: unknown name 'undefinedThing'\n"
            "      return undefinedThing;\n"
            "             ^\n");
}

TEST(BadInput, EmptyFile) {
  // Nothing to compile and no entry point asked for: not an error.
  auto m = compile("empty.hlsl", "");
  EXPECT_TRUE(m->ok());
  EXPECT_EQ(m->diagnostics.render_all(), "");
  EXPECT_EQ(m->entry_points.vertex, nullptr);
  EXPECT_EQ(m->entry_points.fragment, nullptr);

  TempDir dir;
  auto file = compile_file(dir.write("empty.hlsl", ""), {});
  EXPECT_TRUE(file->ok());
  EXPECT_EQ(file->diagnostics.render_all(), "");
}

TEST(BadInput, EmptyFileExceptAnEntryPointPragma) {
  auto m = compile("empty.hlsl", "#pragma fragment frag\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"empty.hlsl:1:18: error: entry point 'frag' is not defined\n"
                                       "    #pragma fragment frag\n"
                                       "                     ^"}));
}

// ---------------------------------------------------------------------------------------------
// Hostile sizes

TEST(BadInput, OneMebibyteExpressionLine) {
  // `float x = 1 + 1 + ... + 1;` on one 1 MiB line: each '+' nests the tree one level deeper, and
  // the 257th '+' (column 13 + 4 * 256) is one too many.
  std::string line = "float x = 1";
  while (line.size() < (size_t(1) << 20)) line += " + 1";
  line += ";";
  const std::string text = "#pragma fragment frag\n" + line + "\nfloat4 frag() : SV_Target { return x; }\n";
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("long.hlsl", text);
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  const std::string all = m->diagnostics.render_all();
  EXPECT_LT(all.size(), kShortRender) << all.substr(0, kShortRender);
  // The excerpt is 120 characters around the column, after "...".
  EXPECT_EQ(first(*m), "long.hlsl:2:1037: error: nesting is too deep (more than 256 levels)\n"
                       "    ..." + line.substr(976, 120) + "\n"
                       "       " + std::string(60, ' ') + "^");
  EXPECT_EQ(line.substr(1036, 1), "+");
}

// Every message cuts the author's names to 64 characters and "..." (in_quotes), so that a 1 MiB
// identifier does not make a 1 MiB message.
TEST(BadInput, OneMebibyteIdentifierKeepsTheMessageShort) {
  const std::string name(size_t(1) << 20, 'a');
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("long.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                   "  return " + name + ";\n"
                   "}\n");
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_EQ(m->diagnostics.error_count(), 1u);
  ASSERT_LT(m->diagnostics.render_all().size(), kShortRender);  // stops before printing 1 MiB
  EXPECT_EQ(first(*m), "long.hlsl:3:10: error: unknown name '" + std::string(64, 'a') + "...'\n"
                       "      return " + std::string(111, 'a') + "\n"
                       "             ^");
}

TEST(BadInput, TenThousandNestedParentheses) {
  const size_t depth = 10000;
  const std::string text = "#pragma fragment frag\n"
                           "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                           "  float x = " + std::string(depth, '(') + "1" + std::string(depth, ')') + ";\n"
                           "  return x;\n"
                           "}\n";
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("deep.hlsl", text);
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_EQ(m->diagnostics.error_count(), 1u) << m->diagnostics.render_all().substr(0, kShortRender);
  EXPECT_LT(m->diagnostics.render_all().size(), kShortRender);
  // The 257th '(' (column 13 + 256) is one level too many.
  EXPECT_EQ(first(*m), "deep.hlsl:3:269: error: nesting is too deep (more than 256 levels)\n"
                       "    ..." + std::string(120, '(') + "\n"
                       "       " + std::string(60, ' ') + "^");
}

TEST(BadInput, TenThousandNestedBraces) {
  const size_t depth = 10000;
  const std::string text = "#pragma fragment frag\n"
                           "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                           "  " + std::string(depth, '{') + std::string(depth, '}') + "\n"
                           "  return 1;\n"
                           "}\n";
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("deep.hlsl", text);
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_LT(m->diagnostics.render_all().size(), kShortRender);
  // The 257th '{' (column 3 + 256) is one level too many.
  EXPECT_EQ(all_rendered(*m), (Strings{"deep.hlsl:3:259: error: nesting is too deep (more than 256 levels)\n"
                                       "    ..." + std::string(120, '{') + "\n"
                                       "       " + std::string(60, ' ') + "^"}));
}

// ---------------------------------------------------------------------------------------------
// Many errors, and a warning

TEST(BadInput, SeveralErrorsInOneFileAreAllReported) {
  // A syntax error in one function, then four different errors in the next: the parser
  // recovers and analysis still runs.
  auto m = compile("many.hlsl",
                   "#pragma fragment frag\n"
                   "float4 _Color;\n"
                   "float helper(float a) { return a * ; }\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  float3 n = uv;\n"
                   "  float k = undefinedThing + 1.0;\n"
                   "  float m = lerp(0.0, 1.0);\n"
                   "  float z = uv.z;\n"
                   "  return _Color * k * m * z;\n"
                   "}\n");
  EXPECT_EQ(errors_rendered(*m), (Strings{"many.hlsl:3:36: error: expected an expression\n"
                                          "    float helper(float a) { return a * ; }\n"
                                          "                                       ^",
                                          "many.hlsl:5:14: error: cannot convert from 'float2' to 'float3'\n"
                                          "      float3 n = uv;\n"
                                          "                 ^",
                                          "many.hlsl:6:13: error: unknown name 'undefinedThing'\n"
                                          "      float k = undefinedThing + 1.0;\n"
                                          "                ^",
                                          "many.hlsl:7:13: error: 'lerp' takes 3 arguments, 2 given\n"
                                          "      float m = lerp(0.0, 1.0);\n"
                                          "                ^",
                                          "many.hlsl:8:16: error: swizzle 'z' is out of range for 'float2'\n"
                                          "      float z = uv.z;\n"
                                          "                   ^"}));
}

TEST(BadInput, TheErrorLimit) {
  std::string text = "#pragma fragment frag\n"
                     "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
                     "  float x = 0;\n";
  for (int i = 0; i < 60; ++i) text += "  x += missing" + std::to_string(i) + ";\n";
  text += "  return x;\n}\n";
  auto m = compile("limit.hlsl", text);
  EXPECT_EQ(m->diagnostics.error_count(), 50u);
  ASSERT_EQ(m->diagnostics.diagnostics().size(), 51u);
  EXPECT_EQ(rendered(*m, 0),
            "limit.hlsl:4:8: error: unknown name 'missing0'\n"
            "      x += missing0;\n"
            "           ^");
  EXPECT_EQ(rendered(*m, 49),
            "limit.hlsl:53:8: error: unknown name 'missing49'\n"
            "      x += missing49;\n"
            "           ^");
  EXPECT_EQ(rendered(*m, 50), "note: too many errors; stopping here");
}

TEST(BadInput, ImplicitTruncationIsOnlyAWarning) {
  auto m = compile("trunc.hlsl",
                   "#pragma fragment frag\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  float4 c = float4(uv, 0, 1);\n"
                   "  float3 rgb = c;\n"
                   "  return float4(rgb, 1);\n"
                   "}\n");
  EXPECT_TRUE(m->ok());
  EXPECT_NE(m->entry_points.fragment, nullptr);
  EXPECT_EQ(all_rendered(*m), (Strings{"trunc.hlsl:4:16: warning: implicit truncation of vector type from 'float4' to 'float3'\n"
                                       "      float3 rgb = c;\n"
                                       "                   ^"}));
}

// ---------------------------------------------------------------------------------------------
// Resources, constant buffers, uniforms

TEST(BadInput, DuplicateTextureRegister) {
  auto m = compile("reg.hlsl",
                   "#pragma fragment frag\n"
                   "Texture2D _MainTex : register(t0);\n"
                   "Texture2D _DetailTex : register(t0);\n"
                   "SamplerState sampler_MainTex;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return _MainTex.Sample(sampler_MainTex, uv) * _DetailTex.Sample(sampler_MainTex, uv);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"reg.hlsl:3:24: error: register t0 of '_DetailTex' is already taken by '_MainTex', and the "
                                       "entry points read both; give one another register\n"
                                       "    Texture2D _DetailTex : register(t0);\n"
                                       "                           ^"}));
}

TEST(BadInput, DuplicateConstantBufferRegister) {
  auto m = compile("reg.hlsl",
                   "#pragma fragment frag\n"
                   "cbuffer A : register(b1) { float4 _A; };\n"
                   "cbuffer B : register(b1) { float4 _B; };\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return _A + _B;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"reg.hlsl:3:13: error: register b1 of 'B' is already taken by 'A', and the entry points "
                                       "read both; give one another register\n"
                                       "    cbuffer B : register(b1) { float4 _B; };\n"
                                       "                ^"}));
}

// fxc and DXC let resources share a register where no entry point reads both: a file of
// several shaders declares each one's inputs at t0.
TEST(BadInput, ASharedRegisterIsAnErrorOnlyWhereBothAreRead) {
  auto m = compile("reg.hlsl",
                   "#pragma fragment frag\n"
                   "Texture2D BloomInput : register(t0);\n"
                   "Texture2D InputTexture0 : register(t0);\n"
                   "cbuffer VSConstants : register(b0) { float4 _V; };\n"
                   "cbuffer PSConstants : register(b0) { float4 _P; };\n"
                   "SamplerState s;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target { return InputTexture0.Sample(s, uv) * _P; }\n");
  EXPECT_TRUE(m->ok()) << all_rendered(*m).size();
  EXPECT_EQ(m->reflection.textures.at(1).binding, 16u);  // the read one has t0
  EXPECT_EQ(m->reflection.find_constant_buffer("PSConstants")->binding, 0u);
}

TEST(BadInput, ConstantBufferStructGlslCannotLayOut) {
  auto m = compile("cb.hlsl",
                   "#pragma fragment frag\n"
                   "struct Light { float power; float3 dir; };\n"
                   "cbuffer Lights : register(b0) {\n"
                   "  Light _Light;\n"
                   "};\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return float4(_Light.dir * _Light.power, 1);\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m),
            (Strings{"cb.hlsl:4:9: error: '_Light' in constant buffer 'Lights': struct 'Light' cannot keep its HLSL "
                     "layout in GLSL: field 'dir' is at offset 4 in HLSL but 16 in std140; reorder its fields or pad "
                     "them to 16-byte registers\n"
                     "      Light _Light;\n"
                     "            ^"}));
}

TEST(BadInput, ConstantBufferMemberInsideStd140Padding) {
  // HLSL packs _Radius into the last register of the array (offset 20); std140 rounds the array
  // up to 32 bytes.
  auto m = compile("cb.hlsl",
                   "#pragma fragment frag\n"
                   "cbuffer Blur : register(b0) {\n"
                   "  float _Weights[2];\n"
                   "  float _Radius;\n"
                   "};\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  return _Weights[0] * _Radius;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m),
            (Strings{"cb.hlsl:4:9: error: '_Radius' is at offset 20 of constant buffer 'Blur', inside the padding "
                     "GLSL gives '_Weights' (up to 32); start '_Radius' on a new 16-byte register (pad before it) or "
                     "declare it before '_Weights'\n"
                     "      float _Radius;\n"
                     "            ^"}));
}

TEST(BadInput, AssignmentToAUniform) {
  auto m = compile("uniform.hlsl",
                   "#pragma fragment frag\n"
                   "float4 _Color;\n"
                   "float _Gloss;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  _Color = float4(uv, 0, 1);\n"
                   "  _Gloss *= 2.0;\n"
                   "  return _Color * _Gloss;\n"
                   "}\n");
  EXPECT_EQ(all_rendered(*m), (Strings{"uniform.hlsl:5:3: error: cannot assign to '_Color': uniforms are read-only\n"
                                       "      _Color = float4(uv, 0, 1);\n"
                                       "      ^",
                                       "uniform.hlsl:6:3: error: cannot assign to '_Gloss': uniforms are read-only\n"
                                       "      _Gloss *= 2.0;\n"
                                       "      ^"}));
}

TEST(BadInput, ArraysOfResourcesAreGlobalsOfASizeNamingTheDeclarationOtherwise) {
  // A global array is one binding of that many descriptors; a parameter, a local or an unsized
  // global (descriptor indexing) has no GLSL form for OpenGL.
  auto m = compile("layers.hlsl",
                   "#pragma fragment frag\n"
                   "Texture2D _Layers[4];\n"
                   "sampler2D _Legacy[2];\n"
                   "SamplerState _Samplers[2];\n"
                   "Texture2D _Bindless[];\n"
                   "float4 pick(Texture2D layers[2], SamplerState s, float2 uv) { return layers[1].Sample(s, uv); }\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target { return _Layers[2].Sample(_Samplers[1], uv); }\n");
  const std::string why = "; arrays of resources are supported as globals of textures, samplers and constant buffers "
                          "only: declare each one separately";
  EXPECT_EQ(headers(*m), (Strings{"layers.hlsl:5:11: error: '_Bindless' is an unsized array of resources "
                                  "(descriptor indexing), which GLSL for OpenGL cannot declare: give it the size the "
                                  "application binds",
                                  "layers.hlsl:6:23: error: parameter 'layers' cannot have type 'Texture2D[2]'" + why}));
}

TEST(BadInput, AFileScopeConstWithoutStaticIsNoArraySize) {
  // As in DXC, `const int N = 4;` at file scope is a uniform in $Globals whose value the host
  // may change, so it cannot size an array; `static const` can.
  auto m = compile("consts.hlsl",
                   "#pragma fragment frag\n"
                   "const int N = 4;\n"
                   "static const int M = 2;\n"
                   "float weights[N];\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  float w[M * 2];\n"
                   "  float v[1 + N];\n"
                   "  return 0;\n"
                   "}\n");
  const std::string why = "array size must be an integer constant; 'N' is a uniform (a file-scope const without "
                          "static); declare it 'static const'";
  EXPECT_EQ(all_rendered(*m), (Strings{"consts.hlsl:4:15: error: " + why + "\n"
                                       "    float weights[N];\n"
                                       "                  ^",
                                       "consts.hlsl:7:11: error: " + why + "\n"
                                       "      float v[1 + N];\n"
                                       "              ^"}));
}

TEST(BadInput, AStatementBeforeTheFirstCaseOfASwitch) {
  auto m = compile("switch.hlsl",
                   "#pragma fragment frag\n"
                   "int _Mode;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  switch (_Mode) {\n"
                   "    uv.x = 1;\n"
                   "    case 0: return 1;\n"
                   "    default: return 0;\n"
                   "  }\n"
                   "}\n");
  EXPECT_EQ(first(*m),
            "switch.hlsl:5:5: error: expected 'case' or 'default' in a switch\n"
            "        uv.x = 1;\n"
            "        ^");
  EXPECT_EQ(m->diagnostics.error_count(), 1u);
}

// A function whose body lost statements to a syntax error is not also warned about as if the
// author forgot a return: the warning would only be noise.
TEST(BadInput, NoMissingReturnWarningAfterASyntaxError) {
  auto m = compile("switch.hlsl",
                   "#pragma fragment frag\n"
                   "int _Mode;\n"
                   "float4 frag(float2 uv : TEXCOORD0) : SV_Target {\n"
                   "  switch (_Mode) {\n"
                   "    case 0: return 1;\n"
                   "    default: return 0 +;\n"
                   "  }\n"
                   "}\n");
  EXPECT_EQ(headers(*m), (Strings{"switch.hlsl:6:24: error: expected an expression"}));
  auto many = compile("many.hlsl",
                      "#pragma fragment frag\n"
                      "float helper(float a) { return a * ; }\n"
                      "float4 frag(float2 uv : TEXCOORD0) : SV_Target { return helper(uv.x); }\n");
  EXPECT_EQ(headers(*many), (Strings{"many.hlsl:2:36: error: expected an expression"}));
}

}  // namespace
}  // namespace xshade::hlsl
