// Why this file is long: one case per table and key of the scene format (docs/scenes.md), each
// with the mistakes a user makes in it, read as the format's list.
#include "harness/scene/scene.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

namespace xshade::harness {
namespace {

// Every scene in these tests lives at scenes/<name>.toml under this folder, so that resolved
// paths are predictable.
const std::filesystem::path scene_root = "/project";

std::filesystem::path scene_file(const std::string& name) { return "scenes/" + name + ".toml"; }

Scene parse_ok(const std::string& text, const std::string& name = "test") {
  auto scene = parse_scene(text, scene_root / scene_file(name));
  EXPECT_TRUE(scene) << scene.error().to_string();
  return scene ? *scene : Scene{};
}

// Each diagnostic in the compiler form, in file order.
std::vector<std::string> errors_of(const std::string& text, const std::string& name = "bad") {
  auto scene = parse_scene(text, scene_file(name));
  if (scene) return {"(no error)"};
  std::vector<std::string> lines;
  for (const Diagnostic& diagnostic : scene.error().diagnostics) lines.push_back(diagnostic.to_string());
  return lines;
}

// The smallest valid scene; tests add to it or break one line of it.
const std::string minimal_head = R"(description = "minimal"
size = [64, 32]
[camera]
position = [0, 0, 8]
target = [0, 0, 0]
fov_y = 40
near = 0.3
far = 100
)";

void expect_vec(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_FLOAT_EQ(actual.x, expected.x);
  EXPECT_FLOAT_EQ(actual.y, expected.y);
  EXPECT_FLOAT_EQ(actual.z, expected.z);
}

void expect_near(const glm::vec4& actual, const glm::vec4& expected) {
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(actual[i], expected[i], 1e-5f) << "component " << i;
}

PropertyValue vec4_value(float x, float y, float z, float w) { return {{x, y, z, w}, 4}; }

TextureRef texture_ref(TextureOrigin source, std::filesystem::path file = {}) {
  TextureRef reference;
  reference.source = source;
  reference.file = std::move(file);
  return reference;
}

TEST(SceneParse, ReadsEveryValueOfACompleteScene) {
  Scene scene = parse_ok(R"(description = "metallic x smoothness ball grid"
size = [320, 240]
lanes = ["vk", "gl"]
clear_color = [0.1, 0.2, 0.3, 1]
time = 2.5
[camera]
position = [0, 1, 8]
target = [0, 0, 0]
up = [0, 0, 1]
fov_y = 40
near = 0.3
far = 100
[[light]]
type = "directional"
direction = [0, 3, 4]
color = [1, 0.9, 0.8]
intensity = 2.5
[[light]]
type = "directional"
direction = [-1, 0, 0]
[environment]
kind = "gradient"
sky = [0.3, 0.5, 0.9]
horizon = [0.9, 0.9, 0.9]
ground = [0.2, 0.18, 0.15]
intensity = 0.5
[[object]]
name = "balls"
mesh = "sphere"
material = "materials/standard_pbr.hlsl"
keywords = ["_GUARDED", "_NORMALMAP"]
position = [1, 2, 3]
rotation = [0, 30, 0]
scale = 0.5
[object.properties]
_Color = [1, 0.2, 0.2, 1]
_Smoothness = 0.5
_Offset = [1, 2]
[object.textures]
_MainTex = "white"
_BumpMap = "normal"
_DetailTex = "textures/detail.png"
[object.grid]
rows = 5
cols = 4
spacing = [2.2, 2.0]
[object.grid.vary]
_Metallic = { along = "cols", from = 0.0, to = 1.0 }
_Tint = { along = "rows", from = [1, 1, 1], to = [0, 0, 0] }
[[object]]
mesh = "models/bunny.obj"
material = "materials/toon.hlsl"
scale = [1, 2, 3]
[[post]]
effect = "post/depth_of_field.hlsl"
keywords = ["_KERNEL_MEDIUM"]
[post.parameters]
_FocusDistance = 6.0
_Range = [1, 2, 3]
[compare]
channel_tolerance = 3
max_failing_fraction = 0.001
position_radius = 1
reason = "edges of the spheres alias differently on the two rasterisers"
)",
                         "grid");

  EXPECT_EQ(scene.name, "grid");
  EXPECT_EQ(scene.path, scene_root / "scenes/grid.toml");
  EXPECT_EQ(scene.description, "metallic x smoothness ball grid");
  EXPECT_EQ(scene.width, 320u);
  EXPECT_EQ(scene.height, 240u);
  EXPECT_EQ(scene.lanes, (std::vector<std::string>{"vk", "gl"}));
  expect_near(scene.clear_color, {0.1f, 0.2f, 0.3f, 1.0f});
  EXPECT_FLOAT_EQ(scene.time_seconds, 2.5f);

  expect_vec(scene.camera.position, {0, 1, 8});
  expect_vec(scene.camera.target, {0, 0, 0});
  expect_vec(scene.camera.up, {0, 0, 1});
  EXPECT_FLOAT_EQ(scene.camera.fov_y_degrees, 40.0f);
  EXPECT_FLOAT_EQ(scene.camera.near_plane, 0.3f);
  EXPECT_FLOAT_EQ(scene.camera.far_plane, 100.0f);

  ASSERT_EQ(scene.lights.size(), 2u);
  expect_vec(scene.lights[0].direction, {0, 0.6f, 0.8f});  // normalised
  expect_vec(scene.lights[0].color, {1, 0.9f, 0.8f});
  EXPECT_FLOAT_EQ(scene.lights[0].intensity, 2.5f);
  expect_vec(scene.lights[1].direction, {-1, 0, 0});
  expect_vec(scene.lights[1].color, {1, 1, 1});  // defaults
  EXPECT_FLOAT_EQ(scene.lights[1].intensity, 1.0f);

