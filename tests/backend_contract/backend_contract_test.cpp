// The Backend contract (harness/backend/backend.h), once, on every backend: the OpenGL backend on
// both routes to its context and the Vulkan backend. What only one API does (its contexts, its
// compiler's logs, validation, SPIR-V checks) stays in that backend's own tests.
//
// Shaders are written once in GLSL that both APIs accept (`#version 450`, set 0 implied): OpenGL
// takes the GLSL, Vulkan its SPIR-V.
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glsl/flavour.h"
#include "harness/backend/shared_backend_test.h"
#include "harness/gl/gl_backend.h"
#include "harness/vulkan/vulkan_backend.h"
#include "spirv/spirv_compiler.h"

namespace xshade::harness {
namespace {

enum class Api { GlOsmesa, GlEgl, Vulkan };

std::string api_test_name(const ::testing::TestParamInfo<Api>& info) {
  switch (info.param) {
    case Api::GlOsmesa: return "gl_osmesa";
    case Api::GlEgl: return "gl_egl";
    case Api::Vulkan: return "vk";
  }
  return "unknown";
}

Result<std::unique_ptr<Backend>> create_backend(Api api) {
  switch (api) {
    case Api::GlOsmesa: return create_gl_backend({.platform = GlPlatform::Osmesa});
    case Api::GlEgl: return create_gl_backend({.platform = GlPlatform::Egl});
    case Api::Vulkan: return create_vulkan_backend();
  }
  return fail("unknown API");
}

// The contract on every API, one backend each for the suite (SharedBackendTest).
class BackendContractTest : public SharedBackendTest<Api, &create_backend> {
 protected:

  // The GLSL for OpenGL, its SPIR-V for Vulkan.
  ShaderStageSource stage(const std::string& glsl, spirv::Stage kind, std::string name) const {
    ShaderStageSource source;
    if (GetParam() == Api::Vulkan) {
      auto module = spirv::compile_vulkan_glsl(glsl, kind, name);
      EXPECT_TRUE(module) << (module ? "" : module.error().to_string());
      if (module) source.spirv = module->words;
    } else {
      source.glsl = glsl;
    }
    source.name = std::move(name);
    return source;
  }

  Result<ProgramHandle> fullscreen_program(const std::string& name, const std::string& fragment,
                                           ProgramLayout layout = {}) {
    const bool gl = GetParam() != Api::Vulkan;
    ProgramDesc desc;
    desc.name = name;
    desc.vertex = stage(glsl::fullscreen_vertex_shader(gl ? glsl::Flavour::Gl : glsl::Flavour::Vk),
                        spirv::Stage::Vertex, "fullscreen.vert");
    desc.fragment = stage(fragment, spirv::Stage::Fragment, name + ".frag");
    desc.layout = std::move(layout);
    desc.fullscreen = true;
    return backend().create_program(desc);
  }

