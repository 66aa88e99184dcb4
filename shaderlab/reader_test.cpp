#include "shaderlab/reader.h"

#include <filesystem>

#include <gtest/gtest.h>

namespace xshade::shaderlab {
namespace {

Shader read_ok(std::string_view text) {
  auto shader = read_shader(text, "test.shader");
  EXPECT_TRUE(shader) << shader.error().to_string();
  return shader ? std::move(*shader) : Shader{};
}

std::string read_error(std::string_view text) {
  auto shader = read_shader(text, "test.shader");
  EXPECT_FALSE(shader) << "read without an error";
  return shader ? std::string() : shader.error().to_string();
}

constexpr const char* kUnlit = R"SL(Shader "Unlit/Texture" {
  Properties {
    _MainTex ("Base (RGB)", 2D) = "white" {}
    [HDR] _Color ("Tint", Color) = (1, 0.5, 0.25)
    [Toggle(_FADE_ON)] _Fade ("Fade", Float) = 1
    _Cutoff ("Cutoff", Range(0.0, 1)) = 0.5
    [KeywordEnum(None, Add, Multiply)] _Overlay ("Overlay mode", Float) = 0
    [Header(Maps: detail, and more)] _Detail ("Detail", 2DArray) = "" {}
  }
  SubShader {
    Tags { "RenderType"="Opaque" "Queue" = "Geometry+1" }
    LOD 100
    Pass {
      Name "BODY"
      CGPROGRAM
      #pragma vertex vert
      ENDCG
    }
  }
  Fallback Off
})SL";

TEST(ShaderLabReader, PropertiesWithTheirTypesDefaultsAndAttributes) {
  const Shader shader = read_ok(kUnlit);
  EXPECT_EQ(shader.name, "Unlit/Texture");
  ASSERT_EQ(shader.properties.size(), 6u);
  const Property& texture = shader.properties[0];
  EXPECT_EQ(texture.name, "_MainTex");
  EXPECT_EQ(texture.display_name, "Base (RGB)");
  EXPECT_EQ(texture.type, PropertyType::Texture2D);
  EXPECT_EQ(texture.texture_default, "white");
  EXPECT_EQ(texture.where.to_string(), "test.shader:3:5");

  const Property* color = shader.property("_Color");
  ASSERT_NE(color, nullptr);
  EXPECT_EQ(color->type, PropertyType::Color);
  EXPECT_EQ(color->value, (std::array<float, 4>{1.0f, 0.5f, 0.25f, 1.0f})) << "three components: alpha 1";
  EXPECT_NE(color->attribute("hdr"), nullptr) << "attribute names ignore case";

  const Property* fade = shader.property("_Fade");
  ASSERT_NE(fade, nullptr);
  ASSERT_NE(fade->attribute("Toggle"), nullptr);
  EXPECT_EQ(fade->attribute("Toggle")->arguments, std::vector<std::string>{"_FADE_ON"});
  EXPECT_EQ(fade->value[0], 1.0f);

  const Property* cutoff = shader.property("_Cutoff");
  ASSERT_NE(cutoff, nullptr);
  EXPECT_EQ(cutoff->type, PropertyType::Range);
  EXPECT_EQ(cutoff->range_min, 0.0f);
  EXPECT_EQ(cutoff->range_max, 1.0f);
  EXPECT_EQ(cutoff->value[0], 0.5f);

  EXPECT_EQ(shader.property("_Overlay")->attribute("KeywordEnum")->arguments,
            (std::vector<std::string>{"None", "Add", "Multiply"}));
  EXPECT_EQ(shader.property("_Detail")->attribute("Header")->arguments,
            std::vector<std::string>{"Maps: detail, and more"})
      << "a header's text is one argument";
  EXPECT_EQ(shader.property("_Detail")->type, PropertyType::Texture2DArray);
  EXPECT_TRUE(shader.notes.empty());
}

TEST(ShaderLabReader, SubShaderTagsLodPassAndProgramWithItsPlaceInTheFile) {
  const Shader shader = read_ok(kUnlit);
  ASSERT_EQ(shader.subshaders.size(), 1u);
  const SubShader& sub = shader.subshaders[0];
  EXPECT_EQ(tag(sub.tags, "Queue"), "Geometry+1");
  EXPECT_EQ(tag(sub.tags, "RenderType"), "Opaque");
  EXPECT_EQ(tag(sub.tags, "QUEUE"), "Geometry+1") << "a tag's name ignores case, as Unity reads it";
  EXPECT_EQ(tag(sub.tags, "LightMode"), "") << "absent";
  EXPECT_EQ(sub.lod, 100);
  ASSERT_EQ(sub.passes.size(), 1u);
  const Pass& pass = sub.passes[0];
  EXPECT_EQ(pass.kind, PassKind::Program);
  EXPECT_EQ(pass.name, "BODY");
  ASSERT_TRUE(pass.program);
  EXPECT_EQ(pass.program->start.to_string(), "test.shader:15:16") << "right after CGPROGRAM";
  EXPECT_EQ(pass.program->text, "\n      #pragma vertex vert\n      ");
  EXPECT_EQ(shader.fallback, std::optional<std::string>(""));
}