  EXPECT_EQ(scene.environment.kind, EnvironmentKind::Gradient);
  expect_vec(scene.environment.sky, {0.3f, 0.5f, 0.9f});
  expect_vec(scene.environment.horizon, {0.9f, 0.9f, 0.9f});
  expect_vec(scene.environment.ground, {0.2f, 0.18f, 0.15f});
  EXPECT_FLOAT_EQ(scene.environment.intensity, 0.5f);
  EXPECT_TRUE(scene.environment.file.empty());

  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneObject& balls = scene.objects[0];
  EXPECT_EQ(balls.name, "balls");
  EXPECT_EQ(balls.mesh, (MeshRef{MeshKind::Sphere, {}, {}}));
  EXPECT_EQ(balls.material, "materials/standard_pbr.hlsl");
  EXPECT_EQ(balls.keywords, (std::vector<std::string>{"_GUARDED", "_NORMALMAP"}));
  expect_vec(balls.position, {1, 2, 3});
  expect_vec(balls.rotation_degrees, {0, 30, 0});
  expect_vec(balls.scale, {0.5f, 0.5f, 0.5f});
  ASSERT_EQ(balls.properties.size(), 3u);
  EXPECT_EQ(balls.properties.at("_Color"), vec4_value(1, 0.2f, 0.2f, 1));
  EXPECT_EQ(balls.properties.at("_Smoothness"), PropertyValue::scalar(0.5f));
  EXPECT_EQ(balls.properties.at("_Offset"), (PropertyValue{{1, 2, 0, 0}, 2}));
  ASSERT_EQ(balls.textures.size(), 3u);
  EXPECT_EQ(balls.textures.at("_MainTex"), texture_ref(TextureOrigin::White));
  EXPECT_EQ(balls.textures.at("_BumpMap"), texture_ref(TextureOrigin::Normal));
  EXPECT_EQ(balls.textures.at("_DetailTex"), texture_ref(TextureOrigin::File, "/project/scenes/textures/detail.png"));
  ASSERT_TRUE(balls.grid);
  EXPECT_EQ(balls.grid->rows, 5u);
  EXPECT_EQ(balls.grid->cols, 4u);
  EXPECT_FLOAT_EQ(balls.grid->spacing.x, 2.2f);
  EXPECT_FLOAT_EQ(balls.grid->spacing.y, 2.0f);
  ASSERT_EQ(balls.grid->vary.size(), 2u);
  const VaryRule& metallic = balls.grid->vary.at("_Metallic");
  EXPECT_EQ(metallic.along, GridAxis::Cols);
  EXPECT_EQ(metallic.from, PropertyValue::scalar(0.0f));
  EXPECT_EQ(metallic.to, PropertyValue::scalar(1.0f));
  const VaryRule& tint = balls.grid->vary.at("_Tint");
  EXPECT_EQ(tint.along, GridAxis::Rows);
  EXPECT_EQ(tint.from, (PropertyValue{{1, 1, 1, 0}, 3}));
  EXPECT_EQ(tint.to, (PropertyValue{{0, 0, 0, 0}, 3}));

  const SceneObject& bunny = scene.objects[1];
  EXPECT_EQ(bunny.name, "object1");
  EXPECT_EQ(bunny.mesh, (MeshRef{MeshKind::ObjFile, "/project/scenes/models/bunny.obj", {}}));
  EXPECT_EQ(bunny.material, "materials/toon.hlsl");
  expect_vec(bunny.scale, {1, 2, 3});
  EXPECT_FALSE(bunny.grid);

  ASSERT_EQ(scene.post.size(), 1u);
  EXPECT_EQ(scene.post[0].effect, "post/depth_of_field.hlsl");
  EXPECT_EQ(scene.post[0].keywords, (std::vector<std::string>{"_KERNEL_MEDIUM"}));
  EXPECT_EQ(scene.post[0].parameters.at("_FocusDistance"), PropertyValue::scalar(6.0f));
  EXPECT_EQ(scene.post[0].parameters.at("_Range"), (PropertyValue{{1, 2, 3, 0}, 3}));

  EXPECT_EQ(scene.compare.channel_tolerance, 3u);
  EXPECT_DOUBLE_EQ(scene.compare.max_failing_fraction, 0.001);
  EXPECT_EQ(scene.compare.position_radius, 1u);
  EXPECT_EQ(scene.compare.reason, "edges of the spheres alias differently on the two rasterisers");
  EXPECT_TRUE(scene.compare.tolerances_given);
}

TEST(SceneParse, AppliesTheDefaults) {
  Scene scene = parse_ok(minimal_head + R"(
[[object]]
mesh = "cube"
material = "materials/unlit.hlsl"
)");
  EXPECT_EQ(scene.lanes, (std::vector<std::string>{"gl", "vk", "vk-hlsl"}));
  expect_near(scene.clear_color, {0, 0, 0, 1});
  EXPECT_EQ(scene.time_seconds, 0.0f);
  expect_vec(scene.camera.up, {0, 1, 0});
  EXPECT_TRUE(scene.lights.empty());
  EXPECT_EQ(scene.environment.kind, EnvironmentKind::Constant);
  expect_vec(scene.environment.color, {0, 0, 0});
  EXPECT_FLOAT_EQ(scene.environment.intensity, 1.0f);
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& cube = scene.objects[0];
  EXPECT_EQ(cube.name, "object0");
  EXPECT_TRUE(cube.keywords.empty());
  expect_vec(cube.position, {0, 0, 0});
  expect_vec(cube.rotation_degrees, {0, 0, 0});
  expect_vec(cube.scale, {1, 1, 1});
  EXPECT_TRUE(cube.properties.empty());
  EXPECT_TRUE(cube.textures.empty());
  EXPECT_FALSE(cube.grid);
  EXPECT_TRUE(scene.post.empty());
  EXPECT_FALSE(scene.fog);
  EXPECT_EQ(scene.compare.channel_tolerance, 1u);
  EXPECT_EQ(scene.compare.max_failing_fraction, 0.0);
  EXPECT_EQ(scene.compare.position_radius, 0u);
  EXPECT_EQ(scene.compare.reason, "");
  EXPECT_FALSE(scene.compare.tolerances_given);
}

TEST(SceneParse, ReadsTheOtherEnvironmentKinds) {
  Scene constant = parse_ok(minimal_head + "[environment]\nkind = \"constant\"\ncolor = [0.5, 0.25, 1]\n");
  EXPECT_EQ(constant.environment.kind, EnvironmentKind::Constant);
  expect_vec(constant.environment.color, {0.5f, 0.25f, 1});

  Scene equirect = parse_ok(minimal_head + "[environment]\nkind = \"equirect\"\nfile = \"./env/../env/sky.exr\"\n");
  EXPECT_EQ(equirect.environment.kind, EnvironmentKind::Equirect);
  EXPECT_EQ(equirect.environment.file, "/project/scenes/env/sky.exr");
}

// [fog] is Unity's RenderSettings fog: what it leaves out is Unity's default.
TEST(SceneParse, TheUnityPlatformIsGlCoreUnlessTheSceneNamesOneAndOnlyForShaderFiles) {
  const std::string shader_object = "[[object]]\nmesh = \"sphere\"\nmaterial = \"Unlit/Texture.shader\"\n";
  EXPECT_EQ(parse_ok(minimal_head + shader_object).unity_platform, shaderlab::UnityPlatform::GLCore);
  EXPECT_EQ(parse_ok(minimal_head + "[unity]\nplatform = \"d3d11\"\n" + shader_object).unity_platform,
            shaderlab::UnityPlatform::D3D11);
  EXPECT_EQ(parse_ok(minimal_head + "[unity]\nplatform = \"vulkan\"\n" + shader_object).unity_platform,
            shaderlab::UnityPlatform::Vulkan);
  EXPECT_EQ(errors_of(minimal_head + "[unity]\nplatform = \"metal\"\n"),
            (std::vector<std::string>{"scenes/bad.toml:10:12: error: unity.platform: expected \"glcore\", \"d3d11\" or "
                                      "\"vulkan\", got \"metal\""}));
  const std::vector<std::string> mixed =
      errors_of(minimal_head + "[unity]\nplatform = \"d3d11\"\n" + shader_object +
                "[[object]]\nname = \"own\"\nmesh = \"cube\"\nmaterial = \"materials/toon.hlsl\"\n");
  ASSERT_EQ(mixed.size(), 1u);
  EXPECT_TRUE(
      mixed[0].starts_with("scenes/bad.toml:10:12: error: unity.platform: \"d3d11\" is for scenes whose materials "
                           "and effects are all Unity .shader files, and object 'own''s material is "
                           "'materials/toon.hlsl'"))
      << mixed[0];
}