  Result<ProgramHandle> mesh_program(const std::string& name, const std::string& fragment) {
    ProgramDesc desc;
    desc.name = name;
    desc.vertex = stage(
        "#version 450\n"
        "layout(location = 0) in vec3 position;\n"
        "layout(location = 3) in vec2 uv;\n"
        "layout(location = 0) out vec2 v_uv;\n"
        "void main() { v_uv = uv; gl_Position = vec4(position, 1.0); }\n",
        spirv::Stage::Vertex, name + ".vert");
    desc.fragment = stage(fragment, spirv::Stage::Fragment, name + ".frag");
    return backend().create_program(desc);
  }

};

const char* const kUvFragment =
    "#version 450\n"
    "layout(location = 0) in vec2 uv;\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(uv, 0.0, 1.0); }\n";

const char* const kRedFragment =
    "#version 450\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(1.0, 0.0, 0.0, 1.0); }\n";

const char* const kCopyFragment =
    "#version 450\n"
    "layout(binding = 1) uniform sampler2D source;\n"
    "layout(location = 0) in vec2 uv;\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = texture(source, uv); }\n";

template <class T>
std::vector<std::byte> bytes_of(const T& value) {
  std::vector<std::byte> bytes(sizeof(T));
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

DrawItem draw(ProgramHandle program, MeshHandle mesh = {}, std::vector<UniformBinding> uniforms = {},
              std::vector<TextureBinding> textures = {}) {
  return DrawItem{program, mesh, std::move(uniforms), std::move(textures)};
}

TextureSlot texture_slot(std::string name, uint32_t binding) {
  return TextureSlot{std::move(name), binding, std::nullopt};
}

ProgramLayout layout(std::vector<UniformBlockSlot> blocks, std::vector<TextureSlot> textures) {
  return ProgramLayout{std::move(blocks), std::move(textures)};
}

Vertex vertex_at(float x, float y, float z) {
  Vertex vertex;
  vertex.position = {x, y, z};
  return vertex;
}

MeshData upper_half(float z) {
  return {{vertex_at(-1, 0, z), vertex_at(3, 0, z), vertex_at(-1, 4, z)}, {0, 1, 2}};
}

TextureData float_texture(uint32_t width, uint32_t height, const std::vector<float>& texels) {
  TextureData data{TextureFormat::Rgba32Float, width, height, {}};
  data.levels.emplace_back(texels.size() * sizeof(float));
  std::memcpy(data.levels[0].data(), texels.data(), data.levels[0].size());
  return data;
}

void expect_near(glm::vec4 actual, glm::vec4 expected, const std::string& what) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-5f) << what << ", channel " << c;
}

void expect_error(const Result<void>& result, const std::string& words) {
  ASSERT_FALSE(result) << "expected an error mentioning " << words;
  EXPECT_NE(result.error().message.find(words), std::string::npos) << result.error().message;
}

// ---- Drawing ------------------------------------------------------------------------------------

TEST_P(BackendContractTest, ClearGivesTheClearColourUnclamped) {
  auto target = backend().create_target({5, 3, true});
  ASSERT_TRUE(target) << target.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.clear_color = {-0.5f, 2.5f, 0.25f, 1.0f};
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image) << image.error().to_string();
  ASSERT_EQ(image->width, 5u);
  ASSERT_EQ(image->height, 3u);
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 5; ++x) expect_near(image->at(x, y), pass.clear_color, "clear");
}

TEST_P(BackendContractTest, FullscreenUvIsZeroAtTheTopLeftPixel) {
  const uint32_t w = 8, h = 4;
  auto target = backend().create_target({w, h, false});
  ASSERT_TRUE(target) << target.error().to_string();
  auto program = fullscreen_program("uv", kUvFragment);
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program));
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image) << image.error().to_string();
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x)
      expect_near(image->at(x, y), {(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h), 0.0f, 1.0f},
                  "pixel " + std::to_string(x) + "," + std::to_string(y));
}

TEST_P(BackendContractTest, MeshTriangleInUpperClipHalfLandsInTheTopRows) {
  auto target = backend().create_target({4, 4, true});
  ASSERT_TRUE(target);
  // Covers clip y in [0, 1] across the whole width.
  auto mesh = backend().upload_mesh(upper_half(0.5f));
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  auto program = mesh_program("red", kRedFragment);
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program, *mesh));
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      expect_near(image->at(x, y), y < 2 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0),
                  "pixel " + std::to_string(x) + "," + std::to_string(y));
}

TEST_P(BackendContractTest, DepthIsZeroToOneLessTestedAndSampleable) {
  auto target = backend().create_target({4, 4, true});
  auto readback = backend().create_target({4, 4, false});
  ASSERT_TRUE(target && readback);
  // Near: the top half at z = 0.25. Far: the whole target at z = 0.75, drawn second.
  auto near = backend().upload_mesh(upper_half(0.25f));
  auto far = backend().upload_mesh(
      {{vertex_at(-1, -1, 0.75f), vertex_at(3, -1, 0.75f), vertex_at(-1, 3, 0.75f)}, {0, 1, 2}});
  ASSERT_TRUE(near && far);
  auto red = mesh_program("red", kRedFragment);
  auto green = mesh_program("green",
                            "#version 450\n"
                            "layout(location = 0) out vec4 color;\n"
                            "void main() { color = vec4(0.0, 1.0, 0.0, 1.0); }\n");
  ASSERT_TRUE(red && green);
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*red, *near));
  pass.draws.push_back(draw(*green, *far));
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(1, 0), {1, 0, 0, 1}, "near wins at the top");
  expect_near(image->at(1, 3), {0, 1, 0, 1}, "far fills the bottom");

  // The depth of clip z = 0.25 (w = 1) is 0.25, and reads as .r.
  auto copy = fullscreen_program("depth_copy", kCopyFragment, layout({}, {texture_slot("source", 1)}));
  ASSERT_TRUE(copy) << copy.error().to_string();
  RenderPass second;
  second.target = *readback;
  second.draws.push_back(draw(*copy, {}, {}, {{"source", TextureSource::depth_of(*target, {Filter::Nearest, {}})}}));
  auto rendered = backend().render(second);
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto depth = backend().read_color(*readback);
  ASSERT_TRUE(depth);
  EXPECT_NEAR(depth->at(2, 0).r, 0.25f, 1e-6f);
  EXPECT_NEAR(depth->at(2, 3).r, 0.75f, 1e-6f);
}

