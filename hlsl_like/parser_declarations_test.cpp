// The parser's declarations, one test per production: a whole Unity-style shader, types, structs
// and typedefs, globals and their declarators, functions.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/lexer.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/parser_internal.h"
#include "hlsl_like/parser_test_support.h"

namespace xshade::hlsl::parser_test {
namespace {

TEST(Parser, UnityShaderEndToEnd) {
  auto p = parse_text(kUnityShader);
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  ASSERT_EQ(p->unit.decls.size(), 12u);

  const auto& fixed4 = p->decl<TypedefDecl>(0);
  EXPECT_EQ(fixed4.kind, DeclKind::Typedef);
  EXPECT_EQ(fixed4.name, "fixed4");
  EXPECT_EQ(fixed4.type, Type::vector(ScalarType::Half, 4));

  const auto& appdata = p->decl<StructDecl>(1);
  ASSERT_EQ(appdata.kind, DeclKind::Struct);
  ASSERT_EQ(appdata.fields.size(), 3u);
  EXPECT_EQ(appdata.fields[1].name, "normal");
  EXPECT_EQ(appdata.fields[1].type, Type::vector(ScalarType::Float, 3));
  EXPECT_EQ(appdata.fields[1].semantic, "NORMAL");
  EXPECT_EQ(appdata.fields[2].semantic, "TEXCOORD0");

  const auto& v2f = p->decl<StructDecl>(2);
  ASSERT_EQ(v2f.fields.size(), 5u);
  EXPECT_EQ(v2f.fields[0].semantic, "SV_POSITION");
  EXPECT_EQ(v2f.fields[3].interpolation, Interpolation::NoInterpolation);
  EXPECT_EQ(v2f.fields[3].type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(v2f.fields[4].type, Type::array(Type::scalar(ScalarType::Float), 4));
  EXPECT_EQ(v2f.fields[4].semantic, "");

  const auto& cbuffer = p->decl<CBufferDecl>(3);
  ASSERT_EQ(cbuffer.kind, DeclKind::CBuffer);
  EXPECT_EQ(cbuffer.name, "UnityPerMaterial");
  EXPECT_EQ(cbuffer.binding.register_class, 'b');
  EXPECT_EQ(cbuffer.binding.index, 0u);
  ASSERT_EQ(cbuffer.members.size(), 4u);
  EXPECT_TRUE(cbuffer.members[0]->is_global);
  EXPECT_EQ(cbuffer.members[1]->packing, MatrixPacking::RowMajor);
  EXPECT_EQ(cbuffer.members[1]->type.rows(), 4u);
  const VarDecl& metallic = *cbuffer.members[2];
  ASSERT_EQ(metallic.annotations.size(), 3u);
  EXPECT_EQ(metallic.annotations[0].name, "UIName");
  EXPECT_EQ(metallic.annotations[0].text, "Metallic");
  EXPECT_EQ(metallic.annotations[0].value, nullptr);
  EXPECT_EQ(metallic.annotations[1].name, "UIMin");
  EXPECT_EQ(metallic.annotations[1].type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(sexpr(*metallic.annotations[2].value), "1.0");
  ASSERT_NE(metallic.initializer, nullptr);
  EXPECT_EQ(sexpr(*metallic.initializer), "0.5");
  const VarDecl& bias = *cbuffer.members[3];
  ASSERT_EQ(bias.annotations.size(), 2u);
  EXPECT_EQ(sexpr(*bias.annotations[0].value), "(- 1.5)");
  EXPECT_EQ(sexpr(*bias.annotations[1].value), "(- 2)");

  const VarDecl& main_tex = p->var("_MainTex");
  EXPECT_EQ(main_tex.type, Type::texture2d());
  EXPECT_EQ(main_tex.binding.register_class, 't');
  EXPECT_EQ(main_tex.binding.index, 0u);
  EXPECT_TRUE(main_tex.is_global);
  const VarDecl& sampler = p->var("sampler_MainTex");
  EXPECT_EQ(sampler.type.kind(), TypeKind::SamplerState);
  EXPECT_EQ(sampler.binding.register_class, 's');
  EXPECT_EQ(sampler.binding.space, 1u);
  EXPECT_EQ(p->var("_ShadowTex").type, Type::texture2d());
  EXPECT_EQ(p->var("_ShadowTex").binding.register_class, 0);
  EXPECT_EQ(p->var("_RampTex").type, Type::sampler2d());
  EXPECT_EQ(p->var("_Tint").storage, StorageClass::Uniform);
  const VarDecl& pi = p->var("PI");
  EXPECT_EQ(pi.storage, StorageClass::Static);
  EXPECT_TRUE(pi.is_const);
  EXPECT_EQ(sexpr(*pi.initializer), "3.14159");

  const FunctionDecl& vert = p->function("vert");
  EXPECT_EQ(vert.return_type.kind(), TypeKind::Struct);
  EXPECT_EQ(vert.return_type.struct_decl(), &v2f);
  ASSERT_EQ(vert.params.size(), 1u);
  EXPECT_EQ(vert.params[0]->type.struct_decl(), &appdata);
  ASSERT_EQ(vert.body->statements.size(), 7u);
  const Stmt& loop = *vert.body->statements[5];
  ASSERT_EQ(loop.kind, StmtKind::For);
  ASSERT_EQ(loop.attributes.size(), 1u);
  EXPECT_EQ(loop.attributes[0].name, "unroll");
  const auto& normal = static_cast<const ExprStmt&>(*vert.body->statements[3]);
  EXPECT_EQ(sexpr(*normal.expr),
            "(= (. o worldNormal) (call normalize (call mul (cast float3x3 _ObjectToWorld) (. v normal))))");

  const FunctionDecl& frag = p->function("frag");
  EXPECT_EQ(frag.semantic, "SV_Target");
  EXPECT_EQ(frag.return_type, Type::vector(ScalarType::Half, 4));
  ASSERT_EQ(frag.body->statements.size(), 6u);
  const auto& albedo = static_cast<const DeclStmt&>(*frag.body->statements[2]);
  EXPECT_EQ(sexpr(*albedo.vars[0]->initializer), "(* (method _MainTex Sample sampler_MainTex (. i uv)) _Color)");
  const auto& tint = static_cast<const ExprStmt&>(*frag.body->statements[3]);
  EXPECT_EQ(sexpr(*tint.expr), "(*= (. albedo rgb) (. (call tex2D _RampTex (ctor float2 nd 0.5)) rgb))");
  const auto& discard_if = static_cast<const IfStmt&>(*frag.body->statements[4]);
  ASSERT_EQ(discard_if.kind, StmtKind::If);
  EXPECT_EQ(discard_if.then_branch->kind, StmtKind::Discard);
  EXPECT_EQ(discard_if.else_branch, nullptr);
}

TEST(Parser, ScalarVectorAndMatrixTypes) {
  auto p = parse_text(
      "bool b; int i; uint u; dword d; half h; float f; min16float m16; min10float m10; min16int mi; min16uint mu;\n"
      "float1 f1; int3 i3; half4 h4; bool2 b2; min16float3 m3;\n"
      "float2x3 m23; float4x4 m44; half1x1 h11; int3x2 i32;\n"
      "vector<float, 3> v3; matrix<half, 2, 3> hm; vector vd; matrix md;\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  EXPECT_EQ(p->var("b").type, Type::scalar(ScalarType::Bool));
  EXPECT_EQ(p->var("i").type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(p->var("u").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("d").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("h").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("f").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("m16").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("m10").type, Type::scalar(ScalarType::Half));
  EXPECT_EQ(p->var("mi").type, Type::scalar(ScalarType::Int));
  EXPECT_EQ(p->var("mu").type, Type::scalar(ScalarType::Uint));
  EXPECT_EQ(p->var("f1").type, Type::vector(ScalarType::Float, 1));
  EXPECT_NE(p->var("f1").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("i3").type, Type::vector(ScalarType::Int, 3));
  EXPECT_EQ(p->var("h4").type, Type::vector(ScalarType::Half, 4));
  EXPECT_EQ(p->var("b2").type, Type::vector(ScalarType::Bool, 2));
  EXPECT_EQ(p->var("m3").type, Type::vector(ScalarType::Half, 3));
  const Type& m23 = p->var("m23").type;
  EXPECT_TRUE(m23.is_matrix());
  EXPECT_EQ(m23.rows(), 2u);
  EXPECT_EQ(m23.cols(), 3u);
  EXPECT_EQ(p->var("m44").type, Type::matrix(ScalarType::Float, 4, 4));
  EXPECT_EQ(p->var("h11").type, Type::matrix(ScalarType::Half, 1, 1));
  EXPECT_EQ(p->var("i32").type, Type::matrix(ScalarType::Int, 3, 2));
  EXPECT_EQ(p->var("v3").type, Type::vector(ScalarType::Float, 3));
  EXPECT_EQ(p->var("hm").type, Type::matrix(ScalarType::Half, 2, 3));
  EXPECT_EQ(p->var("vd").type, Type::vector(ScalarType::Float, 4));
  EXPECT_EQ(p->var("md").type, Type::matrix(ScalarType::Float, 4, 4));
}

TEST(Parser, DoubleIsReportedAndReadAsFloat) {
  auto p = parse_text("double x;\ndouble3 y = double3(1, 2, 3);\n");
  EXPECT_EQ(p->errors(), (std::vector<std::string>{"1:1: double is not supported", "2:1: double is not supported",
                                                   "2:13: double is not supported"}));
  EXPECT_EQ(p->var("x").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("y").type, Type::vector(ScalarType::Float, 3));
}

TEST(Parser, StructAndTypedefNamesAreTypes) {
  auto p = parse_text(
      "struct Light { float3 dir; float3 color; };\n"
      "typedef float3 Color;\n"
      "typedef Light Lamp;\n"
      "Light lights[2];\n"
      "Color tint;\n"
      "float3 f(Lamp l) { Light copy = (Light)0; Color c = (Color)(l.color); return c * copy.color; }\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const auto& light = p->decl<StructDecl>(0);
  const Type& lights = p->var("lights").type;
  ASSERT_EQ(lights.kind(), TypeKind::Array);
  EXPECT_EQ(lights.array_length(), 2u);
  EXPECT_EQ(lights.element().struct_decl(), &light);
  EXPECT_EQ(lights.name(), "Light[2]");
  EXPECT_EQ(p->var("tint").type, Type::vector(ScalarType::Float, 3));
  const FunctionDecl& f = p->function("f");
  EXPECT_EQ(f.params[0]->type.struct_decl(), &light);
  const auto& copy = static_cast<const DeclStmt&>(*f.body->statements[0]);
  EXPECT_EQ(sexpr(*copy.vars[0]->initializer), "(cast Light 0)");
  const auto& c = static_cast<const DeclStmt&>(*f.body->statements[1]);
  EXPECT_EQ(sexpr(*c.vars[0]->initializer), "(cast float3 (. l color))");
}

TEST(Parser, GlobalQualifiersArraysAndDeclarators) {
  auto p = parse_text(
      "static const float2 kKernel[3] = { float2(0, 0), float2(0.5, 0), float2(1, 0) };\n"
      "static const float kWeights[] = { 0.25, 0.5, 0.25 };\n"
      "static const float2 kFlat[] = { 0, 0, 1, 1 };\n"
      "float a, b = 1, c[2];\n"
      "column_major float3x4 cm;\n"
      "static const int N = 2 * 2;\n"
      "float sized[N + 1];\n"
      "sampler s;\n"
      "float m2[2][3];\n"
      "static const int nested[2][2] = { { 1, 2 }, { 3, 4 } };\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  const VarDecl& kernel = p->var("kKernel");
  EXPECT_EQ(kernel.type, Type::array(Type::vector(ScalarType::Float, 2), 3));
  EXPECT_EQ(sexpr(*kernel.initializer), "{ (ctor float2 0 0) (ctor float2 0.5 0) (ctor float2 1 0) }");
  // Unsized arrays stay unsized (length 0): semantic analysis counts their initializers.
  EXPECT_EQ(p->var("kWeights").type.array_length(), 0u);
  EXPECT_EQ(p->var("kFlat").type.array_length(), 0u);
  EXPECT_EQ(p->var("a").type, Type::scalar(ScalarType::Float));
  EXPECT_EQ(p->var("a").initializer, nullptr);
  EXPECT_EQ(sexpr(*p->var("b").initializer), "1");
  EXPECT_EQ(p->var("c").type, Type::array(Type::scalar(ScalarType::Float), 2));
  EXPECT_EQ(p->var("cm").packing, MatrixPacking::ColumnMajor);
  EXPECT_EQ(p->var("cm").type.rows(), 3u);
  EXPECT_EQ(p->var("cm").type.cols(), 4u);
  EXPECT_TRUE(p->var("N").is_const);
  EXPECT_EQ(p->var("N").storage, StorageClass::Static);
  EXPECT_EQ(p->var("sized").type.array_length(), 5u);
  EXPECT_EQ(p->var("s").type, Type::sampler2d());
  const Type& m2 = p->var("m2").type;
  EXPECT_EQ(m2.array_length(), 2u);
  EXPECT_EQ(m2.element().array_length(), 3u);
  EXPECT_EQ(sexpr(*p->var("nested").initializer), "{ { 1 2 } { 3 4 } }");
}

TEST(Parser, FunctionsParametersAndPrototypes) {
  auto p = parse_text(
      "float helper(float x);\n"
      "void vert(in float4 pos : POSITION, out float4 o : SV_Position, inout float k,\n"
      "          uniform float4x4 mvp, centroid float2 uv : TEXCOORD0, float scale = 2.0) {\n"
      "  o = mul(mvp, pos) * scale;\n"
      "}\n"
      "[numthreads(8, 8, 1)] void cs(void) {}\n"
      "float helper(float x) { return x; }\n"
      "float noname(float, int);\n");
  ASSERT_EQ(p->errors(), std::vector<std::string>{});
  ASSERT_EQ(p->unit.decls.size(), 5u);
  const auto& prototype = p->decl<FunctionDecl>(0);
  EXPECT_EQ(prototype.body, nullptr);
  ASSERT_EQ(prototype.params.size(), 1u);
  const FunctionDecl& vert = p->function("vert");
  ASSERT_EQ(vert.params.size(), 6u);
  EXPECT_EQ(vert.return_type.kind(), TypeKind::Void);
  EXPECT_TRUE(vert.params[0]->explicit_in);
  EXPECT_EQ(vert.params[0]->direction, ParamDirection::In);
  EXPECT_EQ(vert.params[0]->semantic, "POSITION");
  EXPECT_EQ(vert.params[1]->direction, ParamDirection::Out);
  EXPECT_EQ(vert.params[1]->semantic, "SV_Position");
  EXPECT_EQ(vert.params[2]->direction, ParamDirection::InOut);
  EXPECT_FALSE(vert.params[2]->explicit_in);
  EXPECT_TRUE(vert.params[3]->is_uniform);
  EXPECT_EQ(vert.params[4]->interpolation, Interpolation::Centroid);
  EXPECT_EQ(vert.params[4]->name, "uv");
  ASSERT_NE(vert.params[5]->default_value, nullptr);
  EXPECT_EQ(sexpr(*vert.params[5]->default_value), "2.0");
  const auto& cs = p->decl<FunctionDecl>(2);
  EXPECT_EQ(cs.params.size(), 0u);
  ASSERT_EQ(cs.attributes.size(), 1u);
  EXPECT_EQ(cs.attributes[0].name, "numthreads");
  EXPECT_EQ(sexpr_list(cs.attributes[0].args), " 8 8 1");
  const auto& noname = p->decl<FunctionDecl>(4);
  ASSERT_EQ(noname.params.size(), 2u);
  EXPECT_EQ(noname.params[0]->name, "");
}

}  // namespace
}  // namespace xshade::hlsl::parser_test
