// Scenes: the TOML file format (docs/scenes.md) read into plain data, and objects expanded into
// the instances a renderer draws.
//
// The model knows nothing about rendering. Paths the scene file names (an equirect image, an .obj
// mesh, texture images) are resolved against the scene file's folder and checked for form only;
// nothing here opens them. Material and post-effect paths stay as written: they are relative to
// the shader folders (a user's, then the library; harness/shader_search_path.h), which the caller knows.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "base/result.h"
#include "harness/image/image_compare.h"    // CompareSettings
#include "shaderlab/compile_environment.h"  // UnityPlatform

namespace xshade::harness {

// A material property or post-effect parameter: a float, float2, float3 or float4.
struct PropertyValue {
  std::array<float, 4> components{};
  uint32_t count = 1;  // 1..4

  static PropertyValue scalar(float value) { return {{value, 0.0f, 0.0f, 0.0f}, 1}; }
  // The components padded with zeros, for uploads that always write a float4.
  glm::vec4 as_vec4() const { return {components[0], components[1], components[2], components[3]}; }
  bool operator==(const PropertyValue&) const = default;
};

struct Camera {
  glm::vec3 position{0.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_degrees = 0.0f;  // vertical, in (0, 180)
  float near_plane = 0.0f;     // > 0
  float far_plane = 0.0f;      // > near_plane
};

enum class LightType { Directional, Point, Spot };

// A light as Unity's built-in forward renderer has one (docs/scenes.md, [[light]]).
struct Light {
  LightType type = LightType::Directional;
  glm::vec3 direction{
      0.0f, 1.0f,
      0.0f};  // unit length, pointing toward the light (the shaders' l); a spot's points back along its axis
  glm::vec3 position{0.0f};  // Point, Spot
  float range = 10.0f;       // Point, Spot: where its light ends
  float spot_angle = 30.0f;  // Spot: the cone's full angle, in degrees, in (0, 180)
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  // Shadows, as Unity's Light has them (a directional or spot light's): none, hard (one
  // comparison per pixel) or soft (the 2x2 comparisons weighted bilinearly, and Unity's
  // SHADOWS_SOFT; not on the vk-hlsl lane, which the reader refuses); strength 0..1;
  // the depth and normal biases in shadow-map texels (xshade's unit: Unity's internal scale of
  // its Bias and Normal Bias is not published; one texel of each keeps a lit surface facing the
  // light free of acne at any angle the normal offset leaves); the shadow map's size.
  enum class Shadows { None, Hard, Soft } shadows = Shadows::None;
  float shadow_strength = 1.0f;
  float shadow_bias = 1.0f;
  float shadow_normal_bias = 1.0f;
  uint32_t shadow_resolution = 1024;
  // How much it lights: Unity ranks pixel lights by it (the colour's luminance times the
  // intensity).
  float brightness() const { return (0.2126f * color.r + 0.7152f * color.g + 0.0722f * color.b) * intensity; }
};

enum class EnvironmentKind {
  Constant,  // one colour in every direction
  Gradient,  // sky above, horizon at y = 0, ground below
  Equirect,  // an equirectangular image
};

struct EnvironmentSpec {
  EnvironmentKind kind = EnvironmentKind::Constant;
  glm::vec3 color{0.0f};  // Constant; the default environment is constant black
  glm::vec3 sky{0.0f};    // Gradient
  glm::vec3 horizon{0.0f};
  glm::vec3 ground{0.0f};
  std::filesystem::path file;  // Equirect: absolute and normalised, inside the scene's folder
  float intensity = 1.0f;
};

// Unity's fog (RenderSettings): its modes, colour and distances as the Lighting window sets them,
// each with Unity's default. A scene with fog draws every shader that has Unity's fog keywords
// (multi_compile_fog) with the mode's keyword; a scene without draws them without.
enum class FogMode { Linear, Exponential, ExponentialSquared };
struct FogSpec {
  FogMode mode = FogMode::ExponentialSquared;
  glm::vec4 color{0.5f, 0.5f, 0.5f, 1.0f};  // linear RGBA, as unity_FogColor holds it
  float density = 0.01f;                    // Exponential and ExponentialSquared
  float start = 0.0f, end = 300.0f;         // Linear: distances from the camera
};
// The keyword Unity's shaders test for `mode` (FOG_LINEAR, FOG_EXP, FOG_EXP2).
const char* fog_keyword(FogMode mode);

enum class MeshKind { Sphere, Torus, Plane, Cube, ObjFile };

struct MeshRef {
  MeshKind kind = MeshKind::Sphere;
  std::filesystem::path file;  // ObjFile: absolute and normalised, inside the scene's folder
  SourceLocation where;        // the value in the scene file, for errors found when the mesh is read

