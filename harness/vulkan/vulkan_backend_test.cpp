// What only the Vulkan lane does on lavapipe: the device it picks, SPIR-V validation and
// reflection against the layout, lavapipe's format limits, separate samplers, and a
// validation-clean frame. The Backend contract itself is tests/backend_contract/.
#include "harness/vulkan/vulkan_backend.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glsl/flavour.h"
#include "spirv/spirv_compiler.h"

namespace xshade::harness {
namespace {

std::vector<uint32_t> compile(const std::string& source, spirv::Stage stage, const char* name) {
  auto module = spirv::compile_vulkan_glsl(source, stage, name);
  EXPECT_TRUE(module) << (module ? "" : module.error().to_string());
  return module ? module->words : std::vector<uint32_t>{};
}

ShaderStageSource stage_source(const std::string& glsl, spirv::Stage stage, const char* name) {
  ShaderStageSource source;
  source.spirv = compile(glsl, stage, name);
  source.name = name;
  return source;
}

ProgramDesc fullscreen_program(const std::string& fragment_glsl, ProgramLayout layout = {}) {
  ProgramDesc desc;
  desc.name = "fullscreen test";
  desc.vertex =
      stage_source(glsl::fullscreen_vertex_shader(glsl::Flavour::Vk), spirv::Stage::Vertex, "fullscreen.vert");
  desc.fragment = stage_source(fragment_glsl, spirv::Stage::Fragment, "test.frag");
  desc.layout = std::move(layout);
  desc.fullscreen = true;
  return desc;
}

// A mesh program: position only, and a fragment colour from a uniform block.
constexpr const char* kMeshVertex = R"(#version 450
layout(location = 0) in vec3 position;
void main() { gl_Position = vec4(position, 1.0); }
)";
constexpr const char* kColorFragment = R"(#version 450
layout(set = 0, binding = 0) uniform Params { vec4 color; } params;
layout(location = 0) out vec4 frag;
void main() { frag = params.color; }
)";

ProgramDesc mesh_color_program() {
  ProgramDesc desc;
  desc.name = "mesh colour";
  desc.vertex = stage_source(kMeshVertex, spirv::Stage::Vertex, "mesh.vert");
  desc.fragment = stage_source(kColorFragment, spirv::Stage::Fragment, "color.frag");
  desc.layout.uniform_blocks.push_back({"Params", 0, 16});
  return desc;
}

UniformBinding color_uniform(glm::vec4 color) {
  UniformBinding binding{"Params", std::vector<std::byte>(sizeof(color))};
  std::memcpy(binding.bytes.data(), &color, sizeof(color));
  return binding;
}

void expect_near(glm::vec4 actual, glm::vec4 expected, const std::string& where) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-5f) << where << " channel " << i;
}

// One backend shared by the tests that do not need validation: creating a device takes time.
class VulkanBackendTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto created = create_vulkan_backend();
    ASSERT_TRUE(created) << created.error().to_string();
    backend_ = std::move(*created).release();
  }
  static void TearDownTestSuite() {
    delete backend_;
    backend_ = nullptr;
  }
  void SetUp() override { ASSERT_NE(backend_, nullptr); }

  static Backend* backend_;
};
Backend* VulkanBackendTest::backend_ = nullptr;

TEST_F(VulkanBackendTest, CreatesOnLlvmpipe) {
  const DriverInfo& info = backend_->driver_info();
  EXPECT_EQ(info.api, "Vulkan 1.3 (lavapipe)");
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
  EXPECT_EQ(info.api_version.rfind("1.3.", 0), 0u) << info.api_version;
  EXPECT_EQ(info.driver_version.rfind("Mesa ", 0), 0u) << info.driver_version;
  EXPECT_EQ(info.driver_version.find('('), std::string::npos) << info.driver_version;
  EXPECT_FALSE(info.llvm_version.empty()) << info.renderer;
  RecordProperty("renderer", info.renderer);
  RecordProperty("api_version", info.api_version);
  RecordProperty("driver_version", info.driver_version);
  RecordProperty("llvm_version", info.llvm_version);
}

