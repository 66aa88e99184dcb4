#include "harness/render/material_source.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "shaderlab/reader.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

const hlsl::Property& property(const hlsl::Reflection& reflection, const std::string& name) {
  auto found = std::find_if(reflection.properties.begin(), reflection.properties.end(),
                            [&](const hlsl::Property& p) { return p.name == name; });
  EXPECT_NE(found, reflection.properties.end()) << name;
  return *found;
}

// The sRGB curve at 0.5 and 2 (a colour above 1, as an [HDR] picker gives): 0.5 -> 0.214041.
TEST(MaterialSource, PropertiesGiveTheDefaultsAsUnitysLinearColourSpacePassesThem) {
  auto shader = shaderlab::read_shader(R"(Shader "T" {
    Properties {
      _Color ("Colour", Color) = (0.5, 0.5, 0.5, 0.25)
      _Tint ("Tint", Color) = (1, 0, 2, 1)
      _Glossiness ("Smoothness", Range(0, 1)) = 0.5
      [Gamma] _Gamma ("Gamma vector", Vector) = (0.5, 1, 0, 3)
      _Plain ("Plain vector", Vector) = (0.5, 1, 0, 3)
      _Written ("Written in HLSL", Float) = 3
      _MainTex ("Albedo", 2D) = "black" {}
      _BumpMap ("Normal", 2D) = "bump" {}
      _Mask ("Mask", 2D) = "" {}
      _Tex ("Declared default", 2D) = "red" {}
    }
    SubShader { Pass { HLSLPROGRAM
    ENDHLSL } } })",
                                       "t.shader");
  ASSERT_TRUE(shader) << shader.error().to_string();
  auto module = hlsl::compile_text("t.hlsl",
                                   "float4 _Color; float3 _Tint; half _Glossiness; float4 _Gamma; float4 _Plain;\n"
                                   "float _Written = 2; float _Undeclared;\n"
                                   "Texture2D _MainTex; sampler2D _BumpMap; sampler2D _Mask;\n"
                                   "Texture2D _Tex <string Default = \"white\";>;\n",
                                   {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  std::vector<std::string> notes;
  apply_properties(*shader, module->reflection, notes);
  const hlsl::Reflection& r = module->reflection;
  const double half_linear = 0.214041;
  const double two_linear = std::pow((2 + 0.055) / 1.055, 2.4);
  const auto near = [](const std::vector<double>& got, const std::vector<double>& want) {
    if (got.size() != want.size()) return false;
    for (size_t i = 0; i < got.size(); ++i)
      if (std::abs(got[i] - want[i]) > 1e-6) return false;
    return true;
  };
  EXPECT_TRUE(near(property(r, "_Color").default_value, {half_linear, half_linear, half_linear, 0.25}));
  EXPECT_TRUE(near(property(r, "_Tint").default_value, {1, 0, two_linear}));  // as many as the uniform has
  EXPECT_TRUE(near(property(r, "_Glossiness").default_value, {0.5}));
  EXPECT_TRUE(near(property(r, "_Gamma").default_value, {half_linear, 1, 0, 3}));
  EXPECT_TRUE(near(property(r, "_Plain").default_value, {0.5, 1, 0, 3}));
  EXPECT_TRUE(near(property(r, "_Written").default_value, {2}));                  // the shader's own initializer stands
  EXPECT_EQ(property(r, "_Undeclared").default_value, (std::vector<double>{0}));  // no Property: 0, as in Unity
  EXPECT_EQ(property(r, "_MainTex").default_texture, "clear");                    // Unity's "black" is (0, 0, 0, 0)
  EXPECT_EQ(property(r, "_BumpMap").default_texture, "normal");
  EXPECT_EQ(property(r, "_Mask").default_texture, "gray");
  EXPECT_EQ(property(r, "_Tex").default_texture, "white");
}

// Unity's material gives a uniform its Properties block does not declare nothing: it reads 0
// until a script sets it. The renderer's inputs, X_ST and what no entry point reads keep theirs.
TEST(MaterialSource, AUniformNoPropertyDeclaresReadsZeroAsInUnity) {
  auto shader = shaderlab::read_shader(R"(Shader "T" {
    Properties { _Color ("Colour", Color) = (1, 1, 1, 1) }
    SubShader { Pass { HLSLPROGRAM
    ENDHLSL } } })",
                                       "t.shader");
  ASSERT_TRUE(shader) << shader.error().to_string();
  auto module =
      hlsl::compile_text("t.hlsl",
                         "#pragma fragment frag\n"
                         "float4 _Color; float2 _Scripted; float4 _Unread; float4 _Time; float4 _MainTex_ST;\n"
                         "float4 frag() : SV_Target { return _Color + _Scripted.x + _Time + _MainTex_ST; }\n",
                         {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  std::vector<std::string> notes;
  apply_properties(*shader, module->reflection, notes);
  const hlsl::Reflection& r = module->reflection;
  EXPECT_EQ(property(r, "_Scripted").default_value, (std::vector<double>{0, 0}));
  EXPECT_TRUE(property(r, "_Unread").default_value.empty());
  EXPECT_TRUE(property(r, "_Time").default_value.empty());        // the renderer's
  EXPECT_TRUE(property(r, "_MainTex_ST").default_value.empty());  // (1, 1, 0, 0) unless given
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_TRUE(notes[0].starts_with("uniform _Scripted reads 0")) << notes[0];
}

hlsl::CompileOptions in_folders(std::vector<fs::path> folders) {
  hlsl::CompileOptions options;
  options.include_dirs = std::move(folders);
  return options;
}

class UnityShaderSource : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        fs::temp_directory_path() /
        ("xshade_material_source_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path write(const std::string& name, const std::string& text) {
    std::ofstream(folder_ / name, std::ios::binary) << text;
    return folder_ / name;
  }
  fs::path folder_;
};

