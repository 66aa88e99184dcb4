#include "harness/render/surface_program.h"

#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "harness/render/material_source.h"
#include "shaderlab/reader.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// Unity's include files, which xshade does not ship: the corpus beside the project has them.
const fs::path kUnityIncludes =
    fs::path(XSHADE_REALWORLD_CORPUS) / "TwoTailsGames+Unity-Built-in-Shaders" / "CGIncludes";

class SurfaceProgram : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::is_directory(kUnityIncludes)) GTEST_SKIP() << "no Unity include files at " << kUnityIncludes;
    folder_ = fs::path(::testing::TempDir()) / "xshade_surface_program";
    fs::create_directories(folder_);
    options_.include_dirs = {kUnityIncludes};
  }
  fs::path write(const std::string& name, const std::string& program) {
    const fs::path path = folder_ / name;
    std::ofstream(path) << "Shader \"Test/" << name << "\" {\n  SubShader {\n    CGPROGRAM\n"
                        << program << "\n    ENDCG\n  }\n}\n";
    return path;
  }
  Result<shaderlab::SurfaceProgramShape> shape_of(const fs::path& path) {
    auto shader = shaderlab::read_shader_file(path);
    EXPECT_TRUE(shader) << shader.error().to_string();
    const shaderlab::SubShader& sub = shader->subshaders.at(0);
    auto directive = shaderlab::read_surface_directive(*sub.surface);
    EXPECT_TRUE(directive) << directive.error().to_string();
    return read_surface_program(path, sub, *directive, options_, shaderlab::UnityPlatform::GLCore);
  }

  fs::path folder_;
  hlsl::CompileOptions options_;
};

constexpr const char* kToon = R"(
    #pragma surface surf Toon vertex:displace alphatest:_Cutoff
    sampler2D _MainTex, _BumpMap;
    struct Input { float2 uv_MainTex; float3 viewDir; float3 localPos; INTERNAL_DATA };
    void displace(inout appdata_full v, out Input o) { UNITY_INITIALIZE_OUTPUT(Input, o); o.localPos = v.vertex.xyz; }
    void surf(Input IN, inout SurfaceOutput o) {
      o.Albedo = tex2D(_MainTex, IN.uv_MainTex).rgb * frac(IN.localPos);
      o.Normal = UnpackNormal(tex2D(_BumpMap, IN.uv_MainTex));
      o.Alpha = 1;
    }
    half4 LightingToon(SurfaceOutput s, half3 lightDir, half3 viewDir, half atten) {
      return half4(s.Albedo * step(0.5, dot(s.Normal, lightDir)) * atten, s.Alpha);
    })";

TEST_F(SurfaceProgram, TheFrontEndReadsInputTheOutputTheLightingFormAndAWrittenNormal) {
  auto shape = shape_of(write("toon.shader", kToon));
  ASSERT_TRUE(shape) << shape.error().to_string();
  std::vector<std::string> input;
  for (const shaderlab::SurfaceField& field : shape->input) input.push_back(field.name);
  EXPECT_EQ(input, (std::vector<std::string>{"uv_MainTex", "viewDir", "localPos", "internalSurfaceTtoW0",
                                             "internalSurfaceTtoW1", "internalSurfaceTtoW2"}));
  EXPECT_EQ(shape->output_type, "SurfaceOutput");
  EXPECT_EQ(shape->lighting, shaderlab::LightingForm::LegacyView);
  EXPECT_TRUE(shape->writes_normal);
  EXPECT_TRUE(shape->vertex_fills_input);
  EXPECT_EQ(shape->vertex_input_type, "appdata_full");
  EXPECT_NE(std::find(shape->vertex_input_fields.begin(), shape->vertex_input_fields.end(), "texcoord1"),
            shape->vertex_input_fields.end());
}

TEST_F(SurfaceProgram, TheGeneratedPassesCompileAndTheForwardRendererDrawsTheBasePass) {
  auto source = compile_source(write("toon_drawn.shader", kToon), options_);
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  EXPECT_EQ(source->module->reflection.vertex_entry, "vert_surf");
  EXPECT_EQ(source->module->reflection.fragment_entry, "frag_surf");
  EXPECT_EQ(source->drawn_passes, (std::vector<size_t>{0}));
  // The additive pass is drawn once for each further light; Meta and Deferred are not generated.
  EXPECT_EQ(source->additive_passes, (std::vector<size_t>{1}));
  EXPECT_TRUE(std::any_of(source->notes.begin(), source->notes.end(), [](const std::string& note) {
    return note.find("Meta and Deferred passes, which Unity also generates, are not generated") != std::string::npos;
  }));
  // The additive pass compiles too.
  auto add = compile_source(write("toon_add.shader", kToon), options_, 1);
  ASSERT_TRUE(add) << add.error().to_string();
  EXPECT_TRUE(add->module->ok()) << add->module->diagnostics.render_all();
}

TEST_F(SurfaceProgram, WhatTheProgramLacksIsAnErrorAtThePragma) {
  const auto error_of = [&](const std::string& name, const std::string& program) {
    auto shape = shape_of(write(name, program));
    EXPECT_FALSE(shape);
    return shape ? Error{} : shape.error();
  };
  Error no_input = error_of("no_input.shader", "    #pragma surface surf Lambert\n    void surf(float x) {}");
  EXPECT_EQ(no_input.where.line, 4u);
  EXPECT_NE(no_input.message.find("struct Input"), std::string::npos) << no_input.message;
  Error no_model = error_of("no_model.shader",
                            "    #pragma surface surf Cel\n    struct Input { float2 uv_MainTex; };\n"
                            "    void surf(Input IN, inout SurfaceOutput o) {}");
  EXPECT_NE(no_model.message.find("has no function LightingCel"), std::string::npos) << no_model.message;
  Error no_gi = error_of("no_gi.shader",
                         "    #pragma surface surf Cel\n    struct Input { float2 uv_MainTex; };\n"
                         "    void surf(Input IN, inout SurfaceOutput o) {}\n"
                         "    half4 LightingCel(SurfaceOutput s, UnityGI gi) { return 1; }");
  EXPECT_NE(no_gi.message.find("LightingCel_GI"), std::string::npos) << no_gi.message;
}

}  // namespace
}  // namespace xshade::harness
