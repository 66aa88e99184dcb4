#include "shaderlab/compile_environment.h"

#include <algorithm>

#include <gtest/gtest.h>

namespace xshade::shaderlab {
namespace {

TEST(CompileEnvironment, ShaderTargetIsTheHighestPragmaTargetOrUnitysDefault) {
  EXPECT_EQ(shader_target("#pragma vertex vert\n"), 25);
  EXPECT_EQ(shader_target("  #  pragma   target 3.0\n#pragma fragment frag\n"), 30);
  EXPECT_EQ(shader_target("#pragma target 4.5\n#pragma target 3.0\n"), 45);
  EXPECT_EQ(shader_target("#pragma target 5.0 // tessellation\n"), 50);
  // Not a target pragma, or a target named by feature.
  EXPECT_EQ(shader_target("#pragma targetx 3.0\n// #pragma target 3.0\n#pragma target gl4.1\n"), 25);
}

// PPv2's Uber shader keeps one SubShader for Vulkan and one for GLES out of the others this way.
TEST(CompileEnvironment, OnlyAndExcludeRenderersSayWhetherAProgramIsCompiledForGlCore) {
  EXPECT_TRUE(compiles_for_platform("float4 frag() : SV_Target { return 1; }"));
  EXPECT_TRUE(compiles_for_platform("#pragma exclude_renderers gles gles3 d3d11_9x\n"));
  EXPECT_TRUE(compiles_for_platform("  #  pragma only_renderers d3d11 glcore // and no other\n"));
  EXPECT_TRUE(compiles_for_platform("#pragma exclude_renderers nomrt\n"));  // GLCore has several render targets
  EXPECT_FALSE(compiles_for_platform("#pragma exclude_renderers gles vulkan glcore switch\n"));
  EXPECT_FALSE(compiles_for_platform("#pragma only_renderers vulkan switch\n"));
  EXPECT_FALSE(compiles_for_platform("#pragma only_renderers d3d11 // glcore\n"));
  EXPECT_FALSE(compiles_for_platform("#pragma only_renderers glcore\n#pragma exclude_renderers glcore\n"));
  EXPECT_FALSE(compiles_for_platform("#pragma only_renderers glcoreish\n"));
}

TEST(CompileEnvironment, TheDefinesAreUnitysGlCoreOnADesktopOfTierThree) {
  const std::vector<Define> defines = unity_defines("#pragma target 3.0\n");
  const auto value = [&](const std::string& name) -> std::string {
    auto found = std::find_if(defines.begin(), defines.end(), [&](const Define& d) { return d.name == name; });
    return found == defines.end() ? "(undefined)" : found->value;
  };
  EXPECT_EQ(value("SHADER_API_GLCORE"), "1");
  EXPECT_EQ(value("SHADER_API_DESKTOP"), "1");
  EXPECT_EQ(value("SHADER_TARGET"), "30");
  EXPECT_EQ(value("UNITY_VERSION"), "201941");
  EXPECT_EQ(value("UNITY_PBS_USE_BRDF1"), "1");
  // Set by HLSLSupport.cginc from the API, never by the compiler; linear colour.
  EXPECT_EQ(value("UNITY_REVERSED_Z"), "(undefined)");
  EXPECT_EQ(value("UNITY_COLORSPACE_GAMMA"), "(undefined)");
  EXPECT_EQ(value("SHADER_API_D3D11"), "(undefined)");
}

TEST(CompileEnvironment, AProgramIsCompiledForTheScenesPlatformAsItsRendererPragmasSay) {
  EXPECT_FALSE(compiles_for_platform("#pragma only_renderers d3d11\n", UnityPlatform::GLCore));
  EXPECT_TRUE(compiles_for_platform("#pragma only_renderers d3d11\n", UnityPlatform::D3D11));
  EXPECT_FALSE(compiles_for_platform("#pragma exclude_renderers vulkan\n", UnityPlatform::Vulkan));
  EXPECT_TRUE(compiles_for_platform("#pragma exclude_renderers vulkan\n", UnityPlatform::D3D11));
}

TEST(CompileEnvironment, EachPlatformDefinesItsApiAndOnlyIts) {
  for (UnityPlatform platform : {UnityPlatform::GLCore, UnityPlatform::D3D11, UnityPlatform::Vulkan}) {
    const std::vector<Define> defines = unity_defines("", platform);
    std::vector<std::string> apis;
    for (const Define& define : defines)
      if (define.name.starts_with("SHADER_API_") && define.name != "SHADER_API_DESKTOP") apis.push_back(define.name);
    const std::string expected = platform == UnityPlatform::GLCore  ? "SHADER_API_GLCORE"
                                 : platform == UnityPlatform::D3D11 ? "SHADER_API_D3D11"
                                                                    : "SHADER_API_VULKAN";
    EXPECT_EQ(apis, std::vector<std::string>{expected});
    EXPECT_EQ(parse_unity_platform(renderer_name(platform)), platform) << "the name a scene writes reads back";
  }
  EXPECT_FALSE(parse_unity_platform("D3D11")) << "as only_renderers spells it";
  EXPECT_FALSE(direct3d_conventions(UnityPlatform::GLCore));
  EXPECT_TRUE(direct3d_conventions(UnityPlatform::D3D11));
  EXPECT_TRUE(direct3d_conventions(UnityPlatform::Vulkan));
}

}  // namespace
}  // namespace xshade::shaderlab