TEST_P(BackendContractTest, TextureRowZeroIsTheTopAndUniformBlocksBindByName) {
  // Row 0 red, row 1 green; a uniform block scales the result.
  auto texture = backend().upload_texture(float_texture(2, 2, {1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1}));
  ASSERT_TRUE(texture) << texture.error().to_string();
  auto target = backend().create_target({4, 4, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program("textured",
                                    "#version 450\n"
                                    "layout(std140, binding = 2) uniform Params { vec4 scale; };\n"
                                    "layout(binding = 3) uniform sampler2D image;\n"
                                    "layout(location = 0) in vec2 uv;\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { color = texture(image, uv) * scale; }\n",
                                    layout({{"Params", 2, 16}}, {texture_slot("image", 3)}));
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program, {}, {{"Params", bytes_of(glm::vec4(2.0f, 3.0f, 1.0f, 1.0f))}},
                            {{"image", TextureSource::texture(*texture, {Filter::Nearest, {}})}}));
  auto rendered = backend().render(pass);
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 0), {2, 0, 0, 1}, "top row samples texture row 0");
  expect_near(image->at(3, 3), {0, 3, 0, 1}, "bottom row samples texture row 1");
}

TEST_P(BackendContractTest, SpecialFloatValuesReachReadBack) {
  auto target = backend().create_target({1, 1, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program(
      "special",
      "#version 450\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() {\n"
      "  color = vec4(-3.5, 1e30, uintBitsToFloat(0x7f800000u), uintBitsToFloat(0x7fc00000u));\n"
      "}\n");
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program));
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  glm::vec4 pixel = image->at(0, 0);
  EXPECT_EQ(pixel.r, -3.5f);
  EXPECT_EQ(pixel.g, 1e30f);
  EXPECT_TRUE(std::isinf(pixel.b) && pixel.b > 0) << pixel.b;
  EXPECT_TRUE(std::isnan(pixel.a)) << pixel.a;
}

TEST_P(BackendContractTest, ASecondColourAttachmentTakesLocationOne) {
  auto target = backend().create_target({4, 2, true, /*second_color=*/true});
  ASSERT_TRUE(target) << target.error().to_string();
  auto both = fullscreen_program("both",
                                 "#version 450\n"
                                 "layout(location = 0) out vec4 color;\n"
                                 "layout(location = 1) out vec4 second;\n"
                                 "void main() {\n"
                                 "  color = vec4(0.25, 0.5, 0.75, 1.0);\n"
                                 "  second = vec4(floor(gl_FragCoord.xy), 16777215.0, -2.0);\n"
                                 "}\n");
  ASSERT_TRUE(both) << both.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.clear_color = {9.0f, 9.0f, 9.0f, 9.0f};
  pass.draws.push_back(draw(*both));
  ASSERT_TRUE(backend().render(pass));
  auto color = backend().read_color(*target);
  auto second = backend().read_second_color(*target);
  ASSERT_TRUE(color && second) << (second ? "" : second.error().to_string());
  for (uint32_t y = 0; y < 2; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      expect_near(color->at(x, y), {0.25f, 0.5f, 0.75f, 1.0f}, "colour");
      // Whole numbers up to 2^24 are exact in the float target: what a traced program counts on.
      EXPECT_EQ(second->at(x, y), glm::vec4(float(x), float(y), 16777215.0f, -2.0f)) << x << "," << y;
    }

  auto plain = backend().create_target({1, 1, false});
  ASSERT_TRUE(plain);
  auto missing = backend().read_second_color(*plain);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("no second colour attachment"), std::string::npos) << missing.error().message;
}