// The program compiles in Unity's environment (SHADER_TARGET from its #pragma target), from the
// pass the forward renderer draws; the plan hears of the passes left out.
TEST_F(UnityShaderSource, TheDrawnPassCompilesInUnitysEnvironment) {
  const fs::path file = write("two.shader", R"(Shader "Two" {
  SubShader {
    Pass { Tags { "LightMode" = "ShadowCaster" } HLSLPROGRAM
      #pragma fragment caster
      float4 caster() : SV_Target { return 0; }
      ENDHLSL }
    Pass { Name "Body" HLSLPROGRAM
      #pragma target 3.0
      #pragma fragment frag
      #if SHADER_TARGET >= 30 && defined(SHADER_API_GLCORE) && !defined(UNITY_REVERSED_Z)
      float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }
      #endif
      ENDHLSL }
  }
})");
  auto source = compile_source(file, {});
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  EXPECT_EQ(source->module->reflection.fragment_entry, "frag");
  // The ShadowCaster is drawn only into a shadow map, where a light casts (the planner decides).
  EXPECT_TRUE(source->notes.empty());
  EXPECT_EQ(source->caster_pass, 0u);
}

// A file included with #include_with_pragmas gives the program its pragmas, #pragma target and
// its SHADER_TARGET among them; a plain #include's are Unity's to ignore.
TEST_F(UnityShaderSource, IncludeWithPragmasGivesTheProgramItsTargetAndStages) {
  write("settings.hlsl", "#pragma target 4.5\n#pragma fragment frag\n");
  const std::string body = R"(
      #if SHADER_TARGET == 45
      float4 frag(float4 pos : SV_Position) : SV_Target { return 1; }
      #else
      float4 frag() : SV_Target { return 0; }
      #endif
      ENDHLSL } } })";
  const fs::path with = write("with.shader",
                              "Shader \"With\" { SubShader { Pass { HLSLPROGRAM\n"
                              "      #include_with_pragmas \"settings.hlsl\"" +
                                  body);
  auto source = compile_source(with, {});
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  EXPECT_EQ(source->module->reflection.fragment_entry, "frag");
  const hlsl::FunctionDecl* frag = source->module->entry_points.fragment;
  ASSERT_NE(frag, nullptr);
  EXPECT_EQ(frag->params.size(), 1u);  // the SHADER_TARGET == 45 branch

  const fs::path plain = write("plain.shader",
                               "Shader \"Plain\" { SubShader { Pass { HLSLPROGRAM\n"
                               "      #pragma fragment frag\n"
                               "      #include \"settings.hlsl\"" +
                                   body);
  source = compile_source(plain, {});
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  ASSERT_NE(source->module->entry_points.fragment, nullptr);
  EXPECT_EQ(source->module->entry_points.fragment->params.size(), 0u);  // Unity's default target, 2.5
  EXPECT_EQ(source->module->diagnostics.warning_count(), 2u);           // the two ignored pragmas
}