  // The same mesh, wherever the scene names it.
  bool operator==(const MeshRef& other) const { return kind == other.kind && file == other.file; }
};

enum class TextureOrigin {
  White,        // (1, 1, 1, 1)
  Black,        // (0, 0, 0, 1)
  Checker,      // a black-and-white checkerboard
  Normal,       // a flat tangent-space normal map, (0.5, 0.5, 1, 1)
  Gray,         // (0.5, 0.5, 0.5, 0.5): Unity's "gray", and what it gives a texture whose default is ""
  Red,          // (1, 0, 0, 0): Unity's "red"
  Clear,        // (0, 0, 0, 0): Unity's "black"
  File,         // an image file (or a .cube LUT), read as the shader's texture shape asks
  Faces,        // six image files, a cube map's faces
  Environment,  // the scene's environment as a cube map
};

// What a scene gives a shader's texture. What the data becomes depends on the shape the shader
// declares (docs/scenes.md): a 2D image; for a cube, an equirect image, six faces or the
// environment; for a 3D texture, a LUT strip or a .cube file.
struct TextureRef {
  TextureOrigin source = TextureOrigin::White;
  std::filesystem::path file;                // File: absolute and normalised, inside the scene's folder
  std::vector<std::filesystem::path> faces;  // Faces: +x, -x, +y, -y, +z, -z, each like `file`
  bool srgb = true;      // an 8-bit file's colour is sRGB-encoded (Unity's default); false: linear data
  SourceLocation where;  // the value in the scene file, for errors found when the texture is made

  // The same texture, wherever the scene names it.
  bool operator==(const TextureRef& other) const {
    return source == other.source && file == other.file && faces == other.faces && srgb == other.srgb;
  }
};

// What a scene gives a shader's read-only buffer (StructuredBuffer, ByteAddressBuffer, Buffer):
// numbers written in the scene, each becoming one 32-bit word of the type the element declares at
// that place (float, int, uint or bool: 0 or 1), elements one after another; or a file of the
// buffer's bytes as Direct3D lays them out (little-endian words, a structured buffer's elements
// packed tightly).
struct BufferRef {
  std::vector<double> numbers;
  std::filesystem::path file;  // absolute and normalised, inside the scene's folder; empty: the numbers
  SourceLocation where;        // the value in the scene file

  // The same buffer, wherever the scene names it.
  bool operator==(const BufferRef& other) const { return numbers == other.numbers && file == other.file; }
};

// A buffer file's bytes at most: a scene's data, not a dataset (lavapipe's storage-buffer range is
// 128 MiB; what a test scene reads fits in far less).
inline constexpr uintmax_t kMaxSceneBufferBytes = uintmax_t(16) << 20;

// Where a scene file names each thing it gives a shader, so that a name the shader does not have
// is reported at the name: "material", "effect", "properties.NAME", "parameters.NAME",
// "keywords.NAME", "textures.NAME", "buffers.NAME", "grid.vary.NAME". A key it lacks answers `fallback`.
struct SceneLocations {
  std::map<std::string, SourceLocation> at;
  SourceLocation fallback;  // the object's or the effect's table

