// What only the OpenGL lane does, on both routes to its context (OSMesa and EGL surfaceless):
// the driver it reports, GLSL compile and link logs, the layout against the linked program,
// KHR_debug messages, texture units from the layout; choosing the route; and backends of both
// routes taking turns in one process. The Backend contract itself is tests/backend_contract/.
#include "harness/gl/gl_backend.h"
#include "harness/backend/shared_backend_test.h"

#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <GL/glcorearb.h>
#include <gtest/gtest.h>

#include "glsl/flavour.h"

namespace xshade::harness {
namespace {

const char* api_of(GlPlatform platform) {
  return platform == GlPlatform::Egl ? "OpenGL 4.5 core (EGL surfaceless)" : "OpenGL 4.5 core (OSMesa)";
}

std::string platform_test_name(const ::testing::TestParamInfo<GlPlatform>& info) {
  return std::string(gl_platform_name(info.param));
}

// One backend per route for the suite (SharedBackendTest).
Result<std::unique_ptr<Backend>> gl_backend_on(GlPlatform platform) {
  return create_gl_backend({.platform = platform});
}

class GlBackendTest : public SharedBackendTest<GlPlatform, &gl_backend_on> {
 protected:
  static ShaderStageSource stage(std::string glsl, std::string name) {
    ShaderStageSource source;
    source.glsl = std::move(glsl);
    source.name = std::move(name);
    return source;
  }

  Result<ProgramHandle> fullscreen_program(const std::string& name, const std::string& fragment,
                                           ProgramLayout layout = {}) {
    ProgramDesc desc;
    desc.name = name;
    desc.vertex = stage(glsl::fullscreen_vertex_shader(glsl::Flavour::Gl), "fullscreen.vert");
    desc.fragment = stage(fragment, name + ".frag");
    desc.layout = std::move(layout);
    desc.fullscreen = true;
    return backend().create_program(desc);
  }
};

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

void expect_near(glm::vec4 actual, glm::vec4 expected, const std::string& what) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(actual[c], expected[c], 1e-5f) << what << ", channel " << c;
}

TEST_P(GlBackendTest, ReportsLlvmpipeAndOpenGl45) {
  const DriverInfo& info = backend().driver_info();
  EXPECT_EQ(info.api, api_of(GetParam()));
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
  EXPECT_TRUE(info.api_version.starts_with("4.5")) << info.api_version;
  EXPECT_TRUE(info.driver_version.starts_with("Mesa ")) << info.driver_version;
  EXPECT_NE(info.api_version.find(info.driver_version), std::string::npos);
  EXPECT_FALSE(info.llvm_version.empty()) << info.renderer;
  EXPECT_NE(info.renderer.find("LLVM " + info.llvm_version), std::string::npos);
}

TEST_P(GlBackendTest, BrokenGlslGivesDiagnosticsWithLineNumbers) {
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
        diagnostic.where.line == 4 && diagnostic.message.find("undeclared_thing") != std::string::npos)
      found = true;
  EXPECT_TRUE(found) << error.to_string();
  EXPECT_EQ(error.where.line, 4u);
}

TEST_P(GlBackendTest, LinkErrorsAreReported) {
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

TEST_P(GlBackendTest, ResourcesMissingFromTheLayoutAreRejected) {
  auto program = fullscreen_program("unlisted",
                                    "#version 450 core\n"
                                    "layout(std140, binding = 0) uniform Hidden { vec4 value; };\n"
                                    "layout(location = 0) out vec4 color;\n"
                                    "void main() { color = value; }\n");
  ASSERT_FALSE(program);
  EXPECT_NE(program.error().message.find("'Hidden'"), std::string::npos) << program.error().message;
}

TEST_P(GlBackendTest, CompileWarningsOfAGoodProgramAreDriverMessages) {
  // Mesa reports compiler warnings through KHR_debug (at high severity); they are the driver's
  // complaints about a program, so they stay in the list. Mesa gives them only when it compiles:
  // the source is made new for each process (a comment with its id and the time), so that no
  // drivers' cache holds the program (the tests share one; xshade's own keeps the messages beside
  // it, which the run tests check).
  const std::string unique = "// " + std::to_string(::getpid()) + " " +
                             std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()) + "\n";
  auto program = fullscreen_program("warns", "#version 450 core\n" + unique +
                                                 "layout(location = 0) out vec4 color;\n"
                                                 "void main() { float x; color = vec4(x); }\n");
  ASSERT_TRUE(program) << program.error().to_string();
  auto messages = backend().take_driver_messages();
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("'warns'"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("uninitialized"), std::string::npos) << messages[0];
}