TEST_F(VulkanBackendTest, InvalidSpirvFails) {
  ProgramDesc desc = mesh_color_program();
  desc.name = "broken";
  desc.vertex.spirv = {0x07230203u, 0x00010600u, 0u, 10u, 0u, 0xdeadbeefu, 0x12345678u};
  auto program = backend_->create_program(desc);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("broken"), std::string::npos) << program.error().message;
  EXPECT_NE(program.error().message.find("not valid SPIR-V"), std::string::npos) << program.error().message;

  desc = mesh_color_program();
  desc.fragment.entry_point = "missing";
  program = backend_->create_program(desc);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("'missing'"), std::string::npos) << program.error().message;
}

TEST_F(VulkanBackendTest, AResourceOfAnotherDescriptorTypeThanTheLayoutsFails) {
  // A texel buffer where the layout says storage buffer: the driver would be given a mismatched
  // descriptor, which lavapipe does not survive.
  ProgramDesc desc = fullscreen_program(R"(#version 450
layout(set = 0, binding = 3) uniform samplerBuffer values;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = texelFetch(values, int(uv.x * 4.0)); }
)");
  desc.layout.storage_buffers = {{"values", 3}};
  auto program = backend_->create_program(desc);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("reads binding 3 as a UniformTexelBuffer descriptor, but the program's layout "
                                         "gives it a StorageBuffer"),
            std::string::npos)
      << program.error().message;
}

TEST_F(VulkanBackendTest, ResourceMissingFromTheLayoutFails) {
  // The shader samples a separate texture (binding 1) and sampler (binding 2); a layout that
  // calls binding 1 a combined sampler leaves binding 2 without a descriptor.
  ProgramDesc desc = fullscreen_program(R"(#version 450
layout(set = 0, binding = 1) uniform texture2D values;
layout(set = 0, binding = 2) uniform sampler values_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = texture(sampler2D(values, values_sampler), uv); }
)");
  desc.layout.textures = {{"values", 1, std::nullopt}};
  auto program = backend_->create_program(desc);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("set 0 binding 2, which the program's layout does not list"),
            std::string::npos)
      << program.error().message;
  desc.layout.textures = {{"values", 1, 2u}};
  EXPECT_TRUE(backend_->create_program(desc));
}

// glslang keeps a declared resource the code never reads in the module (its HLSL front end does so
// for a vertex stage that declares the fragment stage's textures); it needs no descriptor.
TEST_F(VulkanBackendTest, AResourceDeclaredButNeverReadNeedsNoLayoutEntry) {
  ProgramDesc desc = fullscreen_program(R"(#version 450
layout(set = 0, binding = 5) uniform texture2D never_read;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = vec4(uv, 0.0, 1.0); }
)");
  const std::vector<uint32_t>& words = desc.fragment.spirv;
  bool declared = false;  // OpDecorate %never_read Binding 5
  for (size_t i = 5; i + 3 < words.size(); ++i)
    declared = declared || (words[i] == ((4u << 16) | 71u) && words[i + 2] == 33u && words[i + 3] == 5u);
  ASSERT_TRUE(declared) << "the module must declare the resource for this test to mean anything";
  EXPECT_TRUE(backend_->create_program(desc));
}