TEST(SceneParse, FogTakesUnitysModesAndDefaults) {
  Scene linear = parse_ok(minimal_head + "[fog]\nmode = \"linear\"\ncolor = [0.1, 0.2, 0.3, 1]\nstart = 2\nend = 20\n");
  ASSERT_TRUE(linear.fog);
  EXPECT_EQ(linear.fog->mode, FogMode::Linear);
  expect_near(linear.fog->color, {0.1f, 0.2f, 0.3f, 1.0f});
  EXPECT_EQ(linear.fog->start, 2.0f);
  EXPECT_EQ(linear.fog->end, 20.0f);
  EXPECT_STREQ(fog_keyword(linear.fog->mode), "FOG_LINEAR");

  Scene defaults = parse_ok(minimal_head + "[fog]\n");
  ASSERT_TRUE(defaults.fog);
  EXPECT_EQ(defaults.fog->mode, FogMode::ExponentialSquared);
  EXPECT_EQ(defaults.fog->density, 0.01f);
  expect_near(defaults.fog->color, {0.5f, 0.5f, 0.5f, 1.0f});
  EXPECT_STREQ(fog_keyword(FogMode::Exponential), "FOG_EXP");

  EXPECT_EQ(
      errors_of(minimal_head + "[fog]\nmode = \"mist\"\ndensity = -1\n"),
      (std::vector<std::string>{
          "scenes/bad.toml:10:8: error: fog.mode: expected \"linear\", \"exponential\" or \"exponential_squared\", "
          "got \"mist\"",
          "scenes/bad.toml:11:11: error: fog.density: expected a number >= 0, got -1"}));
  EXPECT_EQ(
      errors_of(minimal_head + "[fog]\nmode = \"linear\"\nstart = 5\nend = 5\n"),
      (std::vector<std::string>{"scenes/bad.toml:9:1: error: fog: linear fog ends where it starts or before (5 to 5): "
                                "give an end beyond the start"}));
}

TEST(SceneParse, ACompareTableWithOnlyAReasonGivesNoTolerance) {
  Scene scene = parse_ok(minimal_head + "[compare]\nreason = \"defaults are right here\"\n");
  EXPECT_FALSE(scene.compare.tolerances_given);
  EXPECT_EQ(scene.compare.channel_tolerance, CompareSettings::default_channel_tolerance);
}

TEST(SceneParse, ACompareMetricWithItsThresholds) {
  Scene deltae = parse_ok(minimal_head +
                          "[compare]\nmetric = \"deltae\"\nmetric_threshold = 0.5\npixel_threshold = 2\n"
                          "incorrect_fraction = 0.01\nreason = \"colour is what this scene checks\"\n");
  ASSERT_TRUE(deltae.compare.metric);
  EXPECT_EQ(deltae.compare.metric->metric, Metric::DeltaE);
  EXPECT_EQ(deltae.compare.metric->threshold, 0.5);
  EXPECT_EQ(deltae.compare.metric->pixel_threshold, 2.0);
  EXPECT_EQ(deltae.compare.metric->incorrect_fraction, 0.01);
  // Without a threshold, the metric's default.
  Scene flip = parse_ok(minimal_head + "[compare]\nmetric = \"flip\"\nreason = \"r\"\n");
  ASSERT_TRUE(flip.compare.metric);
  EXPECT_EQ(flip.compare.metric->threshold, default_metric_threshold(Metric::Flip));
  EXPECT_FALSE(parse_ok(minimal_head).compare.metric);
}

TEST(SceneErrors, ACompareMetricsMistakes) {
  EXPECT_EQ(
      errors_of(minimal_head + "[compare]\nmetric = \"psnr\"\nreason = \"r\"\n"),
      (std::vector<std::string>{
          "scenes/bad.toml:10:10: error: compare.metric: expected \"flip\", \"ssim\" or \"deltae\", got \"psnr\""}));
  // Another metric's key, and a metric's key without the metric.
  EXPECT_EQ(errors_of(minimal_head + "[compare]\nmetric = \"flip\"\npixel_threshold = 2\nreason = \"r\"\n"),
            (std::vector<std::string>{"scenes/bad.toml:11:19: error: compare.pixel_threshold: belongs to metric "
                                      "deltae; set compare.metric = \"deltae\" or leave it out"}));
  EXPECT_EQ(errors_of(minimal_head + "[compare]\nmetric_threshold = 0.1\nreason = \"r\"\n"),
            (std::vector<std::string>{"scenes/bad.toml:10:20: error: compare.metric_threshold: belongs to a metric; "
                                      "set compare.metric = \"flip\" or leave it out"}));
  EXPECT_EQ(
      errors_of(minimal_head + "[compare]\nmetric = \"ssim\"\nmetric_threshold = 2\nreason = \"r\"\n"),
      (std::vector<std::string>{"scenes/bad.toml:11:20: error: compare.metric_threshold: expected a number: "
                                "flip's mean in [0, 1], ssim's in [-1, 1], deltae's average of 0 or more, got 2"}));
  // A metric is a choice of tolerance: it needs its reason.
  EXPECT_EQ(errors_of(minimal_head + "[compare]\nmetric = \"ssim\"\n"),
            (std::vector<std::string>{"scenes/bad.toml:9:1: error: compare.reason: missing; a tolerance (metric) "
                                      "needs a reason saying why these numbers"}));
  std::string tiny = minimal_head;
  tiny.replace(tiny.find("size = [64, 32]"), 15, "size = [64, 8]");
  EXPECT_EQ(errors_of(tiny + "[compare]\nmetric = \"ssim\"\nreason = \"r\"\n"),
            (std::vector<std::string>{"scenes/bad.toml:10:10: error: compare.metric: ssim measures in 11x11 windows "
                                      "and this scene is 64x8; choose flip or deltae"}));
}

