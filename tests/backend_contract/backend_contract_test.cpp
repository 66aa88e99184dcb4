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
  return fail(ErrorKind::Internal, "unknown API");
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

  Result<ProgramHandle> mesh_program(const std::string& name, const std::string& fragment, ProgramLayout layout = {}) {
    ProgramDesc desc;
    desc.name = name;
    desc.layout = std::move(layout);
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
  return DrawItem{program, mesh, std::move(uniforms), std::move(textures), {}};
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

MeshData upper_half(float z) { return {{vertex_at(-1, 0, z), vertex_at(3, 0, z), vertex_at(-1, 4, z)}, {0, 1, 2}}; }

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

// With a stencil buffer beside the depth too: the depth is still what a pass samples.
TEST_P(BackendContractTest, DepthIsZeroToOneLessTestedAndSampleable) {
  for (bool stencil : {false, true}) {
    SCOPED_TRACE(stencil ? "with stencil" : "depth alone");
    auto target = backend().create_target({4, 4, true, false, stencil});
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
  auto program =
      fullscreen_program("special",
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

// ---- Render state ---------------------------------------------------------------------------------

// A program that paints what its block says, full screen or on a mesh.
const char* const kPaintFragment =
    "#version 450\n"
    "layout(std140, binding = 0) uniform Paint { vec4 paint; };\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = paint; }\n";

std::vector<UniformBinding> paint(glm::vec4 colour) { return {{"Paint", bytes_of(colour)}}; }

// Direct3D's blend factors and operations, worked out on the host.
glm::vec4 blend_factor(BlendFactor factor, glm::vec4 source, glm::vec4 destination) {
  switch (factor) {
    case BlendFactor::Zero: return glm::vec4(0.0f);
    case BlendFactor::One: return glm::vec4(1.0f);
    case BlendFactor::SrcColor: return source;
    case BlendFactor::OneMinusSrcColor: return glm::vec4(1.0f) - source;
    case BlendFactor::DstColor: return destination;
    case BlendFactor::OneMinusDstColor: return glm::vec4(1.0f) - destination;
    case BlendFactor::SrcAlpha: return glm::vec4(source.a);
    case BlendFactor::OneMinusSrcAlpha: return glm::vec4(1.0f - source.a);
    case BlendFactor::DstAlpha: return glm::vec4(destination.a);
    case BlendFactor::OneMinusDstAlpha: return glm::vec4(1.0f - destination.a);
    case BlendFactor::SrcAlphaSaturate: {
      const float f = std::min(source.a, 1.0f - destination.a);
      return {f, f, f, 1.0f};
    }
  }
  return glm::vec4(0.0f);
}

glm::vec4 blended(const BlendState& b, glm::vec4 s, glm::vec4 d) {
  const glm::vec4 sf = blend_factor(b.color_source, s, d), df = blend_factor(b.color_destination, s, d);
  const glm::vec4 saf = blend_factor(b.alpha_source, s, d), daf = blend_factor(b.alpha_destination, s, d);
  const auto apply = [](BlendOp op, float src, float src_factor, float dst, float dst_factor) {
    switch (op) {
      case BlendOp::Add: return src * src_factor + dst * dst_factor;
      case BlendOp::Subtract: return src * src_factor - dst * dst_factor;
      case BlendOp::ReverseSubtract: return dst * dst_factor - src * src_factor;
      case BlendOp::Min: return std::min(src, dst);
      case BlendOp::Max: return std::max(src, dst);
    }
    return 0.0f;
  };
  glm::vec4 out;
  for (int c = 0; c < 3; ++c) out[c] = apply(b.color_op, s[c], sf[c], d[c], df[c]);
  out.a = apply(b.alpha_op, s.a, saf.a, d.a, daf.a);
  return out;
}

// Every factor as the source's and the destination's, every operation, alpha apart from colour:
// what the backend blends is what the host works out.
TEST_P(BackendContractTest, BlendingIsDirect3DsForEveryFactorAndOperation) {
  auto target = backend().create_target({1, 1, false});
  auto program = fullscreen_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && program);
  const glm::vec4 destination{0.2f, 0.4f, 0.6f, 0.8f}, source{0.5f, 0.25f, 1.0f, 0.3f};
  std::vector<BlendState> cases;
  const BlendFactor factors[] = {BlendFactor::Zero,
                                 BlendFactor::One,
                                 BlendFactor::SrcColor,
                                 BlendFactor::OneMinusSrcColor,
                                 BlendFactor::DstColor,
                                 BlendFactor::OneMinusDstColor,
                                 BlendFactor::SrcAlpha,
                                 BlendFactor::OneMinusSrcAlpha,
                                 BlendFactor::DstAlpha,
                                 BlendFactor::OneMinusDstAlpha,
                                 BlendFactor::SrcAlphaSaturate};
  for (BlendFactor factor : factors) {
    cases.push_back({true, factor, BlendFactor::One, BlendFactor::One, BlendFactor::Zero});
    if (factor != BlendFactor::SrcAlphaSaturate)  // a source factor only, in Direct3D 11
      cases.push_back({true, BlendFactor::One, factor, BlendFactor::Zero, factor});
  }
  for (BlendOp op : {BlendOp::Add, BlendOp::Subtract, BlendOp::ReverseSubtract, BlendOp::Min, BlendOp::Max})
    cases.push_back({true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha, BlendFactor::One, BlendFactor::One, op,
                     op == BlendOp::Min ? BlendOp::Max : BlendOp::Add});
  for (size_t i = 0; i < cases.size(); ++i) {
    RenderPass pass;
    pass.target = *target;
    pass.clear_color = destination;
    pass.draws.push_back(draw(*program, {}, paint(source)));
    pass.draws.back().state.blend = cases[i];
    auto rendered = backend().render(pass);
    ASSERT_TRUE(rendered) << rendered.error().to_string();
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    expect_near(image->at(0, 0), blended(cases[i], source, destination), "blend case " + std::to_string(i));
  }
}

TEST_P(BackendContractTest, TheColourMaskKeepsWhatItDoesNotWrite) {
  auto target = backend().create_target({1, 1, false});
  auto program = fullscreen_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && program);
  const glm::vec4 before{0.2f, 0.4f, 0.6f, 0.8f}, painted{1.0f, 1.0f, 1.0f, 1.0f};
  for (uint8_t mask = 0; mask <= kColorWriteAll; ++mask) {
    RenderPass pass;
    pass.target = *target;
    pass.clear_color = before;
    pass.draws.push_back(draw(*program, {}, paint(painted)));
    pass.draws.back().state.color_write = mask;
    ASSERT_TRUE(backend().render(pass));
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    glm::vec4 expected;
    for (int c = 0; c < 4; ++c) expected[c] = (mask >> c) & 1 ? painted[c] : before[c];
    expect_near(image->at(0, 0), expected, "mask " + std::to_string(mask));
  }
}

// Two triangles side by side on a 4 x 2 target: the left one clockwise in the image, the right
// one counter-clockwise (the front face: backend.h's DrawState).
// OpenGL's row order: clip -y lands in row 0, the faces culled are the same ones, and a
// full-screen program's uv (0, 0) is still row 0.
TEST_P(BackendContractTest, ABottomRowOriginPutsClipMinusYInRowZeroAndKeepsFacesAndFullscreenUv) {
  auto target = backend().create_target({4, 4, true});
  auto upper = backend().upload_mesh(upper_half(0.5f));
  // The culling test's two triangles: the left one back-facing, the right one front-facing.
  auto pair = backend().upload_mesh({{vertex_at(-1, -1, 0.5f), vertex_at(-1, 1, 0.5f), vertex_at(0, -1, 0.5f),
                                      vertex_at(0, -1, 0.5f), vertex_at(1, -1, 0.5f), vertex_at(1, 1, 0.5f)},
                                     {0, 1, 2, 3, 4, 5}});
  auto red = mesh_program("red", kRedFragment);
  auto uv = fullscreen_program("uv", kUvFragment);
  ASSERT_TRUE(target && upper && pair && red && uv);
  RenderPass pass;
  pass.target = *target;
  pass.row_origin = RowOrigin::Bottom;
  pass.draws.push_back(draw(*red, *upper));
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x)
      expect_near(image->at(x, y), y >= 2 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0),
                  "upper clip half, pixel " + std::to_string(x) + "," + std::to_string(y));

  pass.draws = {draw(*red, *pair)};
  pass.draws.back().state.cull = CullMode::Back;
  ASSERT_TRUE(backend().render(pass));
  image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 2), glm::vec4(0), "cull back: the back face is culled");
  expect_near(image->at(3, 2), glm::vec4(1, 0, 0, 1), "cull back: the front face is drawn");

  pass.draws = {draw(*uv)};
  ASSERT_TRUE(backend().render(pass));
  image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 0), {0.125f, 0.125f, 0.0f, 1.0f}, "full-screen uv at row 0");

  // And back to the top origin in the next pass.
  pass.row_origin = RowOrigin::Top;
  pass.draws = {draw(*red, *upper)};
  ASSERT_TRUE(backend().render(pass));
  image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 0), glm::vec4(1, 0, 0, 1), "the next pass's own origin");
}