TEST_F(VulkanBackendTest, LinearFilteringOfFloatTargetsAndSrgbDecoding) {
  // Target A holds uv per texel: (0.25 | 0.75, 0.25 | 0.75), depth 0 (the triangle's z).
  auto uv_program = backend_->create_program(fullscreen_program(R"(#version 450
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = vec4(uv, 0.0, 1.0); }
)"));
  ProgramLayout layout;
  layout.textures = {{"color", 0, std::nullopt}, {"depth", 1, std::nullopt}, {"srgb", 2, 3u}};
  auto sample_program = backend_->create_program(fullscreen_program(R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D color;
layout(set = 0, binding = 1) uniform sampler2D depth;
layout(set = 0, binding = 2) uniform texture2D srgb;
layout(set = 0, binding = 3) uniform sampler srgb_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() {
  frag = vec4(texture(color, uv).rg, texture(depth, uv).r, texture(sampler2D(srgb, srgb_sampler), uv).r);
}
)",
                                                                    layout));
  ASSERT_TRUE(uv_program && sample_program);
  TextureData srgb{TextureFormat::Rgba8Srgb, 1, 1, {std::vector<std::byte>(4, std::byte{188})}};
  auto texture = backend_->upload_texture(srgb);
  ASSERT_TRUE(texture) << texture.error().to_string();
  auto a = backend_->create_target({2, 2, true});
  auto b = backend_->create_target({1, 1, false});
  ASSERT_TRUE(a && b);
  ASSERT_TRUE(backend_->render({*a, glm::vec4(0.0f), 1.0f, {DrawItem{*uv_program, {}, {}, {}, {}}}}));
  const SamplerDesc linear{Filter::Linear, AddressMode::ClampToEdge};
  const SamplerDesc nearest{Filter::Nearest, AddressMode::ClampToEdge};
  // lavapipe does not offer linear filtering of D32_SFLOAT: a clear error, not a validation error.
  DrawItem draw{*sample_program,
                {},
                {},
                {{"color", TextureSource::color_of(*a, linear)},
                 {"depth", TextureSource::depth_of(*a, linear)},
                 {"srgb", TextureSource::texture(*texture, linear)}},
                {}};
  auto rendered = backend_->render({*b, glm::vec4(0.0f), 1.0f, {draw}});
  ASSERT_FALSE(rendered);
  EXPECT_NE(rendered.error().message.find("cannot be filtered linearly"), std::string::npos)
      << rendered.error().message;
  draw.textures[1].source.sampler = nearest;
  rendered = backend_->render({*b, glm::vec4(0.0f), 1.0f, {draw}});
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto image = backend_->read_color(*b);
  ASSERT_TRUE(image);
  const glm::vec4 texel = image->at(0, 0);
  // The centre of a 2x2 float target averages all four texels; sRGB 188 decodes to ~0.5029.
  EXPECT_NEAR(texel.r, 0.5f, 1e-5f);
  EXPECT_NEAR(texel.g, 0.5f, 1e-5f);
  EXPECT_NEAR(texel.b, 0.0f, 1e-5f);
  EXPECT_NEAR(texel.a, 0.5029f, 2e-3f);
}