TEST_F(UnityShaderSource, WhatCannotBeDrawnIsAnErrorInTheShaderFile) {
  const fs::path cg = write("cg.shader",
                            "Shader \"Cg\" {\n  SubShader {\n    Pass {\n      CGPROGRAM\n      #pragma fragment f\n   "
                            "   ENDCG\n    }\n  }\n}\n");
  auto missing = compile_source(cg, {});
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().where.line, 4u);
  EXPECT_NE(missing.error().message.find("\"Built-in shaders\" download"), std::string::npos)
      << missing.error().message;

  const fs::path surface =
      write("surface.shader",
            "Shader \"Surf\" {\n  SubShader {\n    CGPROGRAM\n    #pragma surface surf Lambert\n    ENDCG\n  }\n}\n");
  // A surface shader's passes are generated from Unity's include files too.
  auto generated = compile_source(surface, {});
  ASSERT_FALSE(generated);
  EXPECT_EQ(generated.error().where.line, 3u);
  EXPECT_NE(generated.error().message.find("\"Built-in shaders\" download"), std::string::npos)
      << generated.error().message;

  const fs::path fixed =
      write("fixed.shader",
            "Shader \"Fixed\" {\n  SubShader {\n    Pass { SetTexture [_MainTex] { combine texture } }\n"
            "  }\n}\n");
  auto fixed_function = compile_source(fixed, {});
  ASSERT_FALSE(fixed_function);
  EXPECT_EQ(fixed_function.error().where.line, 2u);
  EXPECT_NE(fixed_function.error().message.find("is a fixed-function shader"), std::string::npos)
      << fixed_function.error().message;

  // A GrabPass whose image a drawn pass reads; one that nothing reads is left out with a note.
  const std::string glass =
      "Shader \"Glass\" {\n  SubShader {\n    GrabPass { \"_Behind\" }\n    Pass { HLSLPROGRAM\n"
      "    #pragma vertex v\n    #pragma fragment f\n    Texture2D _Behind; SamplerState s;\n"
      "    float4 v(float4 p : POSITION) : SV_Position { return p; }\n"
      "    float4 f(float4 p : SV_Position) : SV_Target { return READ; }\n    ENDHLSL }\n  }\n}\n";
  const auto with_read = [&](const std::string& read) {
    std::string text = glass;
    return text.replace(text.find("READ"), 4, read);
  };
  auto grabbed = compile_source(write("grab.shader", with_read("_Behind.Sample(s, p.xy)")), {});
  ASSERT_FALSE(grabbed);
  EXPECT_EQ(grabbed.error().where.line, 3u);
  EXPECT_EQ(grabbed.error().message,
            "'Glass': GrabPass is not drawn yet: xshade's renderer does not copy the target "
            "between an object's passes, and pass 1 reads '_Behind'");
  auto ungrabbed = compile_source(write("ungrabbed.shader", with_read("p")), {});
  ASSERT_TRUE(ungrabbed) << ungrabbed.error().to_string();
  EXPECT_EQ(ungrabbed->notes,
            std::vector<std::string>{"pass 0: not drawn: GrabPass is not drawn yet, and the drawn passes "
                                     "do not read what it grabs"});

  const fs::path broken = write("broken.shader", "Shader \"Broken\" {\n  Properties { _A (\"a\", Flaot) = 1 }\n}\n");
  auto unread = compile_source(broken, {});
  ASSERT_FALSE(unread);
  EXPECT_EQ(unread.error().where.line, 2u);
}