TEST(SceneErrors, SyntaxErrorIsReportedWhereTomlStops) {
  EXPECT_EQ(errors_of("description = \"x\"\nsize = [64, 32\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:2:16: error: syntax error: Error while parsing array: encountered end-of-file"}));
}

TEST(SceneErrors, WrongTypeNamesTheKeyAndWhatWasFound) {
  std::string text = minimal_head;
  text.replace(text.find("fov_y = 40"), 10, "fov_y = \"wide\"");
  EXPECT_EQ(errors_of(text),
            (std::vector<std::string>{
                "scenes/bad.toml:6:9: error: camera.fov_y: expected a number in (0, 180), got \"wide\""}));
}

TEST(SceneErrors, OutOfRangeValues) {
  std::string text = minimal_head;
  text.replace(text.find("fov_y = 40"), 10, "fov_y = 200");
  text.replace(text.find("size = [64, 32]"), 15, "size = [64, 5000]");
  text.replace(text.find("far = 100"), 9, "far = 0.1");
  EXPECT_EQ(errors_of(text + "[compare]\nchannel_tolerance = 2.0\nmax_failing_fraction = 1.5\nposition_radius = 9\n"
                             "reason = \"r\"\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:2:13: error: size[1]: expected an integer in 1..4096, got 5000",
                "scenes/bad.toml:6:9: error: camera.fov_y: expected a number in (0, 180), got 200",
                "scenes/bad.toml:8:7: error: camera.far: expected a number greater than camera.near (0.3), got 0.1",
                "scenes/bad.toml:10:21: error: compare.channel_tolerance: expected an integer in 0..255, got 2.0",
                "scenes/bad.toml:11:24: error: compare.max_failing_fraction: expected a number in [0, 1], got 1.5",
                "scenes/bad.toml:12:19: error: compare.position_radius: expected an integer in 0..8, got 9",
            }));
}

TEST(SceneParse, TexturesAsTablesFacesAndTheEnvironment) {
  Scene scene = parse_ok(minimal_head + R"(
[[object]]
mesh = "cube"
material = "materials/unlit.hlsl"
[object.textures]
_Sky = "environment"
_Faces = { faces = ["px.png", "nx.png", "py.png", "ny.png", "pz.png", "nz.png"] }
_Mask = { file = "mask.png", srgb = false }
[[post]]
effect = "post/grade.hlsl"
[post.textures]
_Lut = "luts/film.cube"
)");
  const auto& textures = scene.objects.at(0).textures;
  EXPECT_EQ(textures.at("_Sky").source, TextureOrigin::Environment);
  const TextureRef& faces = textures.at("_Faces");
  EXPECT_EQ(faces.source, TextureOrigin::Faces);
  ASSERT_EQ(faces.faces.size(), 6u);
  EXPECT_EQ(faces.faces[3], scene_root / "scenes/ny.png");
  EXPECT_EQ(faces.where.to_string(), "/project/scenes/test.toml:15:10");
  const TextureRef& mask = textures.at("_Mask");
  EXPECT_EQ(mask.source, TextureOrigin::File);
  EXPECT_FALSE(mask.srgb);
  EXPECT_TRUE(textures.at("_Sky").srgb);
  ASSERT_EQ(scene.post.size(), 1u);
  EXPECT_EQ(scene.post[0].textures.at("_Lut").file, scene_root / "scenes/luts/film.cube");
}

TEST(SceneErrors, TextureTablesAreChecked) {
  EXPECT_EQ(
      errors_of(minimal_head + R"(
[[object]]
mesh = "cube"
material = "materials/unlit.hlsl"
[object.textures]
_A = { faces = ["a.png", "b.png"] }
_B = { file = "a.png", faces = [] }
_C = { file = "a.png", srgb = "no" }
_D = { fil = "a.png" }
_E = { srgb = false }
_F = "enviroment"
[[post]]
effect = "post/grade.hlsl"
[post.textures]
_G = { faces = ["a.png", "b.png", "c.png", "d.png", "e.png", "../f.png"] }
)"),
      (std::vector<std::string>{
          "scenes/bad.toml:14:16: error: object[0].textures._A.faces: expected an array of 6 image paths: +x, -x, "
          "+y, -y, +z, -z, got [\"a.png\", \"b.png\"]",
          "scenes/bad.toml:15:32: error: object[0].textures._B: give either file or faces, not both",
          "scenes/bad.toml:16:31: error: object[0].textures._C.srgb: expected true (8-bit colour is sRGB-encoded) "
          "or false (linear data), got \"no\"",
          "scenes/bad.toml:17:6: error: object[0].textures._D.file: missing; expected an image path (or faces = "
          "[6 image paths])",
          "scenes/bad.toml:17:8: error: object[0].textures._D.fil: unknown key; did you mean file?",
          "scenes/bad.toml:18:6: error: object[0].textures._E.file: missing; expected an image path (or faces = "
          "[6 image paths])",
          "scenes/bad.toml:19:6: error: object[0].textures._F: expected white, black, checker, normal, "
          "gray, red, clear, environment, an image path or a table (file or faces), got \"enviroment\"; did you mean "
          "\"environment\"?",
          "scenes/bad.toml:23:62: error: post[0].textures._G.faces[5]: expected a path inside the scene file's "
          "folder, got \"../f.png\", which leads out of it",
      }));
}

TEST(SceneParse, BuffersAreNumbersOrAFileInTheScenesFolder) {
  const Scene scene = parse_ok(minimal_head + R"(
[[object]]
mesh = "plane"
material = "materials/unlit.hlsl"
[object.buffers]
palette = [1, 0.5, -2]
words = "data/words.bin"
)");
  const auto& buffers = scene.objects.at(0).buffers;
  ASSERT_EQ(buffers.size(), 2u);
  EXPECT_EQ(buffers.at("palette").numbers, (std::vector<double>{1, 0.5, -2}));
  EXPECT_EQ(buffers.at("words").file, scene_root / "scenes/data/words.bin");
  EXPECT_EQ(buffers.at("words").where.line, 15u);
  EXPECT_EQ(expand_instances(scene).at(0).buffers, buffers);
}

TEST(SceneErrors, BufferValuesAreChecked) {
  EXPECT_EQ(
      errors_of(minimal_head + R"(
[[object]]
mesh = "plane"
material = "materials/unlit.hlsl"
[object.buffers]
a = []
b = [1, true]
c = "../outside.bin"
)"),
      (std::vector<std::string>{
          "scenes/bad.toml:14:5: error: object[0].buffers.a: expected an array of numbers or the path of a file of "
          "the buffer's bytes, got an empty array",
          "scenes/bad.toml:15:9: error: object[0].buffers.b: expected numbers only, got true",
          "scenes/bad.toml:16:5: error: object[0].buffers.c: expected a path inside the scene file's folder, got "
          "\"../outside.bin\", which leads out of it",
      }));
}

