// Smoke tests of the OpenGL lane: creation, orientation, bindings, errors and diagnostics.
#include "harness/osmesa_backend.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glsl/flavour.h"

namespace xshade::harness {
namespace {

// One backend for the suite: an llvmpipe context costs tens of milliseconds.
class OsmesaBackendTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto created = create_osmesa_backend();
    if (created)
      backend_ = std::move(*created);
    else
      error_ = created.error().to_string();
  }
  static void TearDownTestSuite() { backend_.reset(); }

  void SetUp() override {
    ASSERT_NE(backend_, nullptr) << error_;
    backend_->take_driver_messages();
  }
  void TearDown() override {
    if (backend_) {
      EXPECT_EQ(backend_->take_driver_messages(), std::vector<std::string>{});
    }
  }

  static Backend& backend() { return *backend_; }

  static ShaderStageSource stage(std::string glsl, std::string name) {
    ShaderStageSource source;
    source.glsl = std::move(glsl);
    source.name = std::move(name);
    return source;
  }

  static Result<ProgramHandle> fullscreen_program(const std::string& name,
                                                  const std::string& fragment,
                                                  ProgramLayout layout = {}) {
    ProgramDesc desc;
    desc.name = name;
    desc.vertex = stage(glsl::fullscreen_vertex_shader(glsl::Flavour::Gl), "fullscreen.vert");
    desc.fragment = stage(fragment, name + ".frag");
    desc.layout = std::move(layout);
    desc.fullscreen = true;
    return backend().create_program(desc);
  }

  static Result<ProgramHandle> mesh_program(const std::string& name, const std::string& fragment) {
    ProgramDesc desc;
    desc.name = name;
    desc.vertex = stage(
        "#version 450 core\n"
        "layout(location = 0) in vec3 position;\n"
        "layout(location = 3) in vec2 uv;\n"
        "layout(location = 0) out vec2 v_uv;\n"
        "void main() { v_uv = uv; gl_Position = vec4(position, 1.0); }\n",
        name + ".vert");
    desc.fragment = stage(fragment, name + ".frag");
    return backend().create_program(desc);
  }

  static inline std::unique_ptr<Backend> backend_;
  static inline std::string error_;
};

const char* const kUvFragment =
    "#version 450 core\n"
    "layout(location = 0) in vec2 uv;\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(uv, 0.0, 1.0); }\n";

const char* const kRedFragment =
    "#version 450 core\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(1.0, 0.0, 0.0, 1.0); }\n";

