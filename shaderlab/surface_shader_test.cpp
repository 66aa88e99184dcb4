#include "shaderlab/surface_shader.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace xshade::shaderlab {
namespace {

ProgramBlock surface_block(const std::string& pragma) {
  ProgramBlock block;
  block.text =
      "\n  struct Input { float2 uv_MainTex; };\n  " + pragma + "\n  void surf(Input IN, inout SurfaceOutput o) {}\n";
  block.start = {"toon.shader", 10, 5};
  return block;
}

SurfaceDirective directive_of(const std::string& pragma) {
  auto directive = read_surface_directive(surface_block(pragma));
  EXPECT_TRUE(directive) << directive.error().to_string();
  return directive ? *directive : SurfaceDirective{};
}

// What a surface program of Lambert's shape reads: Input's uv, SurfaceOutput's fields.
SurfaceProgramShape lambert_shape() {
  SurfaceProgramShape shape;
  shape.input = {{"float2", "uv_MainTex", ""}};
  shape.output_type = "SurfaceOutput";
  shape.output_fields = {"Albedo", "Normal", "Emission", "Specular", "Gloss", "Alpha"};
  shape.lighting = LightingForm::Gi;
  shape.vertex_input_fields = {"vertex", "tangent", "normal", "texcoord", "texcoord1", "color"};
  return shape;
}

const std::string& text_of(const Pass& pass) { return pass.program->text; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(SurfaceDirective, ReadsTheFunctionTheModelAndEachOptionAtThePragmasLine) {
  const SurfaceDirective directive = directive_of("#pragma surface surf Toon alpha:fade vertex:vert addshadow // why");
  EXPECT_EQ(directive.function, "surf");
  EXPECT_EQ(directive.lighting_model, "Toon");
  EXPECT_EQ(directive.value("alpha"), "fade");
  EXPECT_EQ(directive.value("vertex"), "vert");
  EXPECT_TRUE(directive.has("addshadow"));
  EXPECT_FALSE(directive.has("why"));
  EXPECT_EQ(directive.where.line, 12u);  // the block's text starts at line 10 with a line break
}

TEST(SurfaceDirective, WhatUnityDoesNotHaveOrXshadeDoesNotGenerateIsAnErrorAtThePragma) {
  for (const auto& [pragma, says] : std::vector<std::pair<std::string, std::string>>{
           {"#pragma surface surf", "needs a surface function and a lighting model"},
           {"#pragma surface surf Lambert shiny", "has no option 'shiny'"},
           {"#pragma surface surf Lambert vertex", "takes a value"},
           {"#pragma surface surf Lambert tessellate:tess", "tessellation stage"}}) {
    auto directive = read_surface_directive(surface_block(pragma));
    ASSERT_FALSE(directive) << pragma;
    EXPECT_EQ(directive.error().where.line, 12u) << pragma;
    EXPECT_TRUE(contains(directive.error().message, says)) << directive.error().message;
  }
  ProgramBlock without;
  without.text = "void surf() {}";
  EXPECT_FALSE(read_surface_directive(without));
}

TEST(SurfaceShader, GeneratesForwardBaseAndForwardAddAsUnityDoesAndTheShadowCasterOnlyWithAddshadow) {
  const ProgramBlock block = surface_block("#pragma surface surf Lambert");
  std::vector<Pass> passes =
      generate_surface_passes(block, {}, directive_of("#pragma surface surf Lambert"), lambert_shape());
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_EQ(tag(passes[0].tags, "LightMode"), "ForwardBase");
  EXPECT_FALSE(passes[0].state.zwrite);  // Unity's defaults: ZWrite On, no blending
  EXPECT_TRUE(passes[0].state.blend.empty());
  EXPECT_EQ(tag(passes[1].tags, "LightMode"), "ForwardAdd");
  ASSERT_EQ(passes[1].state.blend.size(), 1u);
  EXPECT_EQ(passes[1].state.blend[0].source.text, "One");
  EXPECT_EQ(passes[1].state.blend[0].destination.text, "One");
  EXPECT_EQ(passes[1].state.zwrite->text, "Off");
  for (const Pass& pass : passes) {
    EXPECT_TRUE(pass.generated);
    EXPECT_TRUE(contains(text_of(pass), "#line 10 \"toon.shader\""));  // the author's text, where it is
    EXPECT_TRUE(contains(text_of(pass), "//#pragma surface surf Lambert"));
    EXPECT_TRUE(contains(text_of(pass), "float4 _MainTex_ST;"));  // each program declares what it reads
  }
  // After the author's text, the generated lines are named by the pass and numbered as its text's.
  const std::string& base = text_of(passes[0]);
  const size_t back = base.rfind("#line ");
  const auto next_line = std::count(base.begin(), base.begin() + static_cast<long>(back), '\n') + 2;
  EXPECT_EQ(base.substr(back, base.find('\n', back) - back),
            "#line " + std::to_string(next_line) + " \"toon.shader (generated ForwardBase pass)\"");
  EXPECT_EQ(passes[0].program->start.file, "toon.shader (generated ForwardBase pass)");
  EXPECT_TRUE(contains(text_of(passes[0]), "#pragma multi_compile_fwdbase"));
  EXPECT_TRUE(contains(text_of(passes[0]), "LightingLambert_GI(o, giInput, gi);"));
  EXPECT_TRUE(contains(text_of(passes[0]), "UNITY_OPAQUE_ALPHA(c.a);"));
  EXPECT_TRUE(contains(text_of(passes[1]), "#pragma multi_compile_fwdadd\n"));
  EXPECT_TRUE(contains(text_of(passes[1]), "gi.light.color *= atten;"));
  EXPECT_FALSE(contains(text_of(passes[1]), "_GI("));  // an additive light has no indirect part

  passes = generate_surface_passes(block, {}, directive_of("#pragma surface surf Lambert noforwardadd addshadow"),
                                   lambert_shape());
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_EQ(tag(passes[1].tags, "LightMode"), "ShadowCaster");
  EXPECT_TRUE(contains(text_of(passes[1]), "TRANSFER_SHADOW_CASTER_NORMALOFFSET(o)"));
  EXPECT_TRUE(contains(text_of(passes[1]), "SHADOW_CASTER_FRAGMENT(IN)"));
  EXPECT_TRUE(generate_surface_passes(block, {}, directive_of("#pragma surface surf Lambert exclude_path:forward"),
                                      lambert_shape())
                  .empty());
}

TEST(SurfaceShader, AlphaAndDecalSetTheBlendOfUnitysManual) {
  const ProgramBlock block = surface_block("");
  const auto base_of = [&](const std::string& options, const SurfaceProgramShape& shape) {
    return generate_surface_passes(block, {}, directive_of("#pragma surface surf Lambert " + options), shape).front();
  };
  const Pass fade = base_of("alpha:fade", lambert_shape());
  ASSERT_EQ(fade.state.blend.size(), 1u);
  EXPECT_EQ(fade.state.blend[0].source.text, "SrcAlpha");
  EXPECT_EQ(fade.state.blend[0].destination.text, "OneMinusSrcAlpha");
  EXPECT_EQ(fade.state.zwrite->text, "Off");
  EXPECT_TRUE(contains(text_of(fade), "#define _ALPHABLEND_ON 1"));
  EXPECT_TRUE(contains(text_of(fade), "multi_compile_fwdbasealpha noshadow"));
  EXPECT_FALSE(contains(text_of(fade), "UNITY_OPAQUE_ALPHA"));
  // `alpha` alone is premultiplied for the physically based models.
  SurfaceProgramShape standard = lambert_shape();
  standard.output_type = "SurfaceOutputStandard";
  standard.lighting = LightingForm::ViewGi;
  const Pass premultiplied =
      generate_surface_passes(block, {}, directive_of("#pragma surface surf Standard alpha"), standard).front();
  EXPECT_EQ(premultiplied.state.blend[0].source.text, "One");
  EXPECT_TRUE(contains(text_of(premultiplied), "#define _ALPHAPREMULTIPLY_ON 1"));
  EXPECT_TRUE(contains(text_of(premultiplied), "#include \"UnityPBSLighting.cginc\""));
  EXPECT_TRUE(contains(text_of(premultiplied), "c += LightingStandard (o, worldViewDir, gi);"));
  const Pass decal = base_of("decal:add", lambert_shape());
  EXPECT_EQ(decal.state.blend[0].source.text, "One");
  ASSERT_TRUE(decal.state.offset);
  EXPECT_EQ(decal.state.offset->first.text, "-1");
  const Pass kept = base_of("keepalpha", lambert_shape());
  EXPECT_FALSE(contains(text_of(kept), "UNITY_OPAQUE_ALPHA"));
}

TEST(SurfaceShader, ALegacyLightingFunctionGetsTheLightDirectionAttenuationAndSHAmbientTimesAlbedo) {
  SurfaceProgramShape shape = lambert_shape();
  shape.lighting = LightingForm::LegacyView;
  const auto passes = generate_surface_passes(surface_block(""), {}, directive_of("#pragma surface surf Toon"), shape);
  const std::string& base = text_of(passes[0]);
  EXPECT_TRUE(contains(base, "c += LightingToon (o, lightDir, worldViewDir, atten);"));
  EXPECT_TRUE(contains(base, "c.rgb += o.Albedo * IN.sh;"));
  EXPECT_TRUE(contains(base, "o.sh = ShadeSH9(float4(worldNormal, 1.0));"));
  EXPECT_FALSE(contains(base, "UnityGI gi;"));
  const std::string half_vector = text_of(
      generate_surface_passes(surface_block(""), {}, directive_of("#pragma surface surf Toon halfasview"), shape)[0]);
  EXPECT_TRUE(contains(half_vector, "LightingToon (o, lightDir, normalize(lightDir + worldViewDir), atten)"));
}

TEST(SurfaceShader, UvsTravelTwoToAnInterpolatorAndATangentSpaceNormalCarriesTheWorldPositionInW) {
  SurfaceProgramShape shape = lambert_shape();
  shape.input = {{"float2", "uv_MainTex", ""},          {"float2", "uv_BumpMap", ""},
                 {"float2", "uv2_Detail", ""},          {"float3", "viewDir", ""},
                 {"float4", "color", "COLOR"},          {"float3", "worldNormal", ""},
                 {"half3", "internalSurfaceTtoW0", ""}, {"half3", "internalSurfaceTtoW1", ""},
                 {"half3", "internalSurfaceTtoW2", ""}};
  shape.writes_normal = true;
  const std::string base =
      text_of(generate_surface_passes(surface_block(""), {}, directive_of("#pragma surface surf Lambert"), shape)[0]);
  EXPECT_TRUE(contains(base, "float4 pack0 : TEXCOORD0;"));
  EXPECT_TRUE(contains(base, "float4 pack1 : TEXCOORD1;"));
  EXPECT_FALSE(contains(base, "pack2"));
  EXPECT_TRUE(contains(base, "o.pack0.xy = TRANSFORM_TEX(v.texcoord, _MainTex);"));
  EXPECT_TRUE(contains(base, "o.pack0.zw = TRANSFORM_TEX(v.texcoord, _BumpMap);"));
  EXPECT_TRUE(contains(base, "o.pack1.xy = TRANSFORM_TEX(v.texcoord1, _Detail);"));
  EXPECT_TRUE(contains(base, "surfIN.uv_BumpMap = IN.pack0.zw;"));
  EXPECT_TRUE(contains(base, "float4 _MainTex_ST;"));
  EXPECT_TRUE(contains(base, "float4 tSpace0 : TEXCOORD2;"));
  EXPECT_FALSE(contains(base, "float3 worldPos :"));
  EXPECT_TRUE(contains(base, "float3 worldPos = float3(IN.tSpace0.w, IN.tSpace1.w, IN.tSpace2.w);"));
  EXPECT_TRUE(contains(base, "surfIN.viewDir = _unity_tbn_0 * worldViewDir.x"));  // tangent space
  EXPECT_TRUE(contains(base, "surfIN.internalSurfaceTtoW2 = _unity_tbn_2;"));
  EXPECT_TRUE(contains(base, "surfIN.color = IN.color;"));
  EXPECT_TRUE(contains(base, "o.Normal = worldN;"));
  EXPECT_TRUE(contains(base, "#define WorldNormalVector(data,normal) fixed3(dot(data.internalSurfaceTtoW0,normal)"));
}

TEST(SurfaceShader, AVertexModifierThatFillsInputPassesItsFieldsAndAlphatestClipsAfterTheSurfaceFunction) {
  SurfaceProgramShape shape = lambert_shape();
  shape.input.push_back({"float3", "localPos", ""});
  shape.vertex_fills_input = true;
  shape.vertex_input_type = "appdata_full";
  const std::string base = text_of(generate_surface_passes(
      surface_block(""), {},
      directive_of("#pragma surface surf Lambert vertex:displace alphatest:_Cutoff finalcolor:tint"), shape)[0]);
  EXPECT_TRUE(contains(base, "displace (v, customInputData);"));
  EXPECT_TRUE(contains(base, "o.custom_localPos = customInputData.localPos;"));
  EXPECT_TRUE(contains(base, "surfIN.localPos = IN.custom_localPos;"));
  EXPECT_TRUE(contains(base, "fixed _Cutoff;"));  // the program declared none
  EXPECT_LT(base.find("surf (surfIN, o);"), base.find("clip(o.Alpha - _Cutoff);"));
  EXPECT_LT(base.find("c += LightingLambert"), base.find("tint (surfIN, o, c);"));
  EXPECT_LT(base.find("tint (surfIN, o, c);"), base.find("UNITY_APPLY_FOG"));
}

}  // namespace
}  // namespace xshade::shaderlab
