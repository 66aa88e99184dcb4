// Names as HLSL scopes them: a variable named like a type hides it (C's rule, which DXC keeps),
// and an entry point's name must name one function (DXC's rule).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl {
namespace {

std::unique_ptr<Module> names_compile(const std::string& text) { return compile_text("names.hlsl", text, {}); }

// Every diagnostic as "line:col: severity: message", without the file name.
std::vector<std::string> names_messages(const Module& module) {
  std::vector<std::string> out;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) {
    std::string text = d.to_string();
    if (text.rfind("names.hlsl:", 0) == 0) text = text.substr(std::string("names.hlsl:").size());
    out.push_back(text);
  }
  return out;
}

const FunctionDecl& names_function(const Module& module, const std::string& name) {
  for (const auto& decl : module.unit.decls)
    if (decl && decl->kind == DeclKind::Function && decl->name == name && static_cast<const FunctionDecl&>(*decl).body)
      return static_cast<const FunctionDecl&>(*decl);
  throw std::runtime_error("no function " + name);
}

const VarDecl& names_local(const FunctionDecl& function, size_t statement) {
  return *static_cast<const DeclStmt&>(*function.body->statements.at(statement)).vars.at(0);
}

// Unity URP's Lit shader writes this: a local named like the vertex input struct.
constexpr const char* kUrpLike =
    "#pragma vertex vert\n"
    "#pragma fragment frag\n"
    "struct Attributes { float4 pos : POSITION; };\n"
    "struct VertexPositionInputs { float4 positionCS; float3 positionWS; };\n"
    "VertexPositionInputs GetVertexPositionInputs(float4 p) {\n"
    "  VertexPositionInputs o;\n"
    "  o.positionCS = p * 2.0;\n"
    "  o.positionWS = p.xyz;\n"
    "  return o;\n"
    "}\n"
    "float4 vert(Attributes v) : SV_Position {\n"
    "  VertexPositionInputs Attributes = GetVertexPositionInputs(v.pos);\n"
    "  float4 p = Attributes.positionCS;\n"
    "  return p;\n"
    "}\n"
    "float4 frag() : SV_Target { Attributes a = (Attributes)0; return a.pos; }\n";

TEST(Names, AVariableNamedLikeAStructIsTheVariableAfterItsDeclarator) {
  auto module = names_compile(kUrpLike);
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const FunctionDecl& vert = names_function(*module, "vert");
  const VarDecl& attributes = names_local(vert, 0);
  EXPECT_EQ(attributes.name, "Attributes");
  EXPECT_EQ(attributes.type.name(), "VertexPositionInputs");
  // `Attributes.positionCS` reads the variable's field, a float4.
  const Expr& read = *names_local(vert, 1).initializer;
  ASSERT_EQ(read.kind, ExprKind::Member);
  const Expr& object = *static_cast<const MemberExpr&>(read).object;
  ASSERT_EQ(object.kind, ExprKind::Name);
  EXPECT_EQ(static_cast<const NameExpr&>(object).decl, &attributes);
  EXPECT_EQ(read.type.name(), "float4");
  // In another function the struct is a type again.
  EXPECT_EQ(names_local(names_function(*module, "frag"), 0).type.name(), "Attributes");
}

TEST(Names, TheTypeIsAnErrorWhereTheVariableHidesIt) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "struct Light { float4 color; };\n"
      "float4 frag() : SV_Target {\n"
      "  float4 Light = 1;\n"
      "  Light x;\n"
      "  return Light;\n"
      "}\n");
  EXPECT_EQ(names_messages(*module),
            (std::vector<std::string>{
                "5:3: error: 'Light' is a variable here, not a type: a variable named like a type hides it to the end "
                "of the variable's scope; rename the variable to use the type here",
                "4:10: note: the variable 'Light' that hides the type is declared here"}));
}

TEST(Names, TheTypeComesBackWhereTheVariablesScopeEnds) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "struct S { float a; };\n"
      "typedef float2 T;\n"
      "float4 frag() : SV_Target {\n"
      "  float r = 0;\n"
      "  { float S = 1; T T = 2; r += S + T.y; }\n"
      "  for (int S = 0; S < 2; ++S) r += S;\n"
      "  S s = (S)0;\n"
      "  T t = 1;\n"
      "  return r + s.a + t.x;\n"
      "}\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const FunctionDecl& frag = names_function(*module, "frag");
  EXPECT_EQ(names_local(frag, 3).type.name(), "S");
  EXPECT_EQ(names_local(frag, 4).type.name(), "float2");
}