// Keywords and state values ignore case and are kept in Unity's spelling; a state may name a
// property; a Pass's state is its own over its SubShader's over its Category's.
TEST(ShaderLabReader, RenderStateInEveryFormAndWhereItIsSet) {
  const Shader shader = read_ok(R"SL(
shader "S" {
  Category {
    zwrite off
    Blend SrcAlpha OneMinusSrcAlpha, One Zero
    SubShader {
      Cull [_Cull]
      ZTest lequal
      Pass {
        Cull Front
        ColorMask rgb
        Offset -1, -1
        BlendOp RevSub, Max
        Stencil { Ref 2 Comp always Pass replace ReadMask 255 }
        Blend 1 Off
        CGPROGRAM
        ENDCG
      }
    }
  }
})SL");
  ASSERT_EQ(shader.subshaders.size(), 1u);
  const SubShader& sub = shader.subshaders[0];
  ASSERT_TRUE(sub.state.cull && sub.state.zwrite && sub.state.ztest);
  EXPECT_TRUE(sub.state.cull->is_property);
  EXPECT_EQ(sub.state.cull->text, "_Cull");
  EXPECT_EQ(sub.state.zwrite->text, "Off") << "from the Category";
  EXPECT_EQ(sub.state.ztest->text, "LEqual");
  ASSERT_EQ(sub.state.blend.size(), 1u);
  EXPECT_EQ(sub.state.blend[0].source.text, "SrcAlpha");
  EXPECT_EQ(sub.state.blend[0].destination_alpha->text, "Zero");

  const Pass& pass = sub.passes[0];
  const RenderState state = pass.state.over(sub.state);
  EXPECT_EQ(state.cull->text, "Front");
  EXPECT_FALSE(state.cull->is_property);
  EXPECT_EQ(state.zwrite->text, "Off");
  EXPECT_EQ(state.color_mask->text, "RGB");
  EXPECT_EQ(state.offset->first.text, "-1");
  EXPECT_EQ(state.offset->second.text, "-1");
  EXPECT_EQ(state.blend_op->first.text, "RevSub");
  EXPECT_EQ(state.blend_op->second->text, "Max");
  ASSERT_TRUE(state.stencil);
  EXPECT_EQ(state.stencil->field("Ref")->text, "2");
  EXPECT_EQ(state.stencil->field("Comp")->text, "Always");
  EXPECT_EQ(state.stencil->field("Pass")->text, "Replace");
  ASSERT_EQ(state.blend.size(), 1u) << "the pass's own blend replaces the outer one";
  EXPECT_EQ(state.blend[0].target, 1);
  EXPECT_TRUE(state.blend[0].off);
}

TEST(ShaderLabReader, IncludeBlocksReachTheSubShadersInTheirScope) {
  const Shader shader = read_ok(R"SL(Shader "S" {
  CGINCLUDE
  float shared;
  ENDCG
  SubShader {
    HLSLINCLUDE
    float mine;
    ENDHLSL
    Pass { CGINCLUDE
    float pass_own;
    ENDCG
    CGPROGRAM
    ENDCG }
    UsePass "Legacy Shaders/VertexLit/SHADOWCASTER"
    GrabPass { "_Behind" }
  }
  SubShader { Pass { Lighting On SetTexture [_MainTex] { combine texture * primary } } }
})SL");
  ASSERT_EQ(shader.subshaders.size(), 2u);
  const SubShader& first = shader.subshaders[0];
  ASSERT_EQ(first.includes.size(), 2u);
  EXPECT_EQ(first.includes[0].language, ProgramLanguage::Cg);
  EXPECT_EQ(first.includes[1].language, ProgramLanguage::Hlsl);
  EXPECT_EQ(first.includes[0].start.line, 2u);
  ASSERT_EQ(first.passes.size(), 3u);
  EXPECT_EQ(first.passes[0].includes.size(), 1u);
  EXPECT_EQ(first.passes[1].kind, PassKind::Use);
  EXPECT_EQ(first.passes[1].used, "Legacy Shaders/VertexLit/SHADOWCASTER");
  EXPECT_EQ(first.passes[2].kind, PassKind::Grab);
  EXPECT_EQ(first.passes[2].grab_texture, "_Behind");
  ASSERT_EQ(shader.subshaders[1].includes.size(), 1u) << "the shader's CGINCLUDE only";
  const Pass& fixed = shader.subshaders[1].passes[0];
  EXPECT_EQ(fixed.kind, PassKind::FixedFunction);
  EXPECT_EQ(fixed.fixed_function, (std::vector<std::string>{"Lighting", "SetTexture"}));
  ASSERT_EQ(shader.notes.size(), 2u);
  EXPECT_EQ(shader.notes[0].to_string(),
            "test.shader:17:22: warning: 'Lighting' is a fixed-function command; xshade draws programs only, and reads "
            "past it");
}

