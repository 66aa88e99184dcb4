// A user's mistakes through the real `xshade`, as CI sees them: each is reported at the file and
// line to fix with exit 2 (never passed, never blamed on the driver with exit 3), and a run that
// would check nothing fails. The scene is a copy of a fixed one in a temporary folder, changed
// one mistake at a time.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/scene_copy.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace {

namespace fs = std::filesystem;

// The 1-based line of `text`'s first occurrence in `file`.
size_t line_of(const fs::path& file, const std::string& text) {
  const std::string content = read_text(file);
  const size_t at = content.find(text);
  EXPECT_NE(at, std::string::npos) << text;
  return size_t(std::count(content.begin(), content.begin() + std::ptrdiff_t(at), '\n')) + 1;
}

class UserMistakes : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("xshade_mistakes_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    copy_fixed_scene(kSource, root_, kCopiedScene);
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path scene() const { return root_ / "scenes" / (std::string(kCopiedScene) + ".toml"); }

  Outcome xshade(const std::string& verb, const std::string& extra = "") {
    return run_xshade("",
                      verb + copied_scene_options(root_) + " --report '" + (root_ / "report").string() + "' " + extra);
  }
  Outcome run(const std::string& extra = "--lane gl") { return xshade("run", extra); }

  // "<scene file>:<line>:" of the line that holds `text`.
  std::string at_line_of(const std::string& text) {
    return scene().string() + ":" + std::to_string(line_of(scene(), text)) + ":";
  }

  fs::path root_;
};

TEST_F(UserMistakes, AMisspeltPropertyIsAnErrorAtItsLineWithTheNameTheShaderHas) {
  replace_in_file(scene(), "_Color = [0.3", "_Colr = [0.3");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("_Colr") + "1: material 'materials/toon.hlsl' has no property '_Colr'; "
                                                      "did you mean '_Color'?"),
            std::string::npos)
      << outcome.output;
}

TEST_F(UserMistakes, AnUndeclaredKeywordIsAnErrorAndThePlanDoesNotListItsVariant) {
  replace_in_file(scene(), "keywords = [\"_SHADOW_TEX\"]", "keywords = [\"_SHADOW_TEXTURE\"]");
  for (const std::string& extra : {std::string("--lane gl"), std::string("--plan")}) {
    Outcome outcome = run(extra);
    EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
    EXPECT_NE(outcome.output.find("declares no keyword '_SHADOW_TEXTURE'"), std::string::npos) << outcome.output;
    EXPECT_NE(outcome.output.find("did you mean '_SHADOW_TEX'?"), std::string::npos) << outcome.output;
    EXPECT_EQ(outcome.output.find("[_SHADOW_TEXTURE]"), std::string::npos) << outcome.output;
  }
}

TEST_F(UserMistakes, AMisspeltTextureIsAnErrorNotAWhiteTexture) {
  replace_in_file(scene(), "_ShadowTex = \"checker\"", "_ShadowTexture = \"checker\"");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("_ShadowTexture") + "1: material 'materials/toon.hlsl' has no texture "
                                                               "'_ShadowTexture'; did you mean '_ShadowTex'?"),
            std::string::npos)
      << outcome.output;
}

TEST_F(UserMistakes, APostParameterTheEffectLacksIsAnError) {
  std::ofstream(scene(), std::ios::app) << "\n[[post]]\neffect = \"post/depth_of_field.hlsl\"\n[post.parameters]\n"
                                           "_BlurAmount = 2.0\n";
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("_BlurAmount") + "1: post effect 'post/depth_of_field.hlsl' has no "
                                                            "parameter '_BlurAmount'"),
            std::string::npos)
      << outcome.output;
}