// A frame with a texture, separate and combined samplers, a uniform block, depth, and a second
// pass sampling the first pass's colour and depth must leave the validation layer silent.
TEST(LavapipeValidation, DrawLeavesNoDriverMessages) {
  ASSERT_TRUE(vulkan_validation_available()) << "install the Debian package vulkan-validationlayers";
  auto created = create_vulkan_backend({.validation = true});
  ASSERT_TRUE(created) << created.error().to_string();
  Backend& backend = **created;

  // 2x2 texture, row 0 red/green, row 1 blue/white, with a 1x1 mip.
  TextureData texture{TextureFormat::Rgba8Unorm, 2, 2, {}};
  const uint8_t texels[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  texture.levels.emplace_back(reinterpret_cast<const std::byte*>(texels),
                              reinterpret_cast<const std::byte*>(texels) + sizeof(texels));
  texture.levels.emplace_back(4, std::byte{128});
  auto tex = backend.upload_texture(texture);
  ASSERT_TRUE(tex) << tex.error().to_string();

  ProgramLayout first_layout;
  first_layout.uniform_blocks.push_back({"Params", 0, 16});
  first_layout.textures.push_back({"image", 1, 2u});
  auto first = backend.create_program(fullscreen_program(R"(#version 450
layout(set = 0, binding = 0) uniform Params { vec4 scale; } params;
layout(set = 0, binding = 1) uniform texture2D image;
layout(set = 0, binding = 2) uniform sampler image_sampler;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = texture(sampler2D(image, image_sampler), uv) * params.scale; }
)",
                                                         first_layout));
  ASSERT_TRUE(first) << first.error().to_string();
  ProgramDesc mesh_desc;
  mesh_desc.name = "mesh sampling";
  mesh_desc.vertex = stage_source(R"(#version 450
layout(location = 0) in vec3 position;
layout(location = 3) in vec2 uv_in;
layout(location = 0) out vec2 uv;
void main() { uv = uv_in; gl_Position = vec4(position, 1.0); }
)",
                                  spirv::Stage::Vertex, "uv.vert");
  mesh_desc.fragment = stage_source(R"(#version 450
layout(set = 0, binding = 3) uniform sampler2D color;
layout(set = 0, binding = 4) uniform sampler2D depth;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 frag;
void main() { frag = texture(color, uv) + vec4(0.0, 0.0, 0.0, texture(depth, uv).r); }
)",
                                    spirv::Stage::Fragment, "sample.frag");
  mesh_desc.layout.textures = {{"color", 3, std::nullopt}, {"depth", 4, std::nullopt}};
  auto second = backend.create_program(mesh_desc);
  ASSERT_TRUE(second) << second.error().to_string();

  MeshData quad;
  for (auto [x, y] : {std::pair{-1.0f, 1.0f}, {1.0f, 1.0f}, {-1.0f, -1.0f}, {1.0f, -1.0f}}) {
    Vertex v;
    v.position = {x, y, 0.25f};
    v.uv = {x * 0.5f + 0.5f, 0.5f - y * 0.5f};
    quad.vertices.push_back(v);
  }
  quad.indices = {0, 1, 2, 2, 1, 3};
  auto mesh = backend.upload_mesh(quad);
  ASSERT_TRUE(mesh) << mesh.error().to_string();

  auto a = backend.create_target({4, 4, true});
  auto b = backend.create_target({4, 4, true});
  ASSERT_TRUE(a && b);
  DrawItem draw_a{*first,
                  {},
                  {color_uniform({1, 1, 1, 1})},
                  {{"image", TextureSource::texture(*tex, {Filter::Nearest, AddressMode::ClampToEdge})}},
                  {}};
  ASSERT_TRUE(backend.render({*a, glm::vec4(0.0f), 0.5f, {draw_a}}));
  DrawItem draw_b{*second,
                  *mesh,
                  {},
                  {{"color", TextureSource::color_of(*a, {Filter::Linear, AddressMode::Repeat})},
                   {"depth", TextureSource::depth_of(*a, {Filter::Nearest, AddressMode::ClampToEdge})}},
                  {}};
  auto rendered = backend.render({*b, glm::vec4(0.0f), 1.0f, {draw_b}});
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto image = backend.read_color(*b);
  ASSERT_TRUE(image);
  // The texture's first row is at the top. Pass A's depth was cleared to 0.5, then the full-screen
  // triangle (z = 0) passed the depth test and wrote 0, so alpha is 1 + 0.
  expect_near(image->at(0, 0), {1, 0, 0, 1}, "top-left");
  expect_near(image->at(3, 0), {0, 1, 0, 1}, "top-right");
  expect_near(image->at(0, 3), {0, 0, 1, 1}, "bottom-left");
  expect_near(image->at(3, 3), {1, 1, 1, 1}, "bottom-right");

  const std::vector<std::string> messages = backend.take_driver_messages();
  EXPECT_TRUE(messages.empty()) << messages.size()
                                << " messages, first: " << (messages.empty() ? "" : messages.front());
}

// The messenger really collects: a fragment input no vertex output produces is reported once.
TEST(LavapipeValidation, ReportsInterfaceMismatch) {
  auto created = create_vulkan_backend({.validation = true});
  ASSERT_TRUE(created) << created.error().to_string();
  Backend& backend = **created;
  auto program = backend.create_program(fullscreen_program(R"(#version 450
layout(location = 1) in vec4 missing;
layout(location = 0) out vec4 frag;
void main() { frag = missing; }
)"));
  ASSERT_TRUE(program) << program.error().to_string();
  auto target = backend.create_target({2, 2, false});
  ASSERT_TRUE(target);
  DrawItem draw{*program, {}, {}, {}, {}};
  ASSERT_TRUE(backend.render({*target, glm::vec4(0.0f), 1.0f, {draw}}));
  const std::vector<std::string> messages = backend.take_driver_messages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("location 1"), std::string::npos) << messages.front();
  EXPECT_TRUE(backend.take_driver_messages().empty());
}

}  // namespace
}  // namespace xshade::harness