TEST(SceneParse, AShaderEffectsPassesAreItsBlitsInOrder) {
  Scene scene = parse_ok(minimal_head + R"(
[[post]]
effect = "Hidden/Blur.shader"
passes = [0, "Downsample", { pass = 2, name = "blurred", scale = "half", sources = { _Bloom = "0" } }]
)");
  ASSERT_EQ(scene.post.size(), 1u);
  const std::vector<PostStep>& steps = scene.post[0].passes;
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].pass, "0");
  EXPECT_EQ(steps[1].pass, "Downsample");
  EXPECT_FALSE(steps[1].half);
  EXPECT_EQ(steps[2].pass, "2");
  EXPECT_EQ(steps[2].name, "blurred");
  EXPECT_TRUE(steps[2].half);
  EXPECT_EQ(steps[2].sources, (std::map<std::string, std::string>{{"_Bloom", "0"}}));
  EXPECT_EQ(steps[2].where.to_string(), "/project/scenes/test.toml:12:28");
}

TEST(SceneErrors, PostStepsAreCheckedEachAtItsPlace) {
  EXPECT_EQ(
      errors_of(minimal_head + R"(
[[post]]
effect = "Hidden/Blur.shader"
passes = [-1, "", 0, 0, { name = "x" }, { pass = 1, scale = "quarter", sources = { _A = "later", _B = 3 } }]
[[post]]
effect = "Hidden/Copy.shader"
passes = []
)"),
      (std::vector<std::string>{
          "scenes/bad.toml:12:11: error: post[0].passes[0]: expected a pass's index (0 to 1023) or Name, or a table "
          "{ pass = ..., name, scale, sources }, got -1",
          "scenes/bad.toml:12:15: error: post[0].passes[1]: expected a pass's index (0 to 1023) or Name, or a table "
          "{ pass = ..., name, scale, sources }, got \"\"",
          "scenes/bad.toml:12:22: error: post[0].passes[3]: a step named '0' comes earlier; give this one its own "
          "name = \"...\"",
          "scenes/bad.toml:12:25: error: post[0].passes[4].pass: missing; expected the pass's index or Name",
          "scenes/bad.toml:12:61: error: post[0].passes[5].scale: expected \"full\" or \"half\", got \"quarter\"",
          "scenes/bad.toml:12:89: error: post[0].passes[5].sources._A: expected \"scene.color\", \"scene.depth\" or "
          "the name of an earlier step, got \"later\"",
          "scenes/bad.toml:12:103: error: post[0].passes[5].sources._B: expected \"scene.color\", \"scene.depth\" or "
          "an earlier step's name, got 3",
          "scenes/bad.toml:15:10: error: post[1].passes: expected an array of passes, each an index, a Name or a "
          "table { pass = ..., name, scale, sources }, got an empty array",
      }));
}

TEST(SceneErrors, TimeIsSecondsFromZeroOn) {
  EXPECT_EQ(errors_of("time = -1\n" + minimal_head),
            (std::vector<std::string>{"scenes/bad.toml:1:8: error: time: expected a number of seconds >= 0, got -1"}));
}

TEST(SceneErrors, UnknownKeysAreAllReportedWithTheNearestKnownKey) {
  std::string text = minimal_head;
  text.replace(text.find("fov_y = 40"), 10, "fvo_y = 40");
  EXPECT_EQ(errors_of("discription = \"typo\"\n" + text +
                      "zoom = 2\n[[object]]\nmesh = \"sphere\"\n"
                      "material = \"m.hlsl\"\ncolour = [1, 1, 1]\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:1:1: error: discription: unknown key; did you mean description?",
                "scenes/bad.toml:4:1: error: camera.fov_y: missing; expected a number in (0, 180)",
                "scenes/bad.toml:7:1: error: camera.fvo_y: unknown key; did you mean fov_y?",
                "scenes/bad.toml:10:1: error: camera.zoom: unknown key; expected one of position, target, up, fov_y, "
                "near, far",
                "scenes/bad.toml:14:1: error: object[0].colour: unknown key; expected one of name, mesh, material, "
                "keywords, position, rotation, scale, properties, textures, buffers, grid",
            }));
}

TEST(SceneErrors, MissingRequiredSectionsAndKeys) {
  EXPECT_EQ(errors_of("description = \"no size, no camera\"\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:1:1: error: size: missing; expected [width, height] in pixels",
                "scenes/bad.toml:1:1: error: camera: missing; expected a table",
            }));
  EXPECT_EQ(errors_of(minimal_head + "[[object]]\nname = \"x\"\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:9:1: error: object[0].mesh: missing; expected sphere, torus, plane, cube or a path "
                "ending in .obj",
                "scenes/bad.toml:9:1: error: object[0].material: missing; expected a path in the shader folders, e.g. "
                "\"materials/standard_pbr.hlsl\"",
            }));
}

TEST(SceneErrors, AToleranceNeedsAReason) {
  EXPECT_EQ(errors_of(minimal_head + "[compare]\nchannel_tolerance = 2\nposition_radius = 1\n"),
            (std::vector<std::string>{"scenes/bad.toml:9:1: error: compare.reason: missing; a tolerance "
                                      "(channel_tolerance, position_radius) needs a reason saying why these numbers"}));
  EXPECT_EQ(errors_of(minimal_head + "[compare]\nmax_failing_fraction = 0.01\nreason = \"  \"\n"),
            (std::vector<std::string>{"scenes/bad.toml:11:10: error: compare.reason: expected a string saying why "
                                      "these tolerances, got \"  \""}));
}

TEST(SceneErrors, LaneNamesAreChecked) {
  EXPECT_EQ(errors_of("lanes = [\"gl\", \"vulkan\", \"vk-hlls\", \"gl\", 3]\n" + minimal_head),
            (std::vector<std::string>{
                "scenes/bad.toml:1:16: error: lanes[1]: expected one of gl, vk, vk-hlsl, got \"vulkan\"",
                "scenes/bad.toml:1:26: error: lanes[2]: expected one of gl, vk, vk-hlsl, got \"vk-hlls\"; did you mean "
                "\"vk-hlsl\"?",
                "scenes/bad.toml:1:37: error: lanes[3]: lane \"gl\" is listed twice",
                "scenes/bad.toml:1:43: error: lanes[4]: expected one of gl, vk, vk-hlsl, got 3",
            }));
}