TEST_P(BackendContractTest, CullingRemovesTheFacesTheStateNames) {
  auto target = backend().create_target({4, 2, true});
  auto mesh = backend().upload_mesh({{vertex_at(-1, -1, 0.5f), vertex_at(-1, 1, 0.5f), vertex_at(0, -1, 0.5f),
                                      vertex_at(0, -1, 0.5f), vertex_at(1, -1, 0.5f), vertex_at(1, 1, 0.5f)},
                                     {0, 1, 2, 3, 4, 5}});
  auto program = mesh_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && mesh && program);
  for (CullMode cull : {CullMode::Off, CullMode::Back, CullMode::Front}) {
    RenderPass pass;
    pass.target = *target;
    pass.draws.push_back(draw(*program, *mesh, paint({1, 0, 0, 1})));
    pass.draws.back().state.cull = cull;
    ASSERT_TRUE(backend().render(pass));
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    // Pixel (0, 1) lies inside the left triangle, (3, 1) inside the right one.
    const bool front_drawn = cull != CullMode::Front, back_drawn = cull != CullMode::Back;
    const std::string name = cull == CullMode::Off ? "off" : cull == CullMode::Back ? "back" : "front";
    expect_near(image->at(0, 1), back_drawn ? glm::vec4(1, 0, 0, 1) : glm::vec4(0), "cull " + name + ", back face");
    expect_near(image->at(3, 1), front_drawn ? glm::vec4(1, 0, 0, 1) : glm::vec4(0), "cull " + name + ", front face");
  }
}