  const SourceLocation& of(const std::string& key) const {
    auto found = at.find(key);
    return found != at.end() ? found->second : fallback;
  }
};

// The built-in texture a scene value names ("white", "black", "checker", "normal", "gray", "red",
// "clear", "environment").
std::optional<TextureOrigin> built_in_texture(std::string_view name);

enum class GridAxis { Rows, Cols };

// A property that changes linearly over a grid: from at index 0, to at the last index.
struct VaryRule {
  GridAxis along = GridAxis::Cols;
  PropertyValue from;
  PropertyValue to;  // has as many components as from
};

struct GridSpec {
  uint32_t rows = 1;        // 1..64; row 0 is the top row
  uint32_t cols = 1;        // 1..64; column 0 is the leftmost
  glm::vec2 spacing{1.0f};  // distance between neighbouring centres along x (cols) and y (rows)
  std::map<std::string, VaryRule> vary;
};

struct SceneObject {
  std::string name;  // unique in the scene; "object<N>" when not given
  MeshRef mesh;
  std::string material;  // relative to the shader folders, as written
  std::vector<std::string> keywords;
  glm::vec3 position{0.0f};
  glm::vec3 rotation_degrees{0.0f};  // Euler angles, applied X, then Y, then Z
  glm::vec3 scale{1.0f};             // each component > 0
  std::map<std::string, PropertyValue> properties;
  std::map<std::string, TextureRef> textures;
  std::map<std::string, BufferRef> buffers;
  std::optional<GridSpec> grid;
  SceneLocations where;
};

// One blit of a Unity .shader post effect (`passes` of a [[post]]), as a C# script calls
// Graphics.Blit(source, destination, material, pass): the pass by its index or Name, into an image
// of its own that later steps read by the step's name.
struct PostStep {
  std::string pass;   // the pass's index ("0", "1", ...) or Name, as written
  std::string name;   // what later steps call its image; empty: the pass as written
  bool half = false;  // at half the scene's size
  // Each texture's source: "scene.color", "scene.depth" or an earlier step's name. _MainTex that
  // is not given reads the step before (the image the effect receives, for the first).
  std::map<std::string, std::string> sources;
  SourceLocation where;
};

struct PostEffect {
  std::string effect;  // relative to the shader folders, as written
  std::vector<std::string> keywords;
  std::map<std::string, PropertyValue> parameters;
  // Textures its passes sample that their #pragma pass lines give no source (a LUT, a noise).
  std::map<std::string, TextureRef> textures;
  // A .shader effect's blits in order; none written: its first pass alone.
  std::vector<PostStep> passes;
  SceneLocations where;
};

struct Scene {
  std::string name;            // the file's stem
  std::filesystem::path path;  // the file as it was named to the loader
  std::string description;
  uint32_t width = 0;              // 1..4096
  uint32_t height = 0;             // 1..4096
  std::vector<std::string> lanes;  // a subset of "gl", "vk", "vk-hlsl" in the order written
  // Each lane's render stops after this long instead of the run's --timeout; set with a reason.
  std::optional<double> timeout_seconds = std::nullopt;
  std::string timeout_reason;
  glm::vec4 clear_color{0.0f, 0.0f, 0.0f, 1.0f};
  // The time since the level loaded that the frame shows, in seconds (Unity's _Time.y).
  float time_seconds = 0.0f;
  Camera camera;
  std::vector<Light> lights;
  EnvironmentSpec environment;
  std::optional<FogSpec> fog;
  // [unity] platform: the Unity platform the .shader files compile and draw as (docs/unity.md).
  shaderlab::UnityPlatform unity_platform = shaderlab::UnityPlatform::GLCore;
  // [unity] pixel_lights: how many lights besides the main directional one light per pixel, each
  // in an object's ForwardAdd pass (Unity's Quality setting, 4 by default); the rest light per
  // vertex in ForwardBase, up to four point lights.
  int pixel_lights = 4;
  std::vector<SceneObject> objects;
  std::vector<PostEffect> post;
  CompareSettings compare;
};

// Reads and validates a scene file. On failure the error's message and location are those of
// the first problem (in file order); its diagnostics hold every problem found, the first
// included, each as "file:line:col: error: key.path: what was expected, got what was found".
Result<Scene> load_scene(const std::filesystem::path& file);
// The same for text already in memory; `file` names it in messages and anchors relative paths.
Result<Scene> parse_scene(std::string_view text, const std::filesystem::path& file);

// A scene file's bytes: the largest scene xshade ships is a few kilobytes, and a generated one of
// kMaxSceneDraws objects about 2 MB; TOML's parser holds several times the text, so 16 MiB keeps
// a mistaken or hostile file (a link to a log, a sparse file) from being read at all.
inline constexpr size_t kMaxSceneFileBytes = size_t(16) << 20;

// What a scene may ask a renderer to do. A 60 KB file of 1000 objects, each a 64 x 64 grid, is
// 4 million instances: expanding and drawing them took 5.5 GB and minutes before anything was
// said. Both budgets are checked as the scene is read, before any object is expanded.
//
// Draws: each object without a grid is one, each cell of a grid one, each post effect at least
// one. The fixed scenes draw at most 26; 16384 is four full 64 x 64 grids. Each draw carries its
// instance (names, properties, textures: about a kilobyte) and its uniform block through the plan
// and the render on every lane, so this keeps a scene's draws to tens of megabytes.
inline constexpr uint64_t kMaxSceneDraws = 16384;
// Draws times the frame's pixels: the fragments a scene could shade if every draw covered the
// frame. The fixed scenes stay below 3 million; 2^32 is a 64 x 64 grid at 1024 x 1024, which at
// llvmpipe's hundred million fragments a second on two cores is already about a minute a render,
// and a run renders each lane twice.
inline constexpr uint64_t kMaxScenePixelDraws = uint64_t(1) << 32;

// Refuses a scene over either budget, at the object or post effect whose draws pass it, naming
// the totals and the limit. load_scene and parse_scene apply it; the planner checks again, for
// scenes made in code.
Result<void> check_scene_work(const Scene& scene);

// One drawable copy of an object: an object without a grid gives one, a grid rows x cols.
struct ObjectInstance {
  std::string object_name;
  size_t object_index = 0;  // into Scene::objects
  bool in_grid = false;
  uint32_t row = 0;  // the grid cell, for labels; 0, 0 outside a grid
  uint32_t col = 0;
  glm::mat4 model{1.0f};  // translate * rotate (X, then Y, then Z) * scale
  MeshRef mesh;
  std::string material;
  std::vector<std::string> keywords;
  std::map<std::string, TextureRef> textures;
  std::map<std::string, BufferRef> buffers;
  std::map<std::string, PropertyValue> properties;  // the object's, then the grid's vary rules
};

// Every object's instances in scene order; within a grid, row by row from the top.
std::vector<ObjectInstance> expand_instances(const Scene& scene);

// The model matrix of an object placed at `position` (the grid offset already added).
glm::mat4 model_matrix(const glm::vec3& position, const glm::vec3& rotation_degrees, const glm::vec3& scale);

}  // namespace xshade::harness
