#include "shaderlab/pass_program.h"

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "shaderlab/reader.h"

namespace xshade::shaderlab {
namespace {

Shader read(std::string_view text) {
  auto shader = read_shader(text, "m/Toon.shader");
  EXPECT_TRUE(shader) << shader.error().to_string();
  return shader ? std::move(*shader) : Shader{};
}

constexpr const char* kTwoPasses = R"SL(Shader "Toon" {
  CGINCLUDE
  float shared_cg;
  ENDCG
  SubShader {
    HLSLINCLUDE
    float shared_hlsl;
    ENDHLSL
    Pass { Name "Outline"
      CGINCLUDE
      float outline_only;
      ENDCG
      CGPROGRAM
      float4 outline;
      ENDCG
    }
    Pass {
      HLSLPROGRAM
      float4 body;
      ENDHLSL
    }
    UsePass "Other/SHADOWCASTER"
  }
})SL";

// A CGPROGRAM: Unity's implicit includes, then the CG include blocks of its scope in the file's
// order, then the program, each behind a #line to its place (column padded).
TEST(PassProgram, ACgProgramAfterTheImplicitIncludesAndItsIncludeBlocksEachWhereItStands) {
  const Shader shader = read(kTwoPasses);
  const SubShader& sub = shader.subshaders.at(0);
  auto program = pass_program(sub, sub.passes.at(0));
  ASSERT_TRUE(program) << program.error().to_string();
  EXPECT_TRUE(program->implicit_includes);
  EXPECT_EQ(program->index, 0u);
  EXPECT_EQ(program->text,
            "#include \"HLSLSupport.cginc\"\n"
            "#include \"UnityShaderVariables.cginc\"\n"
            "#line 2 \"m/Toon.shader\"\n"
            "           \n  float shared_cg;\n  \n"
            "#line 10 \"m/Toon.shader\"\n"
            "               \n      float outline_only;\n      \n"
            "#line 13 \"m/Toon.shader\"\n"
            "               \n      float4 outline;\n      \n");
}

TEST(PassProgram, AnHlslProgramTakesTheHlslIncludeBlocksAndNoImplicitInclude) {
  const Shader shader = read(kTwoPasses);
  const SubShader& sub = shader.subshaders.at(0);
  auto program = pass_program(sub, sub.passes.at(1));
  ASSERT_TRUE(program) << program.error().to_string();
  EXPECT_FALSE(program->implicit_includes);
  EXPECT_EQ(program->text.find("#include"), std::string::npos);
  EXPECT_EQ(program->text.find("shared_cg"), std::string::npos);
  EXPECT_NE(program->text.find("float shared_hlsl;"), std::string::npos);
  EXPECT_NE(program->text.find("float4 body;"), std::string::npos);
}

TEST(PassProgram, APassIsFoundByIndexOrByNameIgnoringCase) {
  const Shader shader = read(kTwoPasses);
  auto by_name = find_pass(shader, "OUTLINE");
  ASSERT_TRUE(by_name) << by_name.error().to_string();
  EXPECT_EQ(*by_name, &shader.subshaders[0].passes[0]);
  auto by_index = find_pass(shader, "1");
  ASSERT_TRUE(by_index) << by_index.error().to_string();
  EXPECT_EQ(*by_index, &shader.subshaders[0].passes[1]);
  auto missing = find_pass(shader, "Body");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "the shader 'Toon' has no pass 'Body' in the SubShader it draws (its passes: 0 (\"Outline\"), 1, 2)");
  EXPECT_FALSE(find_pass(shader, "3"));
}

// Unity takes the first SubShader its platform runs: one whose pass (or include block) keeps
// GLCore out is passed over; with none left, there is no SubShader to draw.
TEST(PassProgram, TheDrawnSubShaderIsTheFirstWhosePassesAreCompiledForGlCore) {
  const Shader shader = read(R"SL(Shader "Uber" {
  SubShader { Pass { Name "A" HLSLPROGRAM
    #pragma only_renderers vulkan switch
    ENDHLSL } }
  SubShader {
    HLSLINCLUDE
    #pragma exclude_renderers glcore
    ENDHLSL
    Pass { Name "B" HLSLPROGRAM
    ENDHLSL } }
  SubShader { Pass { Name "C" HLSLPROGRAM
    #pragma exclude_renderers gles vulkan switch
    ENDHLSL } }
})SL");
  ASSERT_NE(drawn_subshader(shader), nullptr);
  EXPECT_EQ(drawn_subshader(shader)->passes.at(0).name, "C");
  auto found = find_pass(shader, "a");
  EXPECT_FALSE(found) << "pass A is not in the SubShader drawn";
  // The platform a scene chooses chooses the SubShader.
  ASSERT_NE(drawn_subshader(shader, UnityPlatform::Vulkan), nullptr);
  EXPECT_EQ(drawn_subshader(shader, UnityPlatform::Vulkan)->passes.at(0).name, "A");
  ASSERT_NE(drawn_subshader(shader, UnityPlatform::D3D11), nullptr);
  EXPECT_EQ(drawn_subshader(shader, UnityPlatform::D3D11)->passes.at(0).name, "B");

  const Shader none = read("Shader \"Gles\" { SubShader { Pass { CGPROGRAM\n#pragma only_renderers gles\nENDCG } } }");
  EXPECT_EQ(drawn_subshader(none), nullptr);
  EXPECT_EQ(
      without_subshader(none),
      "has no SubShader that Unity compiles for glcore (#pragma only_renderers or exclude_renderers keeps each out)");
}

TEST(PassProgram, AGlslProgramIsAnErrorAtItsLine) {
  const Shader shader = read("Shader \"G\" { SubShader { Pass {\nGLSLPROGRAM\nvoid main() {}\nENDGLSL } } }");
  const SubShader& sub = shader.subshaders.at(0);
  auto program = pass_program(sub, sub.passes.at(0));
  ASSERT_FALSE(program);
  EXPECT_EQ(program.error().where.to_string(), "m/Toon.shader:2:12");
  EXPECT_NE(program.error().message.find("xshade compiles HLSL (CGPROGRAM or HLSLPROGRAM)"), std::string::npos);
}

TEST(PassProgram, TheImplicitIncludesAreFoundInAFolderThatHoldsBothOrTheErrorSaysWhereToGetThem) {
  const auto folder = std::filesystem::temp_directory_path() / ("xshade_cgincludes_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "HLSLSupport.cginc") << "\n";
  auto one = find_implicit_includes({folder});
  ASSERT_FALSE(one) << "a folder with one of the two";
  EXPECT_NE(one.error().message.find("\"Built-in shaders\" download of your Unity version"), std::string::npos);
  std::ofstream(folder / "UnityShaderVariables.cginc") << "\n";
  EXPECT_TRUE(find_implicit_includes({"/nonexistent", folder}));
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace xshade::shaderlab