TEST_P(GlBackendTest, MipLevelsAndSrgbDecodeAreSampled) {
  // Level 0 (2x2) is sRGB 188, level 1 (1x1) is sRGB 255; sRGB 188 decodes to about 0.5029.
  TextureData data{TextureFormat::Rgba8Srgb, 2, 2, {}};
  data.levels.emplace_back(16, std::byte{188});
  data.levels.emplace_back(4, std::byte{255});
  auto texture = backend().upload_texture(data);
  ASSERT_TRUE(texture) << texture.error().to_string();
  auto target = backend().create_target({2, 1, false});
  ASSERT_TRUE(target);
  auto program = fullscreen_program("lod",
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

INSTANTIATE_TEST_SUITE_P(Routes, GlBackendTest, ::testing::Values(GlPlatform::Osmesa, GlPlatform::Egl),
                         platform_test_name);

// ---- Choosing the route -------------------------------------------------------------------------

// Sets (or unsets, with null) an environment variable for one scope, then puts it back.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      setenv(name, value, 1);
    else
      unsetenv(name);
  }
  ~ScopedEnvironment() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

void expect_mentions(const std::string& message, const std::vector<std::string>& words) {
  for (const std::string& word : words) EXPECT_NE(message.find(word), std::string::npos) << word << " in: " << message;
}

TEST(GlRoute, PlatformNamesParseBack) {
  for (GlPlatform platform : {GlPlatform::Auto, GlPlatform::Osmesa, GlPlatform::Egl})
    EXPECT_EQ(parse_gl_platform(gl_platform_name(platform)), platform) << gl_platform_name(platform);
  EXPECT_EQ(gl_platform_name(GlPlatform::Egl), "egl");
  EXPECT_EQ(parse_gl_platform("glx"), std::nullopt);
  EXPECT_EQ(parse_gl_platform("EGL"), std::nullopt);
}

TEST(GlRoute, AMissingOsmesaLibraryNamesTheDebianPackage) {
  auto backend = create_gl_backend({.platform = GlPlatform::Osmesa, .osmesa_library = "libdoesnotexist.so"});
  ASSERT_FALSE(backend);
  expect_mentions(backend.error().message, {"libosmesa6", "libdoesnotexist.so"});
}

TEST(GlRoute, AMissingEglLibraryNamesTheDebianPackageAndDoesNotFallBack) {
  auto backend = create_gl_backend({.platform = GlPlatform::Egl, .egl_library = "libdoesnotexist.so"});
  ASSERT_FALSE(backend) << (*backend)->driver_info().api;
  expect_mentions(backend.error().message, {"cannot open EGL library 'libdoesnotexist.so'", "libegl1"});
}

TEST(GlRoute, ALibraryWithoutTheRoutesEntryPointsNamesTheDebianPackage) {
  // libm opens, but it is neither OSMesa nor EGL.
  auto osmesa = create_gl_backend({.platform = GlPlatform::Osmesa, .osmesa_library = "libm.so.6"});
  ASSERT_FALSE(osmesa);
  expect_mentions(osmesa.error().message, {"libm.so.6", "OSMesaCreateContextAttribs", "libosmesa6"});
  auto egl = create_gl_backend({.platform = GlPlatform::Egl, .egl_library = "libm.so.6"});
  ASSERT_FALSE(egl);
  expect_mentions(egl.error().message, {"libm.so.6", "eglGetProcAddress", "libegl1"});
}

TEST(GlRoute, TheEnvironmentNamesTheLibraryWhenTheOptionsDoNot) {
  const ScopedEnvironment osmesa_library("XSHADE_OSMESA_LIBRARY", "libalsodoesnotexist.so");
  const ScopedEnvironment egl_library("XSHADE_EGL_LIBRARY", "libnorthisone.so");
  auto osmesa = create_gl_backend({.platform = GlPlatform::Osmesa});
  ASSERT_FALSE(osmesa);
  expect_mentions(osmesa.error().message, {"libalsodoesnotexist.so"});
  auto egl = create_gl_backend({.platform = GlPlatform::Egl});
  ASSERT_FALSE(egl);
  expect_mentions(egl.error().message, {"libnorthisone.so"});
}

TEST(GlRoute, AutoTakesOsmesaWhenItOpens) {
  const ScopedEnvironment osmesa_library("XSHADE_OSMESA_LIBRARY", nullptr);
  auto backend = create_gl_backend({.platform = GlPlatform::Auto});
  ASSERT_TRUE(backend) << backend.error().to_string();
  EXPECT_EQ((*backend)->driver_info().api, "OpenGL 4.5 core (OSMesa)");
}

TEST(GlRoute, AutoFallsBackToEglWhenOsmesaDoesNotOpen) {
  auto backend = create_gl_backend({.platform = GlPlatform::Auto, .osmesa_library = "libdoesnotexist.so"});
  ASSERT_TRUE(backend) << backend.error().to_string();
  const DriverInfo& info = (*backend)->driver_info();
  EXPECT_EQ(info.api, "OpenGL 4.5 core (EGL surfaceless)");
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
}

TEST(GlRoute, AutoReportsAnOsmesaThatOpensButFailsInsteadOfFallingBack) {
  auto backend = create_gl_backend({.platform = GlPlatform::Auto, .osmesa_library = "libm.so.6"});
  ASSERT_FALSE(backend) << (*backend)->driver_info().api;
  expect_mentions(backend.error().message, {"libm.so.6", "OSMesaCreateContextAttribs"});
  EXPECT_EQ(backend.error().message.find("EGL"), std::string::npos) << backend.error().message;
}

TEST(GlRoute, AutoWithNeitherRouteSaysWhatWasTriedAndWhatToInstall) {
  auto backend = create_gl_backend(
      {.platform = GlPlatform::Auto, .osmesa_library = "libnoosmesa.so", .egl_library = "libnoegl.so"});
  ASSERT_FALSE(backend);
  expect_mentions(backend.error().message, {"OSMesa", "libnoosmesa.so", "EGL surfaceless", "libnoegl.so", "libosmesa6",
                                            "libegl1", "libegl-mesa0", "libgl1-mesa-dri", "--gl-platform"});
}

TEST(GlRoute, BothRoutesReachTheSameDriver) {
  auto osmesa = create_gl_backend({.platform = GlPlatform::Osmesa});
  ASSERT_TRUE(osmesa) << osmesa.error().to_string();
  auto egl = create_gl_backend({.platform = GlPlatform::Egl});
  ASSERT_TRUE(egl) << egl.error().to_string();
  const DriverInfo& a = (*osmesa)->driver_info();
  const DriverInfo& b = (*egl)->driver_info();
  EXPECT_NE(a.api, b.api);
  EXPECT_EQ(a.renderer, b.renderer);
  EXPECT_EQ(a.api_version, b.api_version);
  EXPECT_EQ(a.driver_version, b.driver_version);
  EXPECT_EQ(a.llvm_version, b.llvm_version);
}

// ---- Contexts of both routes in one process -----------------------------------------------------

// Mesa's dispatch points at one context per thread, whichever route made it current: the clear
// colour each context keeps tells which one GL calls reach.
TEST(GlContexts, MakeCurrentMovesTheDispatchAcrossRoutes) {
  auto osmesa = create_osmesa_context();
  ASSERT_TRUE(osmesa) << osmesa.error().to_string();
  auto egl = create_egl_context();
  ASSERT_TRUE(egl) << egl.error().to_string();
  GlContext& a = **osmesa;
  GlContext& b = **egl;
  EXPECT_TRUE(b.is_current());  // a new context is current
  EXPECT_FALSE(a.is_current());
  const auto clear_color = reinterpret_cast<PFNGLCLEARCOLORPROC>(a.proc_address("glClearColor"));
  const auto get_floats = reinterpret_cast<PFNGLGETFLOATVPROC>(a.proc_address("glGetFloatv"));
  ASSERT_TRUE(clear_color && get_floats);
  clear_color(0.0f, 2.0f, 0.0f, 0.0f);  // into b, the current one
  ASSERT_TRUE(a.make_current());
  clear_color(1.0f, 0.0f, 0.0f, 0.0f);
  const auto reached = [&]() {
    std::array<float, 4> value{};
    get_floats(GL_COLOR_CLEAR_VALUE, value.data());
    return value[0] == 1.0f ? "osmesa" : value[1] == 2.0f ? "egl" : "neither";
  };
  for (int round = 0; round < 3; ++round) {
    ASSERT_TRUE(b.make_current());
    EXPECT_TRUE(b.is_current());
    EXPECT_FALSE(a.is_current());
    EXPECT_STREQ(reached(), "egl") << "round " << round;
    ASSERT_TRUE(a.make_current());
    EXPECT_TRUE(a.is_current());
    EXPECT_FALSE(b.is_current());
    EXPECT_STREQ(reached(), "osmesa") << "round " << round;
  }
}

// A full-screen draw of a uniform colour into a backend's first target with its first program:
// the same names on every backend, so that a draw reaching the wrong context lands in that
// context's objects instead of failing.
struct Tinted {
  TargetHandle target;
  ProgramHandle program;
};

Result<Tinted> prepare_tinted(Backend& backend) {
  auto target = backend.create_target({3, 2, true});
  if (!target) return fail(target.error());
  ProgramDesc desc;
  desc.name = "tint";
  desc.vertex.glsl = glsl::fullscreen_vertex_shader(glsl::Flavour::Gl);
  desc.vertex.name = "fullscreen.vert";
  desc.fragment.glsl =
      "#version 450 core\n"
      "layout(std140, binding = 0) uniform Tint { vec4 tint; };\n"
      "layout(location = 0) out vec4 color;\n"
      "void main() { color = tint; }\n";
  desc.fragment.name = "tint.frag";
  desc.layout = layout({{"Tint", 0, 16}}, {});
  desc.fullscreen = true;
  auto program = backend.create_program(desc);
  if (!program) return fail(program.error());
  return Tinted{*target, *program};
}

Result<void> draw_tint(Backend& backend, const Tinted& tinted, glm::vec4 tint) {
  RenderPass pass;
  pass.target = tinted.target;
  pass.clear_color = {0.5f, 0.5f, 0.5f, 0.5f};
  pass.draws.push_back(draw(tinted.program, {}, {{"Tint", bytes_of(tint)}}));
  return backend.render(pass);
}

void expect_filled(Backend& backend, const Tinted& tinted, glm::vec4 tint, const std::string& what) {
  auto image = backend.read_color(tinted.target);
  ASSERT_TRUE(image) << what << ": " << image.error().to_string();
  for (uint32_t y = 0; y < image->height; ++y)
    for (uint32_t x = 0; x < image->width; ++x)
      expect_near(image->at(x, y), tint, what + ", pixel " + std::to_string(x) + "," + std::to_string(y));
}

TEST(GlContexts, DrawsOnAnOsmesaAndAnEglBackendTakingTurnsLandInTheirOwnTargets) {
  // Each backend makes its objects while its context is new, and so surely current: a later
  // switch that fails to move the dispatch sends one backend's calls to the other's objects.
  auto osmesa = create_gl_backend({.platform = GlPlatform::Osmesa});
  ASSERT_TRUE(osmesa) << osmesa.error().to_string();
  Backend& a = **osmesa;
  auto tinted_a = prepare_tinted(a);
  ASSERT_TRUE(tinted_a) << tinted_a.error().to_string();
  auto egl = create_gl_backend({.platform = GlPlatform::Egl});
  ASSERT_TRUE(egl) << egl.error().to_string();
  Backend& b = **egl;
  auto tinted_b = prepare_tinted(b);
  ASSERT_TRUE(tinted_b) << tinted_b.error().to_string();
  for (int round = 0; round < 4; ++round) {
    const std::string what = "round " + std::to_string(round);
    const glm::vec4 tint_a(float(round), 1.0f, 2.0f, 3.0f);
    const glm::vec4 tint_b(-float(round), 5.0f, 6.0f, 7.0f);
    // Even rounds draw on OSMesa first, odd rounds on EGL first.
    if (round % 2 == 0) {
      ASSERT_TRUE(draw_tint(a, *tinted_a, tint_a));
      ASSERT_TRUE(draw_tint(b, *tinted_b, tint_b));
    } else {
      ASSERT_TRUE(draw_tint(b, *tinted_b, tint_b));
      ASSERT_TRUE(draw_tint(a, *tinted_a, tint_a));
    }
    expect_filled(a, *tinted_a, tint_a, "OSMesa, " + what);
    expect_filled(b, *tinted_b, tint_b, "EGL, " + what);
    expect_filled(a, *tinted_a, tint_a, "OSMesa after EGL, " + what);
  }
  EXPECT_EQ(a.take_driver_messages(), std::vector<std::string>{});
  EXPECT_EQ(b.take_driver_messages(), std::vector<std::string>{});
}

class TwoGlBackends : public ::testing::TestWithParam<std::pair<GlPlatform, GlPlatform>> {};

std::string pair_test_name(const ::testing::TestParamInfo<std::pair<GlPlatform, GlPlatform>>& info) {
  return std::string(gl_platform_name(info.param.first)) + "_then_" + std::string(gl_platform_name(info.param.second));
}

TEST_P(TwoGlBackends, LiveSideBySide) {
  auto first = create_gl_backend({.platform = GetParam().first});
  ASSERT_TRUE(first) << first.error().to_string();
  auto second = create_gl_backend({.platform = GetParam().second});
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
  // And a new backend after the death, of the second's route, works beside the first.
  auto third = create_gl_backend({.platform = GetParam().second});
  ASSERT_TRUE(third) << third.error().to_string();
  auto target_c = (*third)->create_target({2, 2, false});
  ASSERT_TRUE(target_c);
  const RenderPass pass_c{*target_c, {9, 10, 11, 12}, 1.0f, {}};
  ASSERT_TRUE((*third)->render(pass_c));
  auto image_c = (*third)->read_color(*target_c);
  auto image_d = (*first)->read_color(*target_a);
  ASSERT_TRUE(image_c && image_d);
  expect_near(image_c->at(0, 1), {9, 10, 11, 12}, "third backend");
  expect_near(image_d->at(0, 1), {1, 2, 3, 4}, "first backend beside the third");
  EXPECT_EQ((*first)->take_driver_messages(), std::vector<std::string>{});
}

INSTANTIATE_TEST_SUITE_P(Routes, TwoGlBackends,
                         ::testing::Values(std::pair(GlPlatform::Osmesa, GlPlatform::Osmesa),
                                           std::pair(GlPlatform::Egl, GlPlatform::Egl),
                                           std::pair(GlPlatform::Osmesa, GlPlatform::Egl),
                                           std::pair(GlPlatform::Egl, GlPlatform::Osmesa)),
                         pair_test_name);

}  // namespace
}  // namespace xshade::harness