// Whether `a <op> b` holds: the depth test's (the incoming depth against the stored one) and the
// stencil test's (the masked reference against the masked stored value), as Direct3D defines them.
template <class T>
bool compare_holds(CompareOp op, T a, T b) {
  switch (op) {
    case CompareOp::Never: return false;
    case CompareOp::Less: return a < b;
    case CompareOp::Equal: return a == b;
    case CompareOp::LessEqual: return a <= b;
    case CompareOp::Greater: return a > b;
    case CompareOp::NotEqual: return a != b;
    case CompareOp::GreaterEqual: return a >= b;
    case CompareOp::Always: return true;
  }
  return false;
}

// A near red plane (z 0.25) over the top half, then a far green one (z 0.75) over everything,
// each comparison and with and without depth writes: each pixel as the host's test decides it.
TEST_P(BackendContractTest, TheDepthTestAndWriteAreAsTheStateSays) {
  auto target = backend().create_target({2, 4, true});
  auto near = backend().upload_mesh(upper_half(0.25f));
  auto far =
      backend().upload_mesh({{vertex_at(-1, -1, 0.75f), vertex_at(3, -1, 0.75f), vertex_at(-1, 3, 0.75f)}, {0, 1, 2}});
  auto program = mesh_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && near && far && program);
  const glm::vec4 red{1, 0, 0, 1}, green{0, 1, 0, 1}, clear{0, 0, 0, 0};
  for (bool near_writes : {true, false})
    for (CompareOp op : {CompareOp::Never, CompareOp::Less, CompareOp::Equal, CompareOp::LessEqual, CompareOp::Greater,
                         CompareOp::NotEqual, CompareOp::GreaterEqual, CompareOp::Always}) {
      RenderPass pass;
      pass.target = *target;
      pass.draws.push_back(draw(*program, *near, paint(red)));
      pass.draws.back().state.depth_write = near_writes;
      pass.draws.push_back(draw(*program, *far, paint(green)));
      pass.draws.back().state.depth_compare = op;
      ASSERT_TRUE(backend().render(pass));
      auto image = backend().read_color(*target);
      ASSERT_TRUE(image);
      for (uint32_t y : {0u, 3u}) {
        const bool covered_by_near = y < 2;
        const float stored = covered_by_near && near_writes ? 0.25f : 1.0f;
        const glm::vec4 under = covered_by_near ? red : clear;
        expect_near(image->at(0, y), compare_holds(op, 0.75f, stored) ? green : under,
                    "compare " + std::to_string(int(op)) + (near_writes ? ", written" : ", not written") + ", row " +
                        std::to_string(y));
      }
    }
}