TEST(SceneErrors, PathsMustStayInsideTheScenesFolder) {
  EXPECT_EQ(errors_of(minimal_head + R"([environment]
kind = "equirect"
file = "/etc/sky.exr"
[[object]]
mesh = "meshes/../../../model.obj"
material = "../outside.hlsl"
[object.textures]
_MainTex = "../../etc/passwd.png"
_Detail = "whte"
)"),
            (std::vector<std::string>{
                "scenes/bad.toml:11:8: error: environment.file: expected a path relative to the scene file, got the "
                "absolute path \"/etc/sky.exr\"",
                "scenes/bad.toml:13:8: error: object[0].mesh: expected a path inside the scene file's folder, got "
                "\"meshes/../../../model.obj\", which leads out of it",
                "scenes/bad.toml:14:12: error: object[0].material: expected a file path inside the shader folders, got "
                "\"../outside.hlsl\"",
                "scenes/bad.toml:16:12: error: object[0].textures._MainTex: expected a path inside the scene file's "
                "folder, got \"../../etc/passwd.png\", which leads out of it",
                "scenes/bad.toml:17:11: error: object[0].textures._Detail: expected white, black, checker, normal, "
                "gray, red, clear, environment, an image path or a table (file or faces), got \"whte\"; did you mean "
                "\"white\"?",
            }));
}

TEST(SceneErrors, LightDirectionMustNotBeZero) {
  EXPECT_EQ(errors_of(minimal_head + "[[light]]\ntype = \"directional\"\ndirection = [0, 0, 0.0]\n"),
            (std::vector<std::string>{"scenes/bad.toml:11:13: error: light[0].direction: expected a non-zero vector, "
                                      "got [0, 0, 0.0]"}));
}

TEST(Scene, PointAndSpotLightsHaveAPositionARangeAndASpotAngle) {
  auto scene = parse_scene(minimal_head +
                               "[[light]]\ntype = \"point\"\nposition = [1, 2, 3]\nrange = 4\n"
                               "[[light]]\ntype = \"spot\"\nposition = [0, 5, 0]\ndirection = [0, 2, 0]\n"
                               "spot_angle = 40\nintensity = 2\n[unity]\npixel_lights = 1\n",
                           "scenes/lights.toml");
  ASSERT_TRUE(scene) << scene.error().to_string();
  ASSERT_EQ(scene->lights.size(), 2u);
  EXPECT_EQ(scene->lights[0].type, LightType::Point);
  expect_vec(scene->lights[0].position, {1, 2, 3});
  EXPECT_FLOAT_EQ(scene->lights[0].range, 4.0f);
  EXPECT_EQ(scene->lights[1].type, LightType::Spot);
  expect_vec(scene->lights[1].direction, {0, 1, 0});
  EXPECT_FLOAT_EQ(scene->lights[1].spot_angle, 40.0f);
  EXPECT_FLOAT_EQ(scene->lights[1].range, 10.0f);  // Unity's default
  EXPECT_EQ(scene->pixel_lights, 1);
}

TEST(SceneErrors, ALightKeyOfAnotherKindOfLightIsAnError) {
  EXPECT_EQ(
      errors_of(minimal_head + "[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\ndirection = [0, 1, 0]\n"),
      (std::vector<std::string>{"scenes/bad.toml:12:13: error: light[0].direction is for directional and spot lights; "
                                "a point light has none"}));
  EXPECT_EQ(errors_of(minimal_head + "[[light]]\ntype = \"directional\"\ndirection = [0, 1, 0]\nrange = 3\n"),
            (std::vector<std::string>{"scenes/bad.toml:12:9: error: light[0].range is for point and spot lights; "
                                      "a directional light has none"}));
  EXPECT_EQ(
      errors_of(minimal_head + "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, 1, 0]\n"
                               "spot_angle = 180\n"),
      (std::vector<std::string>{"scenes/bad.toml:13:14: error: light[0].spot_angle: expected a number of degrees in "
                                "(0, 180), got 180"}));
  EXPECT_EQ(errors_of(minimal_head + "[[light]]\ntype = \"point\"\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:9:1: error: light[0].position: missing; expected an array of 3 numbers"}));
}

TEST(SceneErrors, ShadowsNotRenderedYetAreErrorsThatSayWhy) {
  const std::vector<std::string> point =
      errors_of(minimal_head + "[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\nshadows = \"hard\"\n");
  ASSERT_EQ(point.size(), 1u);
  EXPECT_NE(point[0].find("light[0].shadows: a point light's shadows are not rendered yet"), std::string::npos)
      << point[0];
  // Soft shadows on every lane (the default lanes): vk-hlsl cannot filter them.
  const std::vector<std::string> soft =
      errors_of(minimal_head + "[[light]]\ntype = \"directional\"\ndirection = [0, 1, 0]\nshadows = \"soft\"\n");
  ASSERT_EQ(soft.size(), 1u);
  EXPECT_NE(soft[0].find("light[0].shadows: \"soft\" is not drawn on the vk-hlsl lane"), std::string::npos) << soft[0];
  auto without_vk_hlsl =
      parse_scene("lanes = [\"gl\", \"vk\"]\n" + minimal_head +
                      "[[light]]\ntype = \"directional\"\ndirection = [0, 1, 0]\nshadows = \"soft\"\n",
                  "scenes/soft.toml");
  ASSERT_TRUE(without_vk_hlsl) << without_vk_hlsl.error().to_string();
  EXPECT_EQ(without_vk_hlsl->lights.at(0).shadows, Light::Shadows::Soft);
  EXPECT_EQ(
      errors_of(minimal_head + "[[light]]\ntype = \"spot\"\nposition = [0, 1, 0]\ndirection = [0, 1, 0]\n"
                               "shadows = \"hard\"\nshadow_resolution = 1000\n"),
      (std::vector<std::string>{"scenes/bad.toml:14:21: error: light[0].shadow_resolution: expected a power of two "
                                "from 64 to 4096, got 1000"}));
}

TEST(SceneErrors, CameraMustSeeSomething) {
  std::string text = minimal_head;
  text.replace(text.find("target = [0, 0, 0]"), 18, "target = [0, 0, 8]");
  EXPECT_EQ(errors_of(text), (std::vector<std::string>{"scenes/bad.toml:5:10: error: camera.target: expected a point "
                                                       "other than camera.position, got the same point"}));
  EXPECT_EQ(errors_of(minimal_head + "up = [0, 0, -2]\n"),
            (std::vector<std::string>{"scenes/bad.toml:9:6: error: camera.up: expected a direction not parallel to "
                                      "the view direction, got [0, 0, -2]"}));
}