// A CGPROGRAM outside any Pass is a surface shader's program; a Category's LOD, tags and state
// reach its SubShaders unless they set their own.
TEST(ShaderLabReader, ASurfaceProgramAndWhatACategoryGivesItsSubShaders) {
  const Shader shader = read_ok(R"SL(Shader "Legacy Shaders/Diffuse" {
  Category {
    LOD 200
    Tags { "Queue" = "Geometry" }
    AlphaToMask True
    SubShader {
      Tags { "RenderType" = "Opaque" }
      CGPROGRAM
      #pragma surface surf Lambert
      ENDCG
    }
    SubShader { LOD 100 Tags { "Queue" = "Transparent" } Pass { CGPROGRAM ENDCG } }
  }
})SL");
  ASSERT_EQ(shader.subshaders.size(), 2u);
  const SubShader& surface = shader.subshaders[0];
  ASSERT_TRUE(surface.surface);
  EXPECT_EQ(surface.surface->start.line, 8u);
  EXPECT_TRUE(surface.passes.empty());
  EXPECT_EQ(surface.lod, 200);
  EXPECT_EQ(tag(surface.tags, "Queue"), "Geometry");
  EXPECT_EQ(tag(surface.tags, "RenderType"), "Opaque");
  EXPECT_EQ(surface.state.alpha_to_mask->text, "True");
  EXPECT_EQ(shader.subshaders[1].lod, 100);
  EXPECT_EQ(tag(shader.subshaders[1].tags, "Queue"), "Transparent");
}

// Every error says where and what is allowed there.
TEST(ShaderLabReader, ErrorsSayWhereAndWhatIsAllowed) {
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { Cull Sideways } } }"),
            "test.shader:1:38: Cull takes Back, Front or Off, or a property in brackets ([_Name]), not 'Sideways'");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { Stencil { Ref one } } } }"),
            "test.shader:1:47: Ref takes a number or a property in brackets ([_Name]), not 'one'");
  EXPECT_EQ(
      read_error("Shader \"S\" {\n  Properties { _X (\"X\", Float4) = 1 }\n}"),
      "test.shader:2:25: unknown property type 'Float4'; a property is Float, Int, Integer, Range(min, max), Color, "
      "Vector, 2D, 2DArray, 3D, Cube, CubeArray or Any");
  EXPECT_EQ(read_error("Shader \"S\" {\n  SubShader { Pass {\n  CGPROGRAM\n float4 f;\n"),
            "test.shader:3:3: CGPROGRAM has no ENDCG before the end of the file");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { CGPROGRAM ENDCG CGPROGRAM ENDCG } } }"),
            "test.shader:1:49: a Pass holds one program; this one already has the block at line 1");
  EXPECT_EQ(read_error("Shader \"S\" { CGPROGRAM ENDCG }"),
            "test.shader:1:14: a CGPROGRAM or HLSLPROGRAM belongs inside a Pass; only CGINCLUDE and HLSLINCLUDE blocks "
            "stand here");
  EXPECT_EQ(read_error("Shader \"S\" { Properties { _A (\"A\", Float) = 0 _A (\"A\", Float) = 1 } }"),
            "test.shader:1:47: the property '_A' is declared twice");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Tags { Queue = \"Geometry\" } } }"),
            "test.shader:1:33: expected a tag's name in quotes (\"Queue\" = \"Geometry\"), found 'Queue'");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { } } } }"),
            "test.shader:1:39: '}' after the Shader block's closing '}'");
  EXPECT_EQ(read_error("Shader \"S\" { Properties { } }"),
            "test.shader:1:1: the shader has no SubShader (and no Fallback)");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { Cull @ } } }"),
            "test.shader:1:38: a character ShaderLab does not use: '@'");
  // Counts and indices are whole numbers an int holds (a fuzzer's LOD of 2e34 was undefined).
  EXPECT_EQ(read_error("Shader \"S\" { Category { LOD 2e34 } }"),
            "test.shader:1:29: expected the LOD's number, a whole number from 0 to 1000000, found 2e34");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { LOD 1.5 } }"),
            "test.shader:1:30: expected the LOD's number, a whole number from 0 to 1000000, found 1.5");
  EXPECT_EQ(read_error("Shader \"S\" { SubShader { Pass { Blend 9 One One } } }"),
            "test.shader:1:39: expected a render target's number, a whole number from 0 to 7, found 9");
}

// Every .shader of the real-world corpus beside the project (Unity's built-in shaders and Post
// Processing's) is read without an error: what Unity reads, xshade reads.
TEST(ShaderLabReader, EveryShaderOfTheRealWorldCorpusIsRead) {
  const std::filesystem::path corpus = XSHADE_REALWORLD_CORPUS;
  if (!std::filesystem::is_directory(corpus)) GTEST_SKIP() << corpus << " is not beside the project";
  size_t read = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(corpus)) {
    if (entry.path().extension() != ".shader") continue;
    auto shader = read_shader_file(entry.path());
    EXPECT_TRUE(shader) << shader.error().to_string();
    ++read;
  }
  EXPECT_GE(read, 100u) << "the corpus holds Unity's built-in shaders";
}

}  // namespace
}  // namespace xshade::shaderlab