// UsePass "Shader/NAME" draws that shader's pass, with its own includes and render state, found by
// the shader's name under the include folders; one not found is left out with a note, as Unity
// leaves it out.
TEST_F(UnityShaderSource, AUsedPassIsTheNamedShadersPassWithItsIncludesAndState) {
  fs::create_directories(folder_ / "library" / "legacy");
  std::ofstream(folder_ / "library" / "legacy" / "base.shader") << R"(Shader "Library/Base" {
  SubShader {
    HLSLINCLUDE
    float4 base_colour() { return float4(0.25, 0.5, 0.75, 1); }
    ENDHLSL
    Pass { Name "Caster" Tags { "LightMode" = "ShadowCaster" } HLSLPROGRAM
      #pragma fragment frag
      float4 frag() : SV_Target { return 0; }
      ENDHLSL }
    Pass { Name "Base" Cull Front HLSLPROGRAM
      #pragma fragment frag
      float4 frag() : SV_Target { return base_colour(); }
      ENDHLSL }
  }
})";
  const fs::path user = write("user.shader", R"(Shader "User" {
  SubShader {
    UsePass "Library/Base/BASE"
    UsePass "Library/Base/CASTER"
    UsePass "Library/Missing/BASE"
  }
})");
  auto source = compile_source(user, in_folders({folder_ / "library"}));
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  EXPECT_EQ(source->drawn_passes, std::vector<size_t>{0});
  EXPECT_EQ(source->module->reflection.fragment_entry, "frag");
  ASSERT_TRUE(source->render_state && source->render_state->cull);
  EXPECT_EQ(source->render_state->cull->text, "Front");
  EXPECT_EQ(source->caster_pass, 1u);  // the used CASTER, a ShadowCaster
  ASSERT_EQ(source->notes.size(), 1u);
  EXPECT_TRUE(
      source->notes[0].starts_with("pass 2: not drawn: " + user.string() +
                                   ":5:5: no .shader in the shader folders declares Shader \"Library/Missing\""))
      << source->notes[0];

  // Asked for by index (a post step, compile --pass), the UsePass not found has no program.
  auto unresolved = compile_source(user, in_folders({folder_ / "library"}), 2);
  ASSERT_FALSE(unresolved);
  EXPECT_EQ(unresolved.error().to_string(), user.string() +
                                                ":5:5: pass 2 of 'User' has no program: a GrabPass, a "
                                                "fixed-function pass or a UsePass not found draws none");

  // No pass of that name: an error at the UsePass.
  const fs::path wrong =
      write("wrong.shader", "Shader \"Wrong\" {\n  SubShader {\n    UsePass \"Library/Base/TOP\"\n  }\n}\n");
  auto no_pass = compile_source(wrong, in_folders({folder_ / "library"}));
  ASSERT_FALSE(no_pass);
  EXPECT_TRUE(
      no_pass.error().message.starts_with("'Wrong' has no pass the forward renderer draws (a program pass without "
                                          "LightMode, or with Always or ForwardBase): pass 0: not drawn: "))
      << "each pass says why it is not drawn: " << no_pass.error().message;
}