// A second plane at the depth of the first fails a less test; offset towards the viewer by one
// unit of depth it passes, offset away it still fails.
TEST_P(BackendContractTest, ADepthOffsetMovesASurfaceByUnitsOfDepth) {
  auto target = backend().create_target({2, 2, true});
  auto plane =
      backend().upload_mesh({{vertex_at(-1, -1, 0.5f), vertex_at(3, -1, 0.5f), vertex_at(-1, 3, 0.5f)}, {0, 1, 2}});
  auto program = mesh_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && plane && program);
  for (float units : {0.0f, -1.0f, 1.0f}) {
    RenderPass pass;
    pass.target = *target;
    pass.draws.push_back(draw(*program, *plane, paint({1, 0, 0, 1})));
    pass.draws.push_back(draw(*program, *plane, paint({0, 1, 0, 1})));
    pass.draws.back().state.depth_bias_units = units;
    ASSERT_TRUE(backend().render(pass));
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    expect_near(image->at(1, 1), units < 0 ? glm::vec4(0, 1, 0, 1) : glm::vec4(1, 0, 0, 1),
                "offset " + std::to_string(units));
  }
}

// Direct3D's stencil operations on an 8-bit value, worked out on the host.
uint8_t stencil_after(StencilOp op, uint8_t stored, uint8_t reference) {
  switch (op) {
    case StencilOp::Keep: return stored;
    case StencilOp::Zero: return 0;
    case StencilOp::Replace: return reference;
    case StencilOp::IncrementClamp: return stored == 255 ? 255 : uint8_t(stored + 1);
    case StencilOp::DecrementClamp: return stored == 0 ? 0 : uint8_t(stored - 1);
    case StencilOp::Invert: return uint8_t(~stored);
    case StencilOp::IncrementWrap: return uint8_t(stored + 1);
    case StencilOp::DecrementWrap: return uint8_t(stored - 1);
  }
  return stored;
}