TEST(Names, AParameterOrGlobalHidesATypeToo) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "struct Surface { float4 albedo; };\n"
      "struct Params { float4 tint; };\n"
      "Params Params;\n"
      "float4 shade(Surface Surface) { return Surface.albedo * Params.tint; }\n"
      "float4 frag() : SV_Target { Surface s = (Surface)0; return shade(s); }\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const FunctionDecl& shade = names_function(*module, "shade");
  EXPECT_EQ(shade.params.at(0)->name, "Surface");
  // A global of a scope holds its name to the file's end: `Params x;` after it is an error.
  module = names_compile(
      "struct Params { float4 tint; };\n"
      "Params Params;\n"
      "Params other;\n");
  ASSERT_FALSE(module->ok());
  EXPECT_EQ(names_messages(*module).at(0),
            "3:1: error: 'Params' is a variable here, not a type: a variable named like a type hides it to the end "
            "of the variable's scope; rename the variable to use the type here");
  EXPECT_EQ(names_messages(*module).at(1), "2:8: note: the variable 'Params' that hides the type is declared here");
}

TEST(Names, TheInitializerSeesTheVariableAsCDoes) {
  // C's point of declaration is the end of the declarator: `(S)0` in the initializer names the
  // variable, which DXC reports too.
  auto module = names_compile(
      "#pragma fragment frag\n"
      "struct S { float a; };\n"
      "float4 frag() : SV_Target { S S = (S)0; return S.a; }\n");
  EXPECT_FALSE(module->ok());
}

TEST(Names, AFieldMayBeNamedLikeATypeAndHidesNothing) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "struct Light { float4 color; };\n"
      "struct Scene { Light Light; };\n"
      "float4 frag() : SV_Target { Scene s = (Scene)0; Light l = s.Light; return l.color; }\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
}

// ---------------------------------------------------------------------------------------------
// Entry points with several declarations

TEST(Names, APrototypeAndTheDefinitionOfAnEntryPointAreOneFunction) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "float4 frag(float4 p : SV_Position) : SV_Target;\n"
      "float4 frag(float4 p : SV_Position) : SV_Target { return p; }\n");
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  ASSERT_NE(module->entry_points.fragment, nullptr);
  EXPECT_NE(module->entry_points.fragment->body, nullptr);
  EXPECT_EQ(module->entry_points.fragment->loc.line, 3u);
}

TEST(Names, AnOverloadedEntryPointIsAmbiguousNamingBothDefinitions) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "float4 frag(float4 p : SV_Position) : SV_Target { return p; }\n"
      "float4 frag(float2 uv : TEXCOORD0) : SV_Target { return uv.xyxy; }\n");
  EXPECT_EQ(
      names_messages(*module),
      (std::vector<std::string>{
          "3:8: error: fragment entry point 'frag' is ambiguous: 'float4 frag(float2)' is defined here and "
          "'float4 frag(float4)' at names.hlsl:2:8; an entry point cannot be overloaded: rename or remove all "
          "but one of them",
          "2:8: note: 'float4 frag(float4)' is defined here", "1:18: note: named the fragment entry point here"}));
}

TEST(Names, AnOverloadWithoutABodyStillMakesTheEntryPointAmbiguous) {
  // DXC: every function of the name counts, defined or not (SemaHLSL's "ambiguous entry point
  // function"); only redeclarations of one parameter list are one function.
  auto module = names_compile(
      "#pragma vertex vert\n"
      "#pragma fragment frag\n"
      "float4 vert(uint id : SV_VertexID) : SV_Position;\n"
      "float4 vert(float4 p : POSITION) : SV_Position { return p; }\n"
      "float4 frag() : SV_Target { return 1; }\n");
  const std::vector<std::string> messages = names_messages(*module);
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[0],
            "4:8: error: vertex entry point 'vert' is ambiguous: 'float4 vert(float4)' is defined here and "
            "'float4 vert(uint)' at names.hlsl:3:8; an entry point cannot be overloaded: rename or remove all but one "
            "of them");
  EXPECT_EQ(messages[1], "3:8: note: 'float4 vert(uint)' is declared here");
}

TEST(Names, AnEntryPointWithOnlyAPrototypeSaysWhereItIsDeclared) {
  auto module = names_compile(
      "#pragma fragment frag\n"
      "float4 frag() : SV_Target;\n");
  EXPECT_EQ(names_messages(*module),
            (std::vector<std::string>{"1:18: error: entry point 'frag' is not defined",
                                      "2:8: note: 'float4 frag()' is declared here, without a body; give it one"}));
}

}  // namespace
}  // namespace xshade::hlsl