// A shader without a SubShader is drawn as its Fallback, found by name; Fallback Off, or a chain
// that goes round, is an error.
TEST_F(UnityShaderSource, AShaderWithoutASubShaderIsDrawnAsItsFallback) {
  write("drawn.shader",
        "Shader \"Drawn\" {\n  SubShader { Pass { HLSLPROGRAM\n  #pragma fragment frag\n"
        "  float4 frag() : SV_Target { return 1; }\n  ENDHLSL } }\n}\n");
  const fs::path middle = write("middle.shader", "Shader \"Middle\" {\n  Fallback \"Drawn\"\n}\n");
  const fs::path first =
      write("first.shader", "Shader \"First\" {\n  Properties { _A (\"a\", Float) = 1 }\n  Fallback \"Middle\"\n}\n");
  // Every file before the first lookup: a folder is read once a process.
  const fs::path off = write("off.shader", "Shader \"Off\" {\n  Fallback Off\n}\n");
  write("loop_a.shader", "Shader \"LoopA\" {\n  Fallback \"LoopB\"\n}\n");
  const fs::path loop = write("loop_b.shader", "Shader \"LoopB\" {\n  Fallback \"LoopA\"\n}\n");
  auto source = compile_source(first, in_folders({folder_}));
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_TRUE(source->module->ok()) << source->module->diagnostics.render_all();
  EXPECT_EQ(source->notes, (std::vector<std::string>{
                               "'First' has no SubShader: drawn as its Fallback 'Middle' (" + middle.string() + ")",
                               "'Middle' has no SubShader: drawn as its Fallback 'Drawn' (" +
                                   (folder_ / "drawn.shader").string() + ")"}));

  auto fallback_off = compile_source(off, in_folders({folder_}));
  ASSERT_FALSE(fallback_off);
  EXPECT_EQ(fallback_off.error().to_string(), off.string() + ":1:1: 'Off' has no SubShader (Fallback Off)");

  auto cycle = compile_source(loop, in_folders({folder_}));
  ASSERT_FALSE(cycle);
  EXPECT_NE(cycle.error().message.find("falls back after 8 shaders without a SubShader (a chain that goes round?)"),
            std::string::npos)
      << cycle.error().to_string();
}

// Unity looks for a ShadowCaster in the Fallback chain where the drawn SubShader has none: the
// first shader of the chain that has one casts for the object (compiled as one more pass).
TEST_F(UnityShaderSource, WithoutAShadowCasterOfItsOwnAnObjectCastsWithItsFallbacks) {
  const std::string program =
      "HLSLPROGRAM\n  #pragma vertex v\n  #pragma fragment f\n"
      "  float4 v(float4 p : POSITION) : SV_Position { return p; }\n"
      "  float4 f() : SV_Target { return CASTS; }\n  ENDHLSL";
  const auto pass = [&](const std::string& tags, const std::string& value) {
    std::string text = "Pass { " + tags + " " + program + " }";
    return text.replace(text.find("CASTS"), 5, value);
  };
  write("caster.shader", "Shader \"Caster\" {\n  SubShader { " + pass("", "0") + "\n" +
                             pass("Tags { \"LightMode\" = \"ShadowCaster\" }", "0.5") + " }\n}\n");
  write("plain.shader", "Shader \"Plain\" {\n  SubShader { " + pass("", "0") + " }\n  Fallback \"Caster\"\n}\n");
  const fs::path lit =
      write("lit.shader", "Shader \"Lit\" {\n  SubShader { " + pass("", "1") + " }\n  Fallback \"Plain\"\n}\n");
  const fs::path alone = write("alone.shader", "Shader \"Alone\" {\n  SubShader { " + pass("", "1") + " }\n}\n");
  auto source = compile_source(lit, in_folders({folder_}));
  ASSERT_TRUE(source) << source.error().to_string();
  ASSERT_EQ(source->caster_pass, 1u);  // past its one pass: the Fallback's Fallback's
  auto caster = compile_source(lit, in_folders({folder_}), source->caster_pass);
  ASSERT_TRUE(caster) << caster.error().to_string();
  ASSERT_TRUE(caster->module->ok()) << caster->module->diagnostics.render_all();
  EXPECT_EQ(caster->module->reflection.fragment_entry, "f");
  EXPECT_NE(caster->module->sources.text(caster->module->main_file).find("return 0.5"), std::string::npos);
  auto without = compile_source(alone, in_folders({folder_}));
  ASSERT_TRUE(without) << without.error().to_string();
  EXPECT_FALSE(without->caster_pass);
}

}  // namespace
}  // namespace xshade::harness