// The stored value after one face's test and operations, where the depth test passed or not.
uint8_t stencil_written(const StencilState& s, const StencilFaceState& face, uint8_t stored, bool depth_passed) {
  const bool passed = compare_holds(face.compare, s.reference & s.read_mask, stored & s.read_mask);
  const StencilOp op = !passed ? face.fail : !depth_passed ? face.depth_fail : face.pass;
  return uint8_t((stored & ~s.write_mask) | (stencil_after(op, stored, s.reference) & s.write_mask));
}

// A 4 x 2 target with stencil: a near plane (depth only) over the top row, then the drawn state's
// quads, back faces over columns 0 and 1, front faces over 2 and 3, writing no colour. Eight
// probe draws then read the stored value back bit by bit (each adds 2^b / 256 to red where bit b
// is set), so that every pixel's stencil is compared with the host's: every comparison, every
// operation as pass, fail and depth-fail, at 0, 255 and between, the masks, each face its own.
TEST_P(BackendContractTest, TheStencilTestAndOperationsAreDirect3Ds) {
  auto target = backend().create_target({4, 2, true, false, /*stencil=*/true});
  auto near = backend().upload_mesh(upper_half(0.25f));
  auto quads = backend().upload_mesh(
      {{vertex_at(-1, -1, 0.5f), vertex_at(-1, 1, 0.5f), vertex_at(0, 1, 0.5f), vertex_at(0, -1, 0.5f),
        vertex_at(0, -1, 0.5f), vertex_at(1, -1, 0.5f), vertex_at(1, 1, 0.5f), vertex_at(0, 1, 0.5f)},
       {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}});
  auto whole =
      backend().upload_mesh({{vertex_at(-1, -1, 0.5f), vertex_at(3, -1, 0.5f), vertex_at(-1, 3, 0.5f)}, {0, 1, 2}});
  auto program = mesh_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && near && quads && whole && program);

  struct Case {
    uint8_t cleared;
    StencilState state;
  };
  std::vector<Case> cases;
  const CompareOp compares[] = {CompareOp::Never,   CompareOp::Less,     CompareOp::Equal,        CompareOp::LessEqual,
                                CompareOp::Greater, CompareOp::NotEqual, CompareOp::GreaterEqual, CompareOp::Always};
  const StencilOp ops[] = {StencilOp::Keep,           StencilOp::Zero,           StencilOp::Replace,
                           StencilOp::IncrementClamp, StencilOp::DecrementClamp, StencilOp::Invert,
                           StencilOp::IncrementWrap,  StencilOp::DecrementWrap};
  for (CompareOp compare : compares)
    for (uint8_t reference : {uint8_t(0x10), uint8_t(0x3C), uint8_t(0xF0)})
      cases.push_back({0x3C,
                       {true,
                        reference,
                        0xFF,
                        0xFF,
                        {compare, StencilOp::Replace, StencilOp::Invert, StencilOp::IncrementWrap},
                        {compare, StencilOp::DecrementClamp, StencilOp::Zero, StencilOp::Keep}}});
  for (StencilOp op : ops)
    for (uint8_t cleared : {uint8_t(0x00), uint8_t(0xFF), uint8_t(0x3C)}) {
      cases.push_back({cleared,
                       {true,
                        0x81,
                        0xFF,
                        0xFF,
                        {CompareOp::Always, op, StencilOp::Keep, op},
                        {CompareOp::Never, StencilOp::Keep, op, StencilOp::Keep}}});
      cases.push_back({cleared,
                       {true,
                        0x81,
                        0xFF,
                        0xFF,
                        {CompareOp::Never, StencilOp::Keep, op, StencilOp::Keep},
                        {CompareOp::Always, op, StencilOp::Keep, op}}});
    }
  // The read mask decides the test on its bits alone; the write mask keeps the others.
  cases.push_back({0x3C,
                   {true,
                    0xAC,
                    0x0F,
                    0xF0,
                    {CompareOp::Equal, StencilOp::Invert, StencilOp::Zero, StencilOp::Invert},
                    {CompareOp::NotEqual, StencilOp::Invert, StencilOp::Replace, StencilOp::Invert}}});
  cases.push_back({0x3C,
                   {true,
                    0x0C,
                    0x0F,
                    0x0F,
                    {CompareOp::Less, StencilOp::Replace, StencilOp::IncrementClamp, StencilOp::Zero},
                    {CompareOp::Equal, StencilOp::Replace, StencilOp::DecrementWrap, StencilOp::Zero}}});

  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    RenderPass pass;
    pass.target = *target;
    pass.clear_stencil = c.cleared;
    pass.draws.push_back(draw(*program, *near, paint({1, 1, 1, 1})));
    pass.draws.back().state.color_write = 0;
    pass.draws.push_back(draw(*program, *quads, paint({1, 1, 1, 1})));
    pass.draws.back().state.color_write = 0;
    pass.draws.back().state.stencil = c.state;
    for (int bit = 0; bit < 8; ++bit) {
      pass.draws.push_back(draw(*program, *whole, paint({float(1 << bit) / 256.0f, 0, 0, 0})));
      DrawState& probe = pass.draws.back().state;
      probe.depth_compare = CompareOp::Always;
      probe.depth_write = false;
      probe.blend = {true, BlendFactor::One, BlendFactor::One, BlendFactor::One, BlendFactor::One};
      probe.stencil = {true, uint8_t(1 << bit), uint8_t(1 << bit), 0, {CompareOp::Equal}, {CompareOp::Equal}};
    }
    auto rendered = backend().render(pass);
    ASSERT_TRUE(rendered) << rendered.error().to_string();
    auto image = backend().read_color(*target);
    ASSERT_TRUE(image);
    for (uint32_t x : {0u, 3u})
      for (uint32_t y : {0u, 1u}) {
        const StencilFaceState& face = x < 2 ? c.state.back : c.state.front;
        const uint8_t expected = stencil_written(c.state, face, c.cleared, /*depth_passed=*/y == 1);
        EXPECT_EQ(std::lround(image->at(x, y).r * 256.0f), long(expected))
            << "case " << i << ", " << (x < 2 ? "back" : "front") << " face, depth " << (y == 1 ? "passed" : "failed");
      }
  }
}

