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
  auto module =
      compile_vulkan_glsl(glsl::fullscreen_vertex_shader(glsl::Flavour::Vk), Stage::Vertex, "fullscreen.vert");
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

TEST(SpirvValidate, ItsRefusalIsToldFromTheCompilersOwn) {
  auto module = compile_vulkan_glsl(kFragment, Stage::Fragment, "ok.frag");
  ASSERT_TRUE(module);
  std::vector<uint32_t> corrupt = module->words;
  corrupt.resize(corrupt.size() / 2);
  auto valid = validate(corrupt, "cut.spv");
  ASSERT_FALSE(valid);
  EXPECT_TRUE(is_spirv_validation_failure(valid.error()));
  auto broken = compile_vulkan_glsl("#version 450\nvoid main() { x = 1; }\n", Stage::Fragment, "broken.frag");
  ASSERT_FALSE(broken);
  EXPECT_FALSE(is_spirv_validation_failure(broken.error()));
}

constexpr std::string_view kOpenGlFragment = R"(#version 450 core
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
uniform sampler2D tex;
void main() { color = texture(tex, uv); }
)";

TEST(OpenGlGlsl, AcceptsAFragmentShaderWithALooseSampler) {
  // A sampler outside any block, with no binding: OpenGL GLSL has them, Vulkan GLSL does not.
  auto valid = validate_opengl_glsl(kOpenGlFragment, Stage::Fragment, "gl.frag");
  ASSERT_TRUE(valid) << valid.error().to_string();
  EXPECT_TRUE(valid->empty());
  EXPECT_FALSE(compile_vulkan_glsl(kOpenGlFragment, Stage::Fragment, "gl.frag"));
}

TEST(OpenGlGlsl, RefusesWhatOpenGlRefusesWithTheLine) {
  auto valid = validate_opengl_glsl(
      "#version 450 core\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() {\n"
      "  color = vec4(undeclared_thing, 1.0);\n"
      "}\n",
      Stage::Fragment, "broken.frag");
  ASSERT_FALSE(valid);
  EXPECT_EQ(valid.error().where.file, "broken.frag");
  ASSERT_FALSE(valid.error().diagnostics.empty());
  EXPECT_EQ(valid.error().diagnostics[0].where.file, "broken.frag");
  EXPECT_EQ(valid.error().diagnostics[0].where.line, 4u);
  EXPECT_NE(valid.error().diagnostics[0].message.find("undeclared_thing"), std::string::npos);
}

TEST(OpenGlGlsl, KnowsTheStage) {
  // gl_FragCoord is the fragment stage's; a vertex shader cannot read it.
  constexpr std::string_view kReadsFragCoord = R"(#version 450 core
layout(location = 0) out vec4 color;
void main() { color = gl_FragCoord; }
)";
  EXPECT_TRUE(validate_opengl_glsl(kReadsFragCoord, Stage::Fragment, "a.frag"));
  EXPECT_FALSE(validate_opengl_glsl(kReadsFragCoord, Stage::Vertex, "a.vert"));
}

TEST(OpenGlGlsl, RefusesOverlappingLocations) {
  // An array takes a location per element: [2] at 2 holds 2 and 3.
  auto valid = validate_opengl_glsl(R"(#version 450 core
layout(location = 2) out vec3 lights[2];
layout(location = 3) out vec3 view;
void main() { gl_Position = vec4(0.0); lights[0] = vec3(0.0); lights[1] = vec3(0.0); view = vec3(0.0); }
)",
                                    Stage::Vertex, "lights.vert");
  ASSERT_FALSE(valid);
  ASSERT_FALSE(valid.error().diagnostics.empty());
  EXPECT_NE(valid.error().diagnostics[0].message.find("overlapping use of location 3"), std::string::npos)
      << valid.error().to_string();
  EXPECT_EQ(valid.error().diagnostics[0].where.line, 3u);
}

TEST(OpenGlGlsl, EmptyAndGarbageInputFailCleanly) {
  EXPECT_FALSE(validate_opengl_glsl("", Stage::Fragment, "empty.frag"));
  EXPECT_FALSE(validate_opengl_glsl("\x01\x02#version 450\n}}}{{{", Stage::Vertex, "junk.vert"));
}

TEST(SpirvCompiler, ReportsItsVersion) { EXPECT_EQ(compiler_version().rfind("glslang ", 0), 0u); }

}  // namespace
}  // namespace xshade::spirv