TEST_F(UserMistakes, AValueOfTheWrongSizeIsAnErrorNotACrash) {
  replace_in_file(scene(), "_Color = [0.3, 0.6, 0.9, 1]", "_Color = [0.3, 0.6, 0.9]");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("_Color") + "1: '_Color' is a half4 in material 'materials/toon.hlsl': "
                                                       "give it 4 numbers, not 3 numbers"),
            std::string::npos)
      << outcome.output;
}

TEST_F(UserMistakes, AUniformWithNoValueIsAnErrorAtTheObjectNotACrash) {
  replace_in_file(root_ / "shaders/materials/toon.hlsl", "float UIMax = 1.0;> = 0.5;\nfixed _RampSmooth",
                  "float UIMax = 1.0;>;\nfixed _RampSmooth");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(
      outcome.output.find(at_line_of("material = ") + "12: object 'toon': material 'materials/toon.hlsl': uniform "
                                                      "'_RampThreshold' (half) has no value"),
      std::string::npos)
      << outcome.output;
}

TEST_F(UserMistakes, ABlessOfAnUnchangedSceneShowsNoDifferenceInAnyMetric) {
  Outcome outcome = xshade("bless", std::string(kCopiedScene) + " --reason \"unchanged\"");
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("exact: pass: bit-identical"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("worst 0 sRGB steps at (0, 0), 0 failing pixels"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, AMissingTextureFileIsTheScenesFaultAtItsLine) {
  replace_in_file(scene(), "_ShadowTex = \"checker\"", "_ShadowTex = \"checks.png\"");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("checks.png") + "14:"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("checks.png"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, AMissingMeshFileIsTheScenesFaultAtItsLine) {
  replace_in_file(scene(), "mesh = \"torus\"", "mesh = \"models/knot.obj\"");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find(at_line_of("knot.obj") + "8:"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, AVariantThatDoesNotCompileShowsItsDiagnosticAndCaretOnTheConsole) {
  replace_in_file(root_ / "shaders/materials/toon.hlsl", "return fixed4(diffuse + specular + rim, albedo.a);",
                  "return fixed4(diffuse + specular + rimm, albedo.a);");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("error: unknown name 'rimm'"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("specular + rimm, albedo.a);\n"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("^"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, AGoldenOfAnotherSizeSaysSoAndNamesTheBlessCommand) {
  replace_in_file(scene(), "size = [256, 256]", "size = [256, 200]");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("is 256x256 and the scene renders 256x200"), std::string::npos) << outcome.output;
  EXPECT_NE(outcome.output.find("xshade bless toon_shadow_texture --reason"), std::string::npos) << outcome.output;
  EXPECT_FALSE(fs::exists(root_ / "report" / kCopiedScene / "gl.diff.png"));
}

TEST_F(UserMistakes, AShardWithNoSceneChecksNothingAndFails) {
  Outcome outcome = run("--lane gl --shard 2/2");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("shard 2/2 holds no scene"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, AFolderThatDoesNotExistIsRefused) {
  Outcome golden =
      run_xshade("", "run --lane gl --scenes '" + (root_ / "scenes").string() + "' --golden '" +
                         (root_ / "nothere").string() + "' --report '" + (root_ / "report").string() + "'");
  EXPECT_EQ(golden.exit_code, 2) << golden.output;
  EXPECT_NE(golden.output.find("the golden folder " + (root_ / "nothere").string() + " (--golden) does not exist"),
            std::string::npos)
      << golden.output;
  Outcome shaders = run("--lane gl --shaders '" + (root_ / "nothere").string() + "'");
  EXPECT_EQ(shaders.exit_code, 2) << shaders.output;
  EXPECT_NE(shaders.output.find("(--shaders) is not a folder"), std::string::npos) << shaders.output;
}

TEST_F(UserMistakes, LanesAreGivenWithCommasOrRepeatedAndNeverSwallowASceneName) {
  Outcome commas = run(std::string("--lane gl,vk ") + kCopiedScene);
  EXPECT_EQ(commas.exit_code, 0) << commas.output;
  EXPECT_NE(commas.output.find(std::string(kCopiedScene) + " on vk: pass"), std::string::npos) << commas.output;
  EXPECT_EQ(commas.output.find(" on vk-hlsl:"), std::string::npos) << commas.output;
  Outcome repeated = run(std::string("--lane gl --lane vk ") + kCopiedScene);
  EXPECT_EQ(repeated.exit_code, 0) << repeated.output;
  EXPECT_NE(repeated.output.find(std::string(kCopiedScene) + " on vk: pass"), std::string::npos) << repeated.output;
  // Before, `--lane gl vk SCENE` took the scene as a lane; now the bare words are scene names.
  Outcome bare = run(std::string("--lane gl vk ") + kCopiedScene);
  EXPECT_EQ(bare.exit_code, 2) << bare.output;
  EXPECT_NE(bare.output.find("no scene 'vk' in"), std::string::npos) << bare.output;
  EXPECT_NE(bare.output.find("(lanes are chosen with --lane vk, or --lane gl,vk)"), std::string::npos) << bare.output;
}

TEST_F(UserMistakes, ALaneGoldenThatMatchesTheCommonOneIsRefused) {
  Outcome outcome = xshade("bless", std::string(kCopiedScene) + " --lane gl --reason \"try\"");
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("matches the common golden"), std::string::npos) << outcome.output;
  EXPECT_FALSE(fs::exists(root_ / "golden" / (std::string(kCopiedScene) + ".gl.png")));
}

TEST_F(UserMistakes, AValueAboveOneThatChangesFailsThoughThePngCannotShowIt) {
  // Every colour above 1 raised further (1.85 becomes 6.07): the same 255 in 8 bits.
  replace_in_file(root_ / "shaders/materials/toon.hlsl", "return fixed4(diffuse + specular + rim, albedo.a);",
                  "fixed3 colour = diffuse + specular + rim;\n  colour += max(colour - 1, 0) * 5;\n"
                  "  return fixed4(colour, albedo.a);");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 1) << outcome.output;
  EXPECT_NE(outcome.output.find(std::string(kCopiedScene) + " on gl: fail - float: "), std::string::npos)
      << outcome.output;
}

// white_furnace has no value above 1, so its PNG is its whole golden.
TEST_F(UserMistakes, ASixteenBitGoldenIsSrgbLikeAnEightBitOne) {
  fs::remove(scene());
  fs::copy_file(kSource / "scenes" / "white_furnace.toml", root_ / "scenes" / "white_furnace.toml");
  const fs::path golden = root_ / "golden" / "white_furnace.png";
  // The same codes times 257 (the 16-bit code of each 8-bit one), by OpenImageIO's own tool, so that
  // this test program need not load the image library.
  const std::string convert =
      "oiiotool '" + (kSource / "golden" / "white_furnace.png").string() + "' -d uint16 -o '" + golden.string() + "'";
  ASSERT_EQ(std::system(convert.c_str()), 0) << convert;
  // No golden is used without its entry and hash (bless writes only 8-bit PNGs, so this one is
  // recorded by hand).
  write_manifest_for(root_ / "golden", "white_furnace");
  Outcome outcome = run();
  EXPECT_EQ(outcome.exit_code, 0) << outcome.output;
  EXPECT_NE(outcome.output.find("white_furnace on gl: pass"), std::string::npos) << outcome.output;
}

TEST_F(UserMistakes, ARunReplacesTheEarlierRunsPagesAndKeepsWhatItDidNotWrite) {
  ASSERT_EQ(run().exit_code, 0);
  ASSERT_TRUE(fs::exists(root_ / "report" / (std::string(kCopiedScene) + ".html")));
  std::ofstream(root_ / "report" / "notes.txt") << "mine";
  fs::rename(scene(), root_ / "scenes" / "renamed.toml");
  fs::rename(root_ / "golden" / (std::string(kCopiedScene) + ".png"), root_ / "golden" / "renamed.png");
  fs::rename(root_ / "golden" / (std::string(kCopiedScene) + ".exr"), root_ / "golden" / "renamed.exr");
  replace_in_file(root_ / "golden" / "MANIFEST.toml", std::string("scene = \"") + kCopiedScene + "\"",
                  "scene = \"renamed\"");
  Outcome second = run();
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_TRUE(fs::exists(root_ / "report" / "renamed.html"));
  EXPECT_FALSE(fs::exists(root_ / "report" / (std::string(kCopiedScene) + ".html")));
  EXPECT_FALSE(fs::exists(root_ / "report" / kCopiedScene));
  EXPECT_TRUE(fs::exists(root_ / "report" / "notes.txt"));
}

// A scene without a post chain compiles and runs no post pass: the plan lists its variants and
// passes, and says why the effect is left out.
TEST(CommandLine, ThePlanOfASceneWithoutPostEffectsHasNoPostVariantOrPass) {
  Outcome plan = run_xshade("", "run dof_off --plan --no-cache");
  ASSERT_EQ(plan.exit_code, 0) << plan.output;
  const std::string variants = plan.output.substr(0, plan.output.find("  passes to run"));
  EXPECT_NE(variants.find("materials/"), std::string::npos) << plan.output;
  EXPECT_EQ(variants.find("post/"), std::string::npos) << plan.output;
  EXPECT_NE(plan.output.find("  passes to run (1):\n    scene: "), std::string::npos) << plan.output;
  EXPECT_NE(
      plan.output.find("post/depth_of_field.hlsl: not in the post chain, so none of its passes is compiled or run"),
      std::string::npos)
      << plan.output;
}

TEST(CommandLine, VersionAndMisspeltVerbsAndOptionsAreAnswered) {
  Outcome version = run_xshade("", "--version");
  EXPECT_EQ(version.exit_code, 0) << version.output;
  EXPECT_EQ(version.output.rfind("xshade ", 0), 0u) << version.output;
  Outcome verb = run_xshade("", "blss");
  EXPECT_EQ(verb.exit_code, 2) << verb.output;
  EXPECT_NE(verb.output.find("unknown command 'blss'; did you mean 'bless'?"), std::string::npos) << verb.output;
  Outcome option = run_xshade("", "run --lan gl");
  EXPECT_EQ(option.exit_code, 2) << option.output;
  EXPECT_NE(option.output.find("unknown option '--lan'; did you mean '--lane'?"), std::string::npos) << option.output;
}

TEST(CommandLine, CompileShowsAPostPassAndSaysHowToChooseOne) {
  Outcome effect = run_xshade("", "compile post/depth_of_field.hlsl --target gl --no-project");
  EXPECT_EQ(effect.exit_code, 2) << effect.output;
  EXPECT_NE(effect.output.find("is a post effect with no #pragma fragment: choose one of its passes (coc, prefilter, "
                               "bokeh, postfilter, combine) with --pass NAME"),
            std::string::npos)
      << effect.output;
  Outcome pass = run_xshade("", "compile post/depth_of_field.hlsl --target gl --pass bokeh --no-project");
  EXPECT_EQ(pass.exit_code, 0) << pass.output;
  EXPECT_NE(pass.output.find("the fragment stage of entry point 'frag_bokeh'"), std::string::npos) << pass.output;
  Outcome all = run_xshade("", "compile materials/toon.hlsl --target vk --all-variants --no-project");
  EXPECT_EQ(all.exit_code, 0) << all.output;
  EXPECT_NE(all.output.find("[_SHADOW_TEX _GUARDED]: compiles"), std::string::npos) << all.output;
  EXPECT_NE(all.output.find("4 keyword combinations for vk"), std::string::npos) << all.output;
}

TEST(CommandLine, EvalFailsOnNonFiniteOutputUnlessTheyAreExpected) {
  const fs::path shader = fs::temp_directory_path() / "xshade_eval_nan.hlsl";
  std::ofstream(shader) << "#pragma fragment frag\n"
                           "float4 frag(float4 p : SV_Position) : SV_Target { float z = p.x - p.x; return 0.0 / z; }\n";
  const std::string common = "eval '" + shader.string() + "' --lane gl --size 8x8 -o '" +
                             (fs::temp_directory_path() / "xshade_eval_nan").string() + "'";
  Outcome failing = run_xshade("", common);
  EXPECT_EQ(failing.exit_code, 1) << failing.output;
  EXPECT_NE(failing.output.find("gl: 256 NaN, 0 Inf, 0 negative channel values, first at (0, 0)"), std::string::npos)
      << failing.output;
  Outcome allowed = run_xshade("", common + " --allow-nonfinite");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  fs::remove(shader);
}

// --no-images: the lanes are compared and printed as always, and nothing is written, not even the
// image library loaded (the dynamic loader's own account of what each process opened says so).
TEST(CommandLine, EvalWithNoImagesComparesTheLanesAndWritesNothing) {
  const fs::path shader = fs::temp_directory_path() / "xshade_eval_no_images.hlsl";
  const fs::path folder = fs::temp_directory_path() / "xshade_eval_no_images";
  fs::remove_all(folder);
  std::ofstream(shader) << "#pragma fragment frag\n"
                           "float4 frag(float4 p : SV_Position) : SV_Target { return float4(p.xy / 8.0, 0.5, 1); }\n";
  const std::string common = "eval '" + shader.string() + "' --lane gl,vk --size 8x8 -o '" + folder.string() + "'";
  Outcome bare = run_xshade("LD_DEBUG=files", common + " --no-images");
  EXPECT_EQ(bare.exit_code, 0) << bare.output;
  EXPECT_NE(bare.output.find("gl vs vk: "), std::string::npos) << bare.output;
  EXPECT_EQ(bare.output.find("libOpenImageIO"), std::string::npos) << "the image library was loaded";
  EXPECT_TRUE(fs::is_empty(folder)) << "something was written into " << folder;
  Outcome written = run_xshade("LD_DEBUG=files", common);
  EXPECT_EQ(written.exit_code, 0) << written.output;
  EXPECT_NE(written.output.find("libOpenImageIO"), std::string::npos) << "the loader's account shows no image library";
  EXPECT_TRUE(fs::exists(folder / "xshade_eval_no_images.gl.exr"));
  fs::remove_all(folder);
  fs::remove(shader);
}

// A Unity .shader compiles pass by pass as Unity composes it; a message inside a program block
// points into the .shader file; a CGPROGRAM without Unity's include files says where to get them.
TEST(CommandLine, CompileReadsAUnityShaderPassByPass) {
  const fs::path folder = fs::temp_directory_path() / "xshade_compile_unity";
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "Two.shader") << R"SL(Shader "Test/Two" {
  Properties { _Color ("Colour", Color) = (1, 0, 0, 1) }
  SubShader {
    HLSLINCLUDE
    float4 _Color;
    float4 vert(float4 p : POSITION) : SV_Position { return p; }
    ENDHLSL
    Pass { Name "Body"
      HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      float4 frag() : SV_Target { return _Color; }
      ENDHLSL
    }
    Pass {
      HLSLPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      float4 frag() : SV_Target { return undefined_thing; }
      ENDHLSL
    }
    Pass {
      CGPROGRAM
      ENDCG
    }
  }
})SL";
  const std::string shader = "'" + (folder / "Two.shader").string() + "' --target gl --no-project";
  Outcome body = run_xshade("", "compile " + shader + " --pass body");
  EXPECT_EQ(body.exit_code, 0) << body.output;
  EXPECT_NE(body.output.find("// ---- frag ----"), std::string::npos) << body.output;
  Outcome reflected = run_xshade("", "compile " + shader + " --pass body --reflect");
  EXPECT_EQ(reflected.exit_code, 0) << reflected.output;
  EXPECT_NE(reflected.output.find("\"shader\": \"Test/Two\""), std::string::npos) << reflected.output;
  EXPECT_NE(reflected.output.find("\"display_name\": \"Colour\""), std::string::npos) << reflected.output;
  EXPECT_NE(reflected.output.find("\"name\": \"Body\""), std::string::npos) << reflected.output;
  EXPECT_NE(reflected.output.find("\"reflection\": {"), std::string::npos) << reflected.output;
  Outcome broken = run_xshade("", "compile " + shader + " --pass 1");
  EXPECT_EQ(broken.exit_code, 2) << broken.output;
  EXPECT_NE(broken.output.find("Two.shader:19:42: error: unknown name 'undefined_thing'"), std::string::npos)
      << broken.output;
  Outcome cg = run_xshade("", "compile " + shader + " --pass 2");
  EXPECT_EQ(cg.exit_code, 2) << cg.output;
  EXPECT_NE(cg.output.find("Two.shader:23:16: a CGPROGRAM includes Unity's HLSLSupport.cginc"), std::string::npos)
      << cg.output;
  Outcome unknown = run_xshade("", "compile " + shader + " --pass Outline");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("has no pass 'Outline' in the SubShader it draws (its passes: 0 (\"Body\"), 1, 2)"),
            std::string::npos)
      << unknown.output;
  // Every pass to files: each pass that compiles is written beside the others, the rest say why.
  Outcome every = run_xshade("", "compile " + shader + " -o '" + (folder / "out").string() + "'");
  EXPECT_EQ(every.exit_code, 2) << every.output;
  EXPECT_TRUE(fs::exists(folder / "out.pass0.frag.glsl")) << every.output;
  EXPECT_FALSE(fs::exists(folder / "out.pass1.frag.glsl")) << every.output;
  EXPECT_NE(every.output.find("unknown name 'undefined_thing'"), std::string::npos) << every.output;
  fs::remove_all(folder);
}

// A .shader compiles to the variant a material of its Properties' defaults draws, as run renders
// it: a [Toggle] on by default turns its keyword on, unless -D names another of its set.
TEST(CommandLine, CompileOfAUnityShaderTakesTheKeywordsItsTogglesSet) {
  const fs::path folder = fs::temp_directory_path() / "xshade_compile_toggle";
  fs::remove_all(folder);
  fs::create_directories(folder);
  std::ofstream(folder / "Toggled.shader") << R"SL(Shader "Test/Toggled" {
  Properties { [Toggle(_RED)] _Red ("Red", Float) = 1 }
  SubShader { Pass {
    HLSLPROGRAM
    #pragma vertex vert
    #pragma fragment frag
    #pragma multi_compile _GREEN _RED
    float4 vert(float4 p : POSITION) : SV_Position { return p; }
    #ifdef _RED
    float4 frag() : SV_Target { return float4(0.25, 0, 0, 1); }
    #else
    float4 frag() : SV_Target { return float4(0, 0.75, 0, 1); }
    #endif
    ENDHLSL
  } }
})SL";
  const std::string shader = "'" + (folder / "Toggled.shader").string() + "' --target gl --no-project";
  Outcome toggled = run_xshade("", "compile " + shader);
  EXPECT_EQ(toggled.exit_code, 0) << toggled.output;
  EXPECT_NE(toggled.output.find("0.25"), std::string::npos) << toggled.output;
  Outcome asked = run_xshade("", "compile " + shader + " -D _GREEN");
  EXPECT_EQ(asked.exit_code, 0) << asked.output;
  EXPECT_NE(asked.output.find("0.75"), std::string::npos) << asked.output;
  EXPECT_EQ(asked.output.find("0.25"), std::string::npos) << asked.output;
  fs::remove_all(folder);
}

}  // namespace
}  // namespace xshade::tests