// As depth is only where a target has depth, so is the stencil test: into a target without
// stencil a draw with a stencil test that never passes draws as if there were none.
TEST_P(BackendContractTest, AStencilTestWithoutAStencilBufferIsNotMade) {
  auto target = backend().create_target({2, 2, true});
  auto program = fullscreen_program("paint", kPaintFragment, layout({{"Paint", 0, 16}}, {}));
  ASSERT_TRUE(target && program);
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program, {}, paint({0, 1, 0, 1})));
  pass.draws.back().state.stencil = {true, 0, 0xFF, 0xFF, {CompareOp::Never}, {CompareOp::Never}};
  ASSERT_TRUE(backend().render(pass));
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(1, 1), {0, 1, 0, 1}, "drawn");
  auto refused = backend().create_target({2, 2, false, false, /*stencil=*/true});
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("needs a depth buffer"), std::string::npos) << refused.error().message;
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
  expect_error(
      backend().render(
          {*target, glm::vec4(0.0f), 1.0f, {draw(*copy, {}, {}, {{"source", TextureSource::texture(*texture)}})}}),
      "missing texture");
  ASSERT_TRUE(backend().destroy(*sampled));
  expect_error(
      backend().render(
          {*target, glm::vec4(0.0f), 1.0f, {draw(*copy, {}, {}, {{"source", TextureSource::color_of(*sampled)}})}}),
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
    RenderPass pass{*target,
                    glm::vec4(0.0f),
                    1.0f,
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
  ASSERT_TRUE(
      backend().render({*second,
                        glm::vec4(0.0f),
                        1.0f,
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