TEST_P(BackendContractTest, ADrawProducesNoDriverMessages) {
  auto target = backend().create_target({16, 16, true});
  auto program = fullscreen_program("uv", kUvFragment);
  ASSERT_TRUE(target && program);
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program));
  ASSERT_TRUE(backend().render(pass));
  ASSERT_TRUE(backend().read_color(*target));
  EXPECT_EQ(backend().take_driver_messages(), std::vector<std::string>{});
}

// ---- Binding mistakes ---------------------------------------------------------------------------

TEST_P(BackendContractTest, BindingMistakesFailWithClearMessages) {
  auto target = backend().create_target({2, 2, false});
  auto other = backend().create_target({2, 2, false});
  auto program = fullscreen_program("tinted",
                                    "#version 450\n"
                                    "layout(std140, binding = 0) uniform Tint { vec4 tint; };\n"
                                    "layout(binding = 1) uniform sampler2D source;\n"
                                    "layout(location = 0) in vec2 uv;\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { color = texture(source, uv) * tint; }\n",
                                    layout({{"Tint", 0, 16}}, {texture_slot("source", 1)}));
  ASSERT_TRUE(target && other && program) << program.error().to_string();
  const auto tint = bytes_of(glm::vec4(1.0f));
  const TextureBinding source{"source", TextureSource::color_of(*other)};

  auto render_with = [&](DrawItem item) {
    RenderPass pass;
    pass.target = *target;
    pass.draws.push_back(std::move(item));
    return backend().render(pass);
  };
  expect_error(render_with(draw(*program, {}, {{"Nope", tint}, {"Tint", tint}}, {source})), "'Nope'");
  expect_error(render_with(draw(*program, {}, {}, {source})), "'Tint' is not bound");
  expect_error(render_with(draw(*program, {}, {{"Tint", bytes_of(1.0f)}}, {source})), "needs 16 bytes but 4");
  expect_error(render_with(draw(*program, {}, {{"Tint", tint}}, {})), "'source'");
  expect_error(render_with(draw(*program, {}, {{"Tint", tint}}, {{"source", TextureSource::color_of(*target)}})),
               "own target");
  expect_error(render_with(draw(ProgramHandle{9999})), "no such program (handle 9999)");
  expect_error(render_with(draw(*program, {}, {{"Tint", tint}}, {{"source", TextureSource::depth_of(*other)}})),
               "which has no depth");

  auto good = render_with(draw(*program, {}, {{"Tint", tint}}, {source}));
  EXPECT_TRUE(good) << good.error().to_string();
}

TEST_P(BackendContractTest, AMeshProgramWithoutAMeshFails) {
  auto target = backend().create_target({2, 2, true});
  auto program = mesh_program("red", kRedFragment);
  ASSERT_TRUE(target && program);
  RenderPass pass{*target, glm::vec4(0.0f), 1.0f, {draw(*program)}};
  expect_error(backend().render(pass), "no such mesh (handle 0)");
}

// ---- Destruction --------------------------------------------------------------------------------

TEST_P(BackendContractTest, DestroyedHandlesAreRefusedWithAnError) {
  auto target = backend().create_target({2, 2, true});
  auto sampled = backend().create_target({2, 2, true});
  auto mesh = backend().upload_mesh(upper_half(0.5f));
  auto texture = backend().upload_texture(float_texture(1, 1, {1, 1, 1, 1}));
  auto red = mesh_program("red", kRedFragment);
  auto copy = fullscreen_program("copy", kCopyFragment, layout({}, {texture_slot("source", 1)}));
  ASSERT_TRUE(target && sampled && mesh && texture && red && copy);

  ASSERT_TRUE(backend().destroy(*mesh));
  expect_error(backend().render({*target, glm::vec4(0.0f), 1.0f, {draw(*red, *mesh)}}), "no such mesh");
  ASSERT_TRUE(backend().destroy(*red));
  expect_error(backend().render({*target, glm::vec4(0.0f), 1.0f, {draw(*red, *mesh)}}), "no such program");
  ASSERT_TRUE(backend().destroy(*texture));
  expect_error(backend().render({*target, glm::vec4(0.0f), 1.0f,
                                 {draw(*copy, {}, {}, {{"source", TextureSource::texture(*texture)}})}}),
               "missing texture");
  ASSERT_TRUE(backend().destroy(*sampled));
  expect_error(backend().render({*target, glm::vec4(0.0f), 1.0f,
                                 {draw(*copy, {}, {}, {{"source", TextureSource::color_of(*sampled)}})}}),
               "missing target");
  ASSERT_TRUE(backend().destroy(*target));
  expect_error(backend().render({*target, glm::vec4(0.0f), 1.0f, {}}), "no such target");
  auto read = backend().read_color(*target);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("no such target"), std::string::npos) << read.error().message;
  EXPECT_TRUE(backend().destroy(*copy));
}

