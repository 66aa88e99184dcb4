#include "spirv/spirv_compiler.h"

#include <gtest/gtest.h>

#include "glsl/flavour.h"

namespace xshade::spirv {
namespace {

constexpr std::string_view kFragment = R"(#version 450
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main() { color = vec4(uv, 0.0, 1.0); }
)";

TEST(SpirvCompiler, CompilesAndValidatesAFragmentShader) {
  auto module = compile_vulkan_glsl(kFragment, Stage::Fragment, "ok.frag");
  ASSERT_TRUE(module) << module.error().to_string();
  ASSERT_GT(module->words.size(), 5u);
  EXPECT_EQ(module->words[0], 0x07230203u);  // the SPIR-V magic number
  EXPECT_TRUE(module->warnings.empty());
}

TEST(SpirvCompiler, CompilesTheFullscreenVertexShader) {
  auto module = compile_vulkan_glsl(glsl::fullscreen_vertex_shader(glsl::Flavour::Vk),
                                    Stage::Vertex, "fullscreen.vert");
  ASSERT_TRUE(module) << module.error().to_string();
}

TEST(SpirvCompiler, BrokenGlslGivesTheLineNotACrash) {
  auto module = compile_vulkan_glsl(
      "#version 450\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() {\n"
      "  color = vec4(undeclared_thing, 1.0);\n"
      "}\n",
      Stage::Fragment, "broken.frag");
  ASSERT_FALSE(module);
  const Error& error = module.error();
  EXPECT_EQ(error.where.file, "broken.frag");
  ASSERT_FALSE(error.diagnostics.empty());
  EXPECT_EQ(error.diagnostics[0].where.file, "broken.frag");
  EXPECT_EQ(error.diagnostics[0].where.line, 4u);
  EXPECT_NE(error.diagnostics[0].message.find("undeclared_thing"), std::string::npos);
}

TEST(SpirvCompiler, EmptyAndGarbageInputFailCleanly) {
  EXPECT_FALSE(compile_vulkan_glsl("", Stage::Fragment, "empty.frag"));
  EXPECT_FALSE(compile_vulkan_glsl("\x01\x02#version 450\n}}}{{{", Stage::Vertex, "junk.vert"));
}

TEST(SpirvValidate, RejectsACorruptModule) {
  auto module = compile_vulkan_glsl(kFragment, Stage::Fragment, "ok.frag");
  ASSERT_TRUE(module);
  std::vector<uint32_t> corrupt = module->words;
  corrupt.resize(corrupt.size() / 2);  // cut in the middle of the instruction stream
  auto valid = validate(corrupt, "cut.spv");
  ASSERT_FALSE(valid);
  EXPECT_EQ(valid.error().where.file, "cut.spv");
  EXPECT_FALSE(valid.error().diagnostics.empty());
}

TEST(SpirvCompiler, ReportsItsVersion) {
  EXPECT_EQ(compiler_version().rfind("glslang ", 0), 0u);
}

}  // namespace
}  // namespace xshade::spirv
