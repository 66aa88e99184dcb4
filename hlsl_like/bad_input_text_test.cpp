// The front end on bad input, end to end, continued: the preprocessor, the lexer, hostile sizes,
// many errors at once, resources and constant buffers.
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
  EXPECT_EQ(all_rendered(*m),
            (Strings{"macro.hlsl:5:13: warning: macro 'A' refers to itself; it is not expanded again\n"
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
  EXPECT_EQ(
      headers(*m),
      (Strings{
          "garbage.hlsl:2:1: error: unknown character '\\x01'", "garbage.hlsl:2:2: error: unknown character '\\x02'",
          "garbage.hlsl:2:3: error: unknown character '\\xFF'", "garbage.hlsl:2:4: error: unknown character '\\xFE'",
          "garbage.hlsl:2:5: error: unknown character '\\x80'", "garbage.hlsl:2:13: error: unknown character '\\x00'",
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
  EXPECT_EQ(first(*m),
            "long.hlsl:2:1037: error: nesting is too deep (more than 256 levels)\n"
            "    ..." +
                line.substr(976, 120) +
                "\n"
                "       " +
                std::string(60, ' ') + "^");
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
                   "  return " +
                       name +
                       ";\n"
                       "}\n");
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_EQ(m->diagnostics.error_count(), 1u);
  ASSERT_LT(m->diagnostics.render_all().size(), kShortRender);  // stops before printing 1 MiB
  EXPECT_EQ(first(*m), "long.hlsl:3:10: error: unknown name '" + std::string(64, 'a') +
                           "...'\n"
                           "      return " +
                           std::string(111, 'a') +
                           "\n"
                           "             ^");
}

TEST(BadInput, TenThousandNestedParentheses) {
  const size_t depth = 10000;
  const std::string text =
      "#pragma fragment frag\n"
      "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
      "  float x = " +
      std::string(depth, '(') + "1" + std::string(depth, ')') +
      ";\n"
      "  return x;\n"
      "}\n";
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("deep.hlsl", text);
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_EQ(m->diagnostics.error_count(), 1u) << m->diagnostics.render_all().substr(0, kShortRender);
  EXPECT_LT(m->diagnostics.render_all().size(), kShortRender);
  // The 257th '(' (column 13 + 256) is one level too many.
  EXPECT_EQ(first(*m),
            "deep.hlsl:3:269: error: nesting is too deep (more than 256 levels)\n"
            "    ..." +
                std::string(120, '(') +
                "\n"
                "       " +
                std::string(60, ' ') + "^");
}

TEST(BadInput, TenThousandNestedBraces) {
  const size_t depth = 10000;
  const std::string text =
      "#pragma fragment frag\n"
      "float4 frag(float4 pos : SV_Position) : SV_Target {\n"
      "  " +
      std::string(depth, '{') + std::string(depth, '}') +
      "\n"
      "  return 1;\n"
      "}\n";
  const auto start = std::chrono::steady_clock::now();
  auto m = compile("deep.hlsl", text);
  EXPECT_LT(seconds_since(start), kFastSeconds * kTimeScale);
  EXPECT_LT(m->diagnostics.render_all().size(), kShortRender);
  // The 257th '{' (column 3 + 256) is one level too many.
  EXPECT_EQ(all_rendered(*m), (Strings{"deep.hlsl:3:259: error: nesting is too deep (more than 256 levels)\n"
                                       "    ..." +
                                       std::string(120, '{') +
                                       "\n"
                                       "       " +
                                       std::string(60, ' ') + "^"}));
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
  std::string text =
      "#pragma fragment frag\n"
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
  EXPECT_EQ(all_rendered(*m),
            (Strings{"trunc.hlsl:4:16: warning: implicit truncation of vector type from 'float4' to 'float3'\n"
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
  EXPECT_EQ(all_rendered(*m),
            (Strings{"reg.hlsl:3:24: error: register t0 of '_DetailTex' is already taken by '_MainTex', and the "
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
  EXPECT_EQ(all_rendered(*m),
            (Strings{"reg.hlsl:3:13: error: register b1 of 'B' is already taken by 'A', and the entry points "
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
  const std::string why =
      "; arrays of resources are supported as globals of textures, samplers and constant buffers "
      "only: declare each one separately";
  EXPECT_EQ(headers(*m),
            (Strings{"layers.hlsl:5:11: error: '_Bindless' is an unsized array of resources "
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
  const std::string why =
      "array size must be an integer constant; 'N' is a uniform (a file-scope const without "
      "static); declare it 'static const'";
  EXPECT_EQ(all_rendered(*m), (Strings{"consts.hlsl:4:15: error: " + why +
                                           "\n"
                                           "    float weights[N];\n"
                                           "                  ^",
                                       "consts.hlsl:7:11: error: " + why +
                                           "\n"
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
}  // namespace xshade::hlsl::bad_input