TEST(SceneErrors, GridAndVaryRules) {
  EXPECT_EQ(errors_of(minimal_head + R"([[object]]
mesh = "sphere"
material = "m.hlsl"
properties = { _Color = [1, 1, 1, 1] }
[object.grid]
rows = 0
cols = 2
spacing = -1
[object.grid.vary]
_Color = { along = "cols", from = 0, to = 1 }
_M = { along = "rows", from = 0, to = [1, 2] }
_N = { alog = "diagonal", from = 0, to = 1 }
_O = { along = "diagonal", from = 0, to = 1 }
)"),
            (std::vector<std::string>{
                "scenes/bad.toml:14:8: error: object[0].grid.rows: expected an integer in 1..64, got 0",
                "scenes/bad.toml:16:11: error: object[0].grid.spacing: expected a number > 0 or [dx, dy], got -1",
                "scenes/bad.toml:18:10: error: object[0].grid.vary._Color: expected 4 numbers like the object's "
                "property, got a number",
                "scenes/bad.toml:19:39: error: object[0].grid.vary._M.to: expected a number like from, got [1, 2]",
                "scenes/bad.toml:20:6: error: object[0].grid.vary._N.along: missing; expected \"rows\" or \"cols\"",
                "scenes/bad.toml:20:8: error: object[0].grid.vary._N.alog: unknown key; did you mean along?",
                "scenes/bad.toml:21:16: error: object[0].grid.vary._O.along: expected \"rows\" or \"cols\", got "
                "\"diagonal\"",
            }));
}

TEST(SceneErrors, ObjectNamesAreUnique) {
  EXPECT_EQ(errors_of(minimal_head + "[[object]]\nname = \"a\"\nmesh = \"cube\"\nmaterial = \"m.hlsl\"\n"
                                     "[[object]]\nname = \"a\"\nmesh = \"sphre\"\nmaterial = \"m.hlsl\"\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:14:8: error: object[1].name: \"a\" is already the name of object[0]",
                "scenes/bad.toml:15:8: error: object[1].mesh: expected sphere, torus, plane, cube or a path ending in "
                ".obj, got \"sphre\"; did you mean \"sphere\"?",
            }));
}

TEST(SceneErrors, TheErrorCarriesTheFirstProblemAsItsMessage) {
  std::string text = minimal_head + "[[light]]\ntype = \"area\"\ndirection = [0, 1, 0]\n";
  text.replace(text.find("size = [64, 32]"), 15, "size = [0, 32]");
  auto scene = parse_scene(text, "scenes/bad.toml");
  ASSERT_FALSE(scene);
  EXPECT_EQ(scene.error().message, "size[0]: expected an integer in 1..4096, got 0");
  EXPECT_EQ(scene.error().where.to_string(), "scenes/bad.toml:2:9");
  ASSERT_EQ(scene.error().diagnostics.size(), 2u);
  EXPECT_EQ(
      scene.error().diagnostics[1].to_string(),
      "scenes/bad.toml:10:8: error: light[0].type: expected \"directional\", \"point\" or \"spot\", got \"area\"");
  EXPECT_EQ(scene.error().diagnostics[0].message, scene.error().message);
}

// One key of 100,000 parts overflowed toml++'s stack (SIGSEGV); now it is refused before toml++
// reads it, at the key.
TEST(SceneErrors, AKeyNestedTooDeepIsRefusedBeforeTheTomlParserRecurses) {
  std::string key = "a";
  for (int i = 1; i < 100000; ++i) key += ".a";
  const std::vector<std::string> errors = errors_of(minimal_head + key + " = 1\n");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0],
            "scenes/bad.toml:9:1: error: a dotted key or table header of 100000 parts; xshade reads at "
            "most 100 (a longer one could overflow the TOML parser's stack)");
}

TEST(SceneLoad, ReadsAFileAndReportsAMissingOne) {
  auto folder = std::filesystem::temp_directory_path() / "xshade_scene_test";
  std::filesystem::create_directories(folder);
  auto path = folder / "on_disk.toml";
  std::ofstream(path) << minimal_head;
  auto scene = load_scene(path);
  ASSERT_TRUE(scene) << scene.error().to_string();
  EXPECT_EQ(scene->name, "on_disk");
  EXPECT_EQ(scene->width, 64u);

  auto missing = load_scene(folder / "absent.toml");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().to_string(),
            "the scene file " + (folder / "absent.toml").string() + " cannot be opened: No such file or directory");
}

TEST(SceneLoad, ASymbolicLinkOutOfTheScenesFolderIsRefused) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "xshade_scene_link_test";
  fs::remove_all(root);
  fs::create_directories(root / "scenes");
  fs::create_directories(root / "private");
  std::ofstream(root / "private" / "secret.png") << "not an image";
  fs::create_symlink(root / "private", root / "scenes" / "textures");
  std::ofstream(root / "scenes" / "linked.toml") << minimal_head << "[[object]]\nmesh = \"sphere\"\n"
                                                 << "material = \"materials/toon.hlsl\"\n[object.textures]\n"
                                                 << "_MainTex = \"textures/secret.png\"\n";
  auto scene = load_scene(root / "scenes" / "linked.toml");
  ASSERT_FALSE(scene);
  EXPECT_EQ(scene.error().message,
            "object[0].textures._MainTex: expected a path inside the scene file's folder, got \"textures/secret.png\", "
            "which leads out of it through a symbolic link");
  EXPECT_EQ(scene.error().where.line, 13u);
  EXPECT_EQ(scene.error().where.column, 12u);
  fs::remove_all(root);
}

TEST(SceneErrors, EnvironmentKeysBelongToTheirKind) {
  EXPECT_EQ(errors_of(minimal_head + "[environment]\nkind = \"constant\"\ncolor = [1, 1, 1]\nsky = [0, 0, 1]\n"),
            (std::vector<std::string>{"scenes/bad.toml:12:1: error: environment.sky: unknown key for kind "
                                      "\"constant\"; expected one of kind, color, intensity"}));
  EXPECT_EQ(errors_of(minimal_head + "[environment]\nkind = \"gradient\"\nsky = [0, 0, 1]\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:9:1: error: environment.horizon: missing; expected an array of 3 numbers >= 0",
                "scenes/bad.toml:9:1: error: environment.ground: missing; expected an array of 3 numbers >= 0",
            }));
}

TEST(SceneErrors, ALightWrittenAsASingleTableIsRefused) {
  EXPECT_EQ(errors_of(minimal_head + "[light]\ntype = \"directional\"\ndirection = [0, 1, 0]\n"),
            (std::vector<std::string>{
                "scenes/bad.toml:9:1: error: light: expected an array of tables ([[light]]), got a table"}));
}

// The format reference's complete example is a scene that reads without error.
TEST(SceneDocs, TheCompleteExampleParses) {
  std::ifstream stream(std::filesystem::path(XSHADE_SOURCE_DIR) / "docs/scenes.md");
  ASSERT_TRUE(stream);
  std::string line, example;
  bool inside = false;
  while (std::getline(stream, line)) {
    if (!inside && line == "```toml") {
      inside = true;
    } else if (inside && line == "```") {
      break;
    } else if (inside) {
      example += line + "\n";
    }
  }
  ASSERT_FALSE(example.empty());
  Scene scene = parse_ok(example, "ball_grid");
  EXPECT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(expand_instances(scene).size(), 26u);
  EXPECT_TRUE(scene.compare.tolerances_given);
}

// ---- instances