template <class T>
std::vector<std::byte> bytes_of(const T& value) {
  std::vector<std::byte> bytes(sizeof(T));
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

DrawItem draw(ProgramHandle program, MeshHandle mesh = {},
              std::vector<UniformBinding> uniforms = {},
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

void expect_near(glm::vec4 actual, glm::vec4 expected, const std::string& what) {
  for (int c = 0; c < 4; ++c)
    EXPECT_NEAR(actual[c], expected[c], 1e-5f) << what << ", channel " << c;
}

TEST_F(OsmesaBackendTest, ReportsLlvmpipeAndOpenGl45) {
  const DriverInfo& info = backend().driver_info();
  EXPECT_EQ(info.api, "OpenGL 4.5 core (OSMesa)");
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
  EXPECT_TRUE(info.api_version.starts_with("4.5")) << info.api_version;
  EXPECT_TRUE(info.driver_version.starts_with("Mesa ")) << info.driver_version;
  EXPECT_NE(info.api_version.find(info.driver_version), std::string::npos);
  EXPECT_FALSE(info.llvm_version.empty()) << info.renderer;
  EXPECT_NE(info.renderer.find("LLVM " + info.llvm_version), std::string::npos);
}

TEST_F(OsmesaBackendTest, ClearGivesTheClearColourUnclamped) {
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

TEST_F(OsmesaBackendTest, FullscreenUvIsZeroAtTheTopLeftPixel) {
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
      expect_near(image->at(x, y),
                  {(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h), 0.0f, 1.0f},
                  "pixel " + std::to_string(x) + "," + std::to_string(y));
}

TEST_F(OsmesaBackendTest, MeshTriangleInUpperClipHalfLandsInTheTopRows) {
  auto target = backend().create_target({4, 4, true});
  ASSERT_TRUE(target);
  // Covers clip y in [0, 1] across the whole width.
  auto mesh = backend().upload_mesh(
      {{vertex_at(-1, 0, 0.5f), vertex_at(3, 0, 0.5f), vertex_at(-1, 4, 0.5f)}, {0, 1, 2}});
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

TEST_F(OsmesaBackendTest, DepthIsZeroToOneLessTestedAndSampleable) {
  auto target = backend().create_target({4, 4, true});
  auto readback = backend().create_target({4, 4, false});
  ASSERT_TRUE(target && readback);
  // Near: the top half at z = 0.25. Far: the whole target at z = 0.75, drawn second.
  auto near = backend().upload_mesh(
      {{vertex_at(-1, 0, 0.25f), vertex_at(3, 0, 0.25f), vertex_at(-1, 4, 0.25f)}, {0, 1, 2}});
  auto far = backend().upload_mesh(
      {{vertex_at(-1, -1, 0.75f), vertex_at(3, -1, 0.75f), vertex_at(-1, 3, 0.75f)}, {0, 1, 2}});
  ASSERT_TRUE(near && far);
  auto red = mesh_program("red", kRedFragment);
  auto green = mesh_program("green",
                            "#version 450 core\n"
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

  // The depth of clip z = 0.25 (w = 1) is 0.25 with GL_ZERO_TO_ONE, and reads as .r.
  auto copy = fullscreen_program("depth_copy",
                                 "#version 450 core\n"
                                 "layout(binding = 1) uniform sampler2D depth_map;\n"
                                 "layout(location = 0) in vec2 uv;\n"
                                 "layout(location = 0) out vec4 color;\n"
                                 "void main() { color = texture(depth_map, uv); }\n",
                                 layout({}, {texture_slot("depth_map", 1)}));
  ASSERT_TRUE(copy) << copy.error().to_string();
  RenderPass second;
  second.target = *readback;
  second.draws.push_back(draw(
      *copy, {}, {}, {{"depth_map", TextureSource::depth_of(*target, {Filter::Nearest, {}})}}));
  auto rendered = backend().render(second);
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto depth = backend().read_color(*readback);
  ASSERT_TRUE(depth);
  EXPECT_NEAR(depth->at(2, 0).r, 0.25f, 1e-6f);
  EXPECT_NEAR(depth->at(2, 3).r, 0.75f, 1e-6f);
}

TEST_F(OsmesaBackendTest, TextureRowZeroIsTheTopAndUniformBlocksBindByName) {
  // Row 0 red, row 1 green; a uniform block scales the result.
  std::vector<float> texels = {1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  TextureData data{TextureFormat::Rgba32Float, 2, 2, {}};
  data.levels.emplace_back(texels.size() * sizeof(float));
  std::memcpy(data.levels[0].data(), texels.data(), data.levels[0].size());
  auto texture = backend().upload_texture(data);
  ASSERT_TRUE(texture) << texture.error().to_string();
  auto target = backend().create_target({4, 4, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program(
      "textured",
      "#version 450 core\n"
      "layout(std140, binding = 2) uniform Params { vec4 scale; };\n"
      "layout(binding = 3) uniform sampler2D image;\n"
      "layout(location = 0) in vec2 uv;\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() { color = texture(image, uv) * scale; }\n",
      layout({{"Params", 2, 16}}, {texture_slot("image", 3)}));
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(
      draw(*program, {}, {{"Params", bytes_of(glm::vec4(2.0f, 3.0f, 1.0f, 1.0f))}},
           {{"image", TextureSource::texture(*texture, {Filter::Nearest, {}})}}));
  auto rendered = backend().render(pass);
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  expect_near(image->at(0, 0), {2, 0, 0, 1}, "top row samples texture row 0");
  expect_near(image->at(3, 3), {0, 3, 0, 1}, "bottom row samples texture row 1");
}

TEST_F(OsmesaBackendTest, SpecialFloatValuesReachReadBack) {
  auto target = backend().create_target({1, 1, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program(
      "special",
      "#version 450 core\n"
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

TEST_F(OsmesaBackendTest, ADrawProducesNoDriverMessages) {
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

TEST_F(OsmesaBackendTest, BindingMistakesFailWithClearMessages) {
  auto target = backend().create_target({2, 2, false});
  auto other = backend().create_target({2, 2, false});
  auto program = fullscreen_program(
      "tinted",
      "#version 450 core\n"
      "layout(std140, binding = 0) uniform Tint { vec4 tint; };\n"
      "layout(binding = 0) uniform sampler2D source;\n"
      "layout(location = 0) in vec2 uv;\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() { color = texture(source, uv) * tint; }\n",
      layout({{"Tint", 0, 16}}, {texture_slot("source", 0)}));
  ASSERT_TRUE(target && other && program) << program.error().to_string();
  const auto tint = bytes_of(glm::vec4(1.0f));
  const TextureBinding source{"source", TextureSource::color_of(*other)};

  auto render_with = [&](DrawItem item) {
    RenderPass pass;
    pass.target = *target;
    pass.draws.push_back(std::move(item));
    return backend().render(pass);
  };
  auto missing_name = render_with(draw(*program, {}, {{"Nope", tint}, {"Tint", tint}}, {source}));
  ASSERT_FALSE(missing_name);
  EXPECT_NE(missing_name.error().message.find("'Nope'"), std::string::npos)
      << missing_name.error().message;

  auto unbound = render_with(draw(*program, {}, {}, {source}));
  ASSERT_FALSE(unbound);
  EXPECT_NE(unbound.error().message.find("'Tint'"), std::string::npos) << unbound.error().message;
  EXPECT_NE(unbound.error().message.find("not bound"), std::string::npos);

  auto wrong_size = render_with(draw(*program, {}, {{"Tint", bytes_of(1.0f)}}, {source}));
  ASSERT_FALSE(wrong_size);
  EXPECT_NE(wrong_size.error().message.find("16 bytes"), std::string::npos)
      << wrong_size.error().message;

  auto no_texture = render_with(draw(*program, {}, {{"Tint", tint}}, {}));
  ASSERT_FALSE(no_texture);
  EXPECT_NE(no_texture.error().message.find("'source'"), std::string::npos);

  auto own = render_with(
      draw(*program, {}, {{"Tint", tint}}, {{"source", TextureSource::color_of(*target)}}));
  ASSERT_FALSE(own);
  EXPECT_NE(own.error().message.find("own target"), std::string::npos) << own.error().message;

  auto good = render_with(draw(*program, {}, {{"Tint", tint}}, {source}));
  EXPECT_TRUE(good) << good.error().to_string();
}

TEST_F(OsmesaBackendTest, BrokenGlslGivesDiagnosticsWithLineNumbers) {
  auto program = fullscreen_program("broken",
                                    "#version 450 core\n"
                                    "layout(location = 0) in vec2 uv;\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { color = vec4(undeclared_thing, 1.0); }\n");
  ASSERT_FALSE(program);
  const Error& error = program.error();
  EXPECT_NE(error.message.find("'broken'"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("fragment"), std::string::npos) << error.message;
  ASSERT_FALSE(error.diagnostics.empty());
  bool found = false;
  for (const Diagnostic& diagnostic : error.diagnostics)
    if (diagnostic.severity == Severity::Error && diagnostic.where.file == "broken.frag" &&
        diagnostic.where.line == 4 &&
        diagnostic.message.find("undeclared_thing") != std::string::npos)
      found = true;
  EXPECT_TRUE(found) << error.to_string();
  EXPECT_EQ(error.where.line, 4u);
}

TEST_F(OsmesaBackendTest, LinkErrorsAreReported) {
  ProgramDesc desc;
  desc.name = "mismatch";
  desc.vertex = stage(glsl::fullscreen_vertex_shader(glsl::Flavour::Gl), "fullscreen.vert");
  desc.fragment = stage(
      "#version 450 core\n"
      "in vec3 not_written;\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() { color = vec4(not_written, 1.0); }\n",
      "mismatch.frag");
  desc.fullscreen = true;
  auto program = backend().create_program(desc);
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("'mismatch'"), std::string::npos);
  EXPECT_FALSE(program.error().diagnostics.empty()) << program.error().to_string();
}

TEST_F(OsmesaBackendTest, ResourcesMissingFromTheLayoutAreRejected) {
  auto program = fullscreen_program("unlisted",
                                    "#version 450 core\n"
                                    "layout(std140, binding = 0) uniform Hidden { vec4 value; };\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { color = value; }\n");
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("'Hidden'"), std::string::npos)
      << program.error().message;
}

TEST_F(OsmesaBackendTest, CompileWarningsOfAGoodProgramAreDriverMessages) {
  // Mesa reports compiler warnings through KHR_debug (at high severity); they are the driver's
  // complaints about a program, so they stay in the list.
  auto program = fullscreen_program("warns",
                                    "#version 450 core\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { float x; color = vec4(x); }\n");
  ASSERT_TRUE(program) << program.error().to_string();
  auto messages = backend().take_driver_messages();
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("'warns'"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("uninitialized"), std::string::npos) << messages[0];
}

TEST_F(OsmesaBackendTest, MipLevelsAndSrgbDecodeAreSampled) {
  // Level 0 (2x2) is sRGB 188, level 1 (1x1) is sRGB 255; sRGB 188 decodes to about 0.5029.
  TextureData data{TextureFormat::Rgba8Srgb, 2, 2, {}};
  data.levels.emplace_back(16, std::byte{188});
  data.levels.emplace_back(4, std::byte{255});
  auto texture = backend().upload_texture(data);
  ASSERT_TRUE(texture) << texture.error().to_string();
  auto target = backend().create_target({2, 1, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program(
      "lod",
      "#version 450 core\n"
      "uniform sampler2D image;\n"  // no layout(binding): the unit comes from the layout
      "layout(location = 0) in vec2 uv;\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() { color = textureLod(image, uv, uv.x < 0.5 ? 0.0 : 1.0); }\n",
      layout({}, {texture_slot("image", 5)}));
  ASSERT_TRUE(program) << program.error().to_string();
  RenderPass pass;
  pass.target = *target;
  pass.draws.push_back(draw(*program, {}, {}, {{"image", TextureSource::texture(*texture)}}));
  auto rendered = backend().render(pass);
  ASSERT_TRUE(rendered) << rendered.error().to_string();
  auto image = backend().read_color(*target);
  ASSERT_TRUE(image);
  EXPECT_NEAR(image->at(0, 0).r, 0.5029f, 2e-3f);
  EXPECT_NEAR(image->at(0, 0).a, 188.0f / 255.0f, 1e-6f);  // alpha is stored linear
  EXPECT_NEAR(image->at(1, 0).g, 1.0f, 1e-6f);
}

TEST(OsmesaBackendCreation, AMissingLibraryNamesTheDebianPackage) {
  std::optional<std::string> saved;
  if (const char* value = std::getenv("XSHADE_OSMESA_LIBRARY")) saved = value;
  unsetenv("XSHADE_OSMESA_LIBRARY");
  auto backend = create_osmesa_backend(OsmesaOptions{"libdoesnotexist.so"});
  if (saved) setenv("XSHADE_OSMESA_LIBRARY", saved->c_str(), 1);
  ASSERT_FALSE(backend);
  EXPECT_NE(backend.error().message.find("libosmesa6"), std::string::npos)
      << backend.error().message;
  EXPECT_NE(backend.error().message.find("libdoesnotexist.so"), std::string::npos);
}

TEST(OsmesaBackendCreation, TheEnvironmentOverridesTheLibrary) {
  std::optional<std::string> saved;
  if (const char* value = std::getenv("XSHADE_OSMESA_LIBRARY")) saved = value;
  setenv("XSHADE_OSMESA_LIBRARY", "libalsodoesnotexist.so", 1);
  auto backend = create_osmesa_backend();
  if (saved)
    setenv("XSHADE_OSMESA_LIBRARY", saved->c_str(), 1);
  else
    unsetenv("XSHADE_OSMESA_LIBRARY");
  ASSERT_FALSE(backend);
  EXPECT_NE(backend.error().message.find("libalsodoesnotexist.so"), std::string::npos)
      << backend.error().message;
}

TEST(OsmesaBackendCreation, TwoBackendsLiveSideBySide) {
  auto first = create_osmesa_backend();
  ASSERT_TRUE(first) << first.error().to_string();
  auto second = create_osmesa_backend();
  ASSERT_TRUE(second) << second.error().to_string();
  auto target_a = (*first)->create_target({2, 2, true});
  auto target_b = (*second)->create_target({2, 2, true});
  ASSERT_TRUE(target_a && target_b);
  RenderPass pass_a{*target_a, {1, 2, 3, 4}, 1.0f, {}};
  RenderPass pass_b{*target_b, {5, 6, 7, 8}, 1.0f, {}};
  ASSERT_TRUE((*first)->render(pass_a));
  ASSERT_TRUE((*second)->render(pass_b));
  auto image_a = (*first)->read_color(*target_a);
  second->reset();  // destroying the current context must leave the first one usable
  auto image_b = (*first)->read_color(*target_a);
  ASSERT_TRUE(image_a && image_b);
  expect_near(image_a->at(1, 1), {1, 2, 3, 4}, "first backend");
  expect_near(image_b->at(1, 1), {1, 2, 3, 4}, "first backend after the second died");
  EXPECT_EQ((*first)->take_driver_messages(), std::vector<std::string>{});
}

}  // namespace
}  // namespace xshade::harness