TEST_P(BackendContractTest, DestroyingTwiceOrAnUnknownHandleIsAnError) {
  auto target = backend().create_target({2, 2, false});
  auto mesh = backend().upload_mesh(upper_half(0.5f));
  auto texture = backend().upload_texture(float_texture(1, 1, {1, 1, 1, 1}));
  auto program = fullscreen_program("uv", kUvFragment);
  ASSERT_TRUE(target && mesh && texture && program);
  ASSERT_TRUE(backend().destroy(*target));
  ASSERT_TRUE(backend().destroy(*mesh));
  ASSERT_TRUE(backend().destroy(*texture));
  ASSERT_TRUE(backend().destroy(*program));
  expect_error(backend().destroy(*target), "no such target");
  expect_error(backend().destroy(*mesh), "no such mesh");
  expect_error(backend().destroy(*texture), "no such texture");
  expect_error(backend().destroy(*program), "no such program");
  expect_error(backend().destroy(TargetHandle{}), "no such target (handle 0)");
  expect_error(backend().destroy(MeshHandle{123456}), "no such mesh (handle 123456)");
}

TEST_P(BackendContractTest, CreatingAfterDestroyingWorksAndGivesANewHandle) {
  auto program = fullscreen_program("copy", kCopyFragment, layout({}, {texture_slot("source", 1)}));
  ASSERT_TRUE(program) << program.error().to_string();
  TargetHandle previous;
  for (int round = 0; round < 3; ++round) {
    const float value = float(round + 1);
    auto texture = backend().upload_texture(float_texture(1, 1, {value, 0, 0, 1}));
    auto target = backend().create_target({64, 64, true});
    ASSERT_TRUE(texture && target);
    EXPECT_NE(*target, previous) << "a destroyed target's handle is not given out again";
    previous = *target;
    RenderPass pass{*target, glm::vec4(0.0f), 1.0f,
                    {draw(*program, {}, {}, {{"source", TextureSource::texture(*texture, {Filter::Nearest, {}})}})}};
    auto rendered = backend().render(pass);
    ASSERT_TRUE(rendered) << rendered.error().to_string();
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    expect_near(image->at(5, 7), {value, 0, 0, 1}, "round " + std::to_string(round));
    ASSERT_TRUE(backend().destroy(*texture));
    ASSERT_TRUE(backend().destroy(*target));
  }
}

TEST_P(BackendContractTest, ATargetSampledByAnEarlierPassCanBeDestroyedAfterIt) {
  auto first = backend().create_target({4, 4, true});
  auto second = backend().create_target({4, 4, false});
  auto uv = fullscreen_program("uv", kUvFragment);
  auto copy = fullscreen_program("copy", kCopyFragment, layout({}, {texture_slot("source", 1)}));
  ASSERT_TRUE(first && second && uv && copy);
  ASSERT_TRUE(backend().render({*first, glm::vec4(0.0f), 1.0f, {draw(*uv)}}));
  ASSERT_TRUE(backend().render({*second, glm::vec4(0.0f), 1.0f,
                                {draw(*copy, {}, {}, {{"source", TextureSource::color_of(*first, {Filter::Nearest, {}})}})}}));
  ASSERT_TRUE(backend().destroy(*first));
  auto image = backend().read_color(*second);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 0), {0.125f, 0.125f, 0.0f, 1.0f}, "the copy outlives its source");
  ASSERT_TRUE(backend().destroy(*second));
}

INSTANTIATE_TEST_SUITE_P(Backends, BackendContractTest, ::testing::Values(Api::GlOsmesa, Api::GlEgl, Api::Vulkan),
                         api_test_name);

}  // namespace
}  // namespace xshade::harness