const std::string grid_scene = minimal_head + R"([[object]]
name = "balls"
mesh = "sphere"
material = "materials/standard_pbr.hlsl"
keywords = ["_GUARDED"]
position = [1, 2, 0]
[object.properties]
_Metallic = 0.25
_Color = [1, 0, 0, 1]
[object.textures]
_MainTex = "checker"
[object.grid]
rows = 3
cols = 5
spacing = [2, 3]
[object.grid.vary]
_Metallic = { along = "cols", from = 0.0, to = 1.0 }
_Smoothness = { along = "rows", from = 1.0, to = 0.0 }
)";

glm::vec3 translation(const glm::mat4& model) { return glm::vec3(model[3]); }

TEST(SceneInstances, GridRowZeroIsOnTopAndVaryRulesInterpolate) {
  Scene scene = parse_ok(grid_scene);
  std::vector<ObjectInstance> instances = expand_instances(scene);
  ASSERT_EQ(instances.size(), 15u);

  auto at = [&](uint32_t row, uint32_t col) -> const ObjectInstance& { return instances[row * 5 + col]; };
  EXPECT_EQ(at(0, 0).row, 0u);
  EXPECT_EQ(at(0, 0).col, 0u);
  EXPECT_EQ(at(2, 3).row, 2u);
  EXPECT_EQ(at(2, 3).col, 3u);

  // Centred on (1, 2): columns at x = 1 + (c - 2) * 2, rows at y = 2 + (1 - r) * 3.
  expect_vec(translation(at(0, 0).model), {-3, 5, 0});   // top left
  expect_vec(translation(at(0, 4).model), {5, 5, 0});    // top right
  expect_vec(translation(at(1, 2).model), {1, 2, 0});    // centre
  expect_vec(translation(at(2, 0).model), {-3, -1, 0});  // bottom left
  expect_vec(translation(at(2, 4).model), {5, -1, 0});   // bottom right

  EXPECT_EQ(at(0, 0).properties.at("_Metallic"), PropertyValue::scalar(0.0f));  // vary replaces the base 0.25
  EXPECT_EQ(at(0, 4).properties.at("_Metallic"), PropertyValue::scalar(1.0f));
  EXPECT_EQ(at(1, 2).properties.at("_Metallic"), PropertyValue::scalar(0.5f));
  EXPECT_EQ(at(2, 1).properties.at("_Metallic"), PropertyValue::scalar(0.25f));
  EXPECT_EQ(at(0, 0).properties.at("_Smoothness"), PropertyValue::scalar(1.0f));  // top row: from
  EXPECT_EQ(at(1, 2).properties.at("_Smoothness"), PropertyValue::scalar(0.5f));
  EXPECT_EQ(at(2, 4).properties.at("_Smoothness"), PropertyValue::scalar(0.0f));  // bottom row: to

  for (const ObjectInstance& instance : instances) {
    EXPECT_EQ(instance.object_name, "balls");
    EXPECT_EQ(instance.object_index, 0u);
    EXPECT_TRUE(instance.in_grid);
    EXPECT_EQ(instance.mesh.kind, MeshKind::Sphere);
    EXPECT_EQ(instance.material, "materials/standard_pbr.hlsl");
    EXPECT_EQ(instance.keywords, (std::vector<std::string>{"_GUARDED"}));
    EXPECT_EQ(instance.textures.at("_MainTex").source, TextureOrigin::Checker);
    EXPECT_EQ(instance.properties.at("_Color"), vec4_value(1, 0, 0, 1));
  }
}

TEST(SceneInstances, VectorPropertiesInterpolatePerComponent) {
  Scene scene = parse_ok(minimal_head + R"([[object]]
mesh = "sphere"
material = "m.hlsl"
grid = { rows = 1, cols = 3, spacing = 1, vary = { _Tint = { along = "cols", from = [0, 1, 2, 4], to = [2, 1, 0, 8] } } }
)");
  std::vector<ObjectInstance> instances = expand_instances(scene);
  ASSERT_EQ(instances.size(), 3u);
  EXPECT_EQ(instances[1].properties.at("_Tint"), vec4_value(1, 1, 1, 6));
  expect_vec(translation(instances[0].model), {-1, 0, 0});
}

TEST(SceneInstances, AOneByOneGridGivesFrom) {
  Scene scene = parse_ok(minimal_head + R"([[object]]
mesh = "sphere"
material = "m.hlsl"
position = [4, 5, 6]
grid = { rows = 1, cols = 1, spacing = 2, vary = { _A = { along = "rows", from = 0.3, to = 0.9 }, _B = { along = "cols", from = 7, to = 9 } } }
)");
  std::vector<ObjectInstance> instances = expand_instances(scene);
  ASSERT_EQ(instances.size(), 1u);
  EXPECT_EQ(instances[0].properties.at("_A"), PropertyValue::scalar(0.3f));
  EXPECT_EQ(instances[0].properties.at("_B"), PropertyValue::scalar(7.0f));
  expect_vec(translation(instances[0].model), {4, 5, 6});
}

TEST(SceneInstances, ObjectsWithoutAGridGiveOneInstanceEach) {
  Scene scene = parse_ok(minimal_head + R"([[object]]
mesh = "cube"
material = "a.hlsl"
[[object]]
name = "floor"
mesh = "plane"
material = "b.hlsl"
position = [0, -1, 0]
)");
  std::vector<ObjectInstance> instances = expand_instances(scene);
  ASSERT_EQ(instances.size(), 2u);
  EXPECT_EQ(instances[0].object_name, "object0");
  EXPECT_FALSE(instances[0].in_grid);
  EXPECT_EQ(instances[1].object_name, "floor");
  EXPECT_EQ(instances[1].object_index, 1u);
  EXPECT_EQ(instances[1].mesh.kind, MeshKind::Plane);
  expect_vec(translation(instances[1].model), {0, -1, 0});
}

TEST(SceneInstances, ModelMatrixScalesThenRotatesXThenYThenZThenTranslates) {
  glm::mat4 model = model_matrix({10, 20, 30}, {90, 90, 0}, {2, 2, 2});
  // (0, 1, 0) scaled to (0, 2, 0); X by 90 degrees takes +y to +z; Y by 90 takes +z to +x.
  glm::vec4 moved = model * glm::vec4(0, 1, 0, 1);
  EXPECT_NEAR(moved.x, 12.0f, 1e-5f);
  EXPECT_NEAR(moved.y, 20.0f, 1e-5f);
  EXPECT_NEAR(moved.z, 30.0f, 1e-5f);
  // Z by 90 takes +x to +y.
  glm::vec4 turned = model_matrix({0, 0, 0}, {0, 0, 90}, {1, 1, 1}) * glm::vec4(1, 0, 0, 0);
  EXPECT_NEAR(turned.x, 0.0f, 1e-6f);
  EXPECT_NEAR(turned.y, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace xshade::harness
