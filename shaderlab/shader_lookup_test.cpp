#include "shaderlab/shader_lookup.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace xshade::shaderlab {
namespace {

namespace fs = std::filesystem;

TEST(ShaderLookup, TheNameIsTheShaderLinesStringAfterCommentsAndAByteOrderMark) {
  EXPECT_EQ(declared_shader_name("Shader \"Unlit/Texture\" {"), "Unlit/Texture");
  EXPECT_EQ(declared_shader_name("\xEF\xBB\xBF// licence\n/* more\n lines */\n  Shader\n\t\"Hidden/A B\"{}"),
            "Hidden/A B");
  EXPECT_EQ(declared_shader_name("// Shader \"Commented/Out\"\nShader \"Real\" {}"), "Real");
  EXPECT_EQ(declared_shader_name("Properties { } Shader \"Late\""), "");
  EXPECT_EQ(declared_shader_name("Shader Unquoted {"), "");
  EXPECT_EQ(declared_shader_name("Shader \"unterminated"), "");
  EXPECT_EQ(declared_shader_name("/* open"), "");
}

TEST(ShaderLookup, AShaderIsFoundByItsNameUnderTheFoldersInTheirOrder) {
  const fs::path root = fs::temp_directory_path() / ("xshade_shader_lookup_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "first" / "deep" / "er");
  fs::create_directories(root / "second");
  std::ofstream(root / "first" / "deep" / "er" / "a.shader") << "// A\nShader \"Legacy Shaders/Diffuse\" {}\n";
  std::ofstream(root / "second" / "b.shader") << "Shader \"Legacy Shaders/Diffuse\" {}\n";
  std::ofstream(root / "second" / "c.shader") << "Shader \"Legacy Shaders/VertexLit\" {}\n";
  std::ofstream(root / "second" / "not_a_shader.txt") << "Shader \"Hidden/Text\" {}\n";
  const std::vector<fs::path> folders = {root / "first", root / "second"};
  auto diffuse = find_shader_named("Legacy Shaders/Diffuse", folders);
  ASSERT_TRUE(diffuse) << diffuse.error().to_string();
  EXPECT_EQ(*diffuse, root / "first" / "deep" / "er" / "a.shader");
  auto vertex_lit = find_shader_named("Legacy Shaders/VertexLit", folders);
  ASSERT_TRUE(vertex_lit) << vertex_lit.error().to_string();
  EXPECT_EQ(*vertex_lit, root / "second" / "c.shader");
  auto text = find_shader_named("Hidden/Text", folders);
  ASSERT_FALSE(text);
  EXPECT_EQ(text.error().message, "no .shader in the shader folders declares Shader \"Hidden/Text\" (searched " +
                                      (root / "first").string() + ", " + (root / "second").string() +
                                      " and their subfolders)");
  EXPECT_FALSE(find_shader_named("legacy shaders/diffuse", folders)) << "Unity's names are matched exactly";
  // A legacy shader by its name before Unity 5, as Unity's own shaders name them in a Fallback.
  auto old_name = find_shader_named("VertexLit", folders);
  ASSERT_TRUE(old_name) << old_name.error().to_string();
  EXPECT_EQ(*old_name, root / "second" / "c.shader");
  fs::remove_all(root);
}

TEST(ShaderLookup, AUsedPassIsTheShadersNameAndThePassesSplitAtTheLastSlash) {
  EXPECT_EQ(split_used_pass("Reflective/Bumped Unlit/BASE"),
            (std::pair<std::string, std::string>{"Reflective/Bumped Unlit", "BASE"}));
  EXPECT_EQ(split_used_pass("NOSLASH"), (std::pair<std::string, std::string>{"NOSLASH", ""}));
}

}  // namespace
}  // namespace xshade::shaderlab
