// Why this file is long: it reads every table of the scene format (docs/scenes.md), one reader
// method per table, each checking its keys where they are written; split, each table would reach
// into the same reporting state.
#include "harness/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <set>
#include <system_error>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "base/file_io.h"
#include "base/paths.h"
#include "harness/image/image_limits.h"
#include "harness/scene/lane.h"
#include "harness/scene/scene_values.h"
#include "harness/scene/toml_reader.h"

namespace xshade::harness {
namespace {

using namespace toml_text;

constexpr int64_t max_grid_cells_per_axis = 64;
// Every lane's name, in lane order (scene/lane.h).
const std::vector<std::string_view>& lane_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> all;
    for (Lane lane : all_lanes()) all.push_back(lane_name(lane));
    return all;
  }();
  return names;
}

// Reads one scene file's table tree into a Scene, collecting every problem it can find.
class SceneReader : SceneValueReader {
 public:
  explicit SceneReader(const std::filesystem::path& file) : SceneValueReader(file), file_(file) {}

  Result<Scene> read(std::string_view text) {
    std::optional<toml::table> root = parse(text);
    if (!root) return finish(Scene{});
    Scene scene;
    scene.name = file_.stem().string();
    scene.path = file_;
    read_root(*root, scene);
    if (Result<void> work = check_scene_work(scene); !work) report(work.error().where, work.error().message);
    return finish(std::move(scene));
  }

 private:
  // ---- the sections

  void read_root(const toml::table& root, Scene& scene) {
    check_keys(root, "",
               {"description", "size", "lanes", "clear_color", "time", "camera", "light", "environment", "fog", "unity",
                "object", "post", "compare", "timeout", "timeout_reason"});

    if (const toml::node* node = root.get("description")) {
      if (auto text = string(*node, "description", "a non-empty string")) scene.description = *text;
    } else {
      missing(root, "description", "a string saying what the scene shows");
    }

    if (const toml::node* node = root.get("size"))
      read_size(*node, scene);
    else
      missing(root, "size", "[width, height] in pixels");

    if (const toml::node* node = root.get("lanes"))
      read_lanes(*node, scene);
    else
      scene.lanes.assign(lane_names().begin(), lane_names().end());

    if (const toml::node* node = root.get("clear_color")) {
      if (auto value = vector<4>(*node, "clear_color", "a number >= 0", non_negative)) scene.clear_color = *value;
    }
    if (const toml::node* node = root.get("time")) {
      if (auto value = float_value(*node, "time", "a number of seconds >= 0", non_negative))
        scene.time_seconds = *value;
    }

    read_timeout(root, scene);

    if (const toml::table* camera = table(root, "", "camera", true)) read_camera(*camera, scene.camera);

    std::vector<const toml::table*> lights = table_array(root, "light");
    for (size_t i = 0; i < lights.size(); ++i) read_light(*lights[i], index_path("light", i), scene);

    if (const toml::table* environment = table(root, "", "environment", false))
      read_environment(*environment, scene.environment);
    if (const toml::table* fog = table(root, "", "fog", false)) read_fog(*fog, scene.fog.emplace());
    const toml::table* unity = table(root, "", "unity", false);
    if (unity) read_unity(*unity, scene);

    std::vector<const toml::table*> objects = table_array(root, "object");
    for (size_t i = 0; i < objects.size(); ++i) read_object(*objects[i], i, scene);

    std::vector<const toml::table*> effects = table_array(root, "post");
    for (size_t i = 0; i < effects.size(); ++i) read_post(*effects[i], index_path("post", i), scene);

    if (const toml::table* compare = table(root, "", "compare", false)) read_compare(*compare, scene);
    if (unity) check_unity_platform(*unity, scene);
  }

  // The Unity platform the scene's .shader files compile and draw as.
  void read_unity(const toml::table& table, Scene& scene) {
    check_keys(table, "unity", {"platform", "pixel_lights"});
    if (const toml::node* node = table.get("pixel_lights")) {
      const auto* count = node->as_integer();
      if (count && count->get() >= 0 && count->get() <= 8)
        scene.pixel_lights = static_cast<int>(count->get());
      else
        expected(*node, "unity.pixel_lights", "a whole number from 0 to 8");
    }
    if (const toml::node* node = table.get("platform")) {
      auto name = node->as_string();
      auto platform = name ? shaderlab::parse_unity_platform(name->get()) : std::nullopt;
      if (platform)
        scene.unity_platform = *platform;
      else
        expected(*node, "unity.platform", "\"glcore\", \"d3d11\" or \"vulkan\"");
    }
  }

  // A platform of Direct3D's conventions flips the scene's targets and reverses its depth for every
  // draw; xshade's own .hlsl shaders are written for the renderer's conventions and know nothing of
  // Unity's macros, so a scene that draws one keeps GLCore.
  void check_unity_platform(const toml::table& table, const Scene& scene) {
    if (scene.unity_platform == shaderlab::UnityPlatform::GLCore) return;
    const toml::node* node = table.get("platform");
    const auto refuse = [&](const std::string& what, const std::string& path) {
      report(node->source(),
             fmt::format("unity.platform: \"{}\" is for scenes whose materials and effects are all Unity "
                         ".shader files, and {} is '{}', an .hlsl shader written for xshade's own "
                         "conventions: remove the platform, or draw it in a scene of its own",
                         shaderlab::renderer_name(scene.unity_platform), what, path));
    };
    for (const SceneObject& object : scene.objects)
      if (!object.material.ends_with(".shader"))
        return refuse("object '" + object.name + "''s material", object.material);
    for (const PostEffect& effect : scene.post)
      if (!effect.effect.ends_with(".shader")) return refuse("a post effect", effect.effect);
  }

  // A scene's own time limit for each lane's render, in place of the run's, with why it needs it.
  void read_timeout(const toml::table& root, Scene& scene) {
    const toml::node* timeout = root.get("timeout");
    const toml::node* reason = root.get("timeout_reason");
    if (timeout) {
      // An hour: a render slower than that is no gate anyone waits for.
      if (auto seconds = number(*timeout, "timeout", "a number of seconds in (0, 3600]",
                                [](double value) { return value > 0.0 && value <= 3600.0; }))
        scene.timeout_seconds = *seconds;
      if (!reason) missing(root, "timeout_reason", "a string saying why the scene needs longer than a run allows");
    }
    if (reason) {
      if (auto text = string(*reason, "timeout_reason", "a non-empty string")) scene.timeout_reason = *text;
      if (!timeout)
        report(reason->source(),
               "timeout_reason: there is no timeout for it to explain; set timeout = SECONDS or remove it");
    }
  }

  void read_size(const toml::node& node, Scene& scene) {
    auto* array = node.as_array();
    if (!array || array->size() != 2) {
      expected(node, "size", "[width, height]");
      return;
    }
    auto width = integer(*array->get(0), "size[0]", 1, kMaxRenderSize);
    auto height = integer(*array->get(1), "size[1]", 1, kMaxRenderSize);
    if (width) scene.width = static_cast<uint32_t>(*width);
    if (height) scene.height = static_cast<uint32_t>(*height);
  }

  void read_lanes(const toml::node& node, Scene& scene) {
    auto* array = node.as_array();
    if (!array || array->empty()) {
      expected(node, "lanes", "a non-empty array of lane names (gl, vk, vk-hlsl)");
      return;
    }
    for (size_t i = 0; i < array->size(); ++i) {
      const toml::node& element = *array->get(i);
      std::string path = index_path("lanes", i);
      auto* name = element.as_string();
      if (!name || std::find(lane_names().begin(), lane_names().end(), name->get()) == lane_names().end()) {
        std::string message =
            fmt::format("{}: expected one of {}, got {}", path, fmt::join(lane_names(), ", "), describe(element));
        if (name) {
          if (auto suggestion = nearest(name->get(), lane_names()))
            message += fmt::format("; did you mean \"{}\"?", *suggestion);
        }
        report(element.source(), std::move(message));
        continue;
      }
      if (std::find(scene.lanes.begin(), scene.lanes.end(), name->get()) != scene.lanes.end()) {
        report(element.source(), fmt::format("{}: lane \"{}\" is listed twice", path, name->get()));
        continue;
      }
      scene.lanes.push_back(name->get());
    }
  }

  void read_camera(const toml::table& table, Camera& camera) {
    check_keys(table, "camera", {"position", "target", "up", "fov_y", "near", "far"});
    bool placed = true;  // position, target and up read well enough to check them against each other
    auto required_point = [&](std::string_view key, glm::vec3& out) {
      std::string path = key_path("camera", key);
      if (const toml::node* node = table.get(key)) {
        if (auto value = point(*node, path))
          out = *value;
        else
          placed = false;
      } else {
        missing(table, path, "an array of 3 numbers");
        placed = false;
      }
    };
    required_point("position", camera.position);
    required_point("target", camera.target);
    const toml::node* up = table.get("up");
    if (up) {
      if (auto value = point(*up, "camera.up"))
        camera.up = *value;
      else
        placed = false;
    }
    if (placed) {
      glm::vec3 view = camera.target - camera.position;
      if (glm::length(view) == 0.0f) {
        report(table.get("target")->source(),
               "camera.target: expected a point other than camera.position, got the same point");
      } else if (glm::length(glm::cross(view, camera.up)) <= 1e-6f * glm::length(view) * glm::length(camera.up)) {
        report(up ? up->source() : table.source(),
               fmt::format("camera.up: expected a direction not parallel to the view direction, got [{}, {}, {}]",
                           camera.up.x, camera.up.y, camera.up.z));
      }
    }

    if (const toml::node* node = table.get("fov_y")) {
      if (auto value =
              float_value(*node, "camera.fov_y", "a number in (0, 180)", [](double v) { return v > 0.0 && v < 180.0; }))
        camera.fov_y_degrees = *value;
    } else {
      missing(table, "camera.fov_y", "a number in (0, 180)");
    }

    std::optional<double> near;
    if (const toml::node* node = table.get("near")) {
      near = number(*node, "camera.near", "a number > 0", positive);
      if (near) camera.near_plane = static_cast<float>(*near);
    } else {
      missing(table, "camera.near", "a number > 0");
    }
    if (const toml::node* node = table.get("far")) {
      double near_value = near.value_or(0.0);
      std::string expectation =
          near ? fmt::format("a number greater than camera.near ({})", *near) : std::string("a number > 0");
      if (auto far = float_value(*node, "camera.far", expectation, [&](double v) { return v > near_value; }))
        camera.far_plane = *far;
    } else {
      missing(table, "camera.far", "a number greater than camera.near");
    }
  }

  void read_light(const toml::table& table, const std::string& path, Scene& scene) {
    check_keys(table, path,
               {"type", "direction", "position", "range", "spot_angle", "color", "intensity", "shadows",
                "shadow_strength", "shadow_bias", "shadow_normal_bias", "shadow_resolution"});
    Light light;
    bool ok = true;
    const char* const types = "\"directional\", \"point\" or \"spot\"";
    if (const toml::node* node = table.get("type")) {
      auto* type = node->as_string();
      if (type && type->get() == "directional")
        light.type = LightType::Directional;
      else if (type && type->get() == "point")
        light.type = LightType::Point;
      else if (type && type->get() == "spot")
        light.type = LightType::Spot;
      else {
        expected(*node, path + ".type", types);
        ok = false;
      }
    } else {
      missing(table, path + ".type", types);
      ok = false;
    }
    const bool positioned = light.type != LightType::Directional;
    const bool aimed = light.type != LightType::Point;
    // Each key belongs to the kinds of light that have it.
    const auto not_for = [&](const char* key, const char* kinds) {
      if (const toml::node* node = table.get(key)) {
        report(node->source(), fmt::format("{}.{} is for {} lights; a {} light has none", path, key, kinds,
                                           light.type == LightType::Directional ? "directional"
                                           : light.type == LightType::Point     ? "point"
                                                                                : "spot"));
        ok = false;
      }
    };
    if (!aimed) not_for("direction", "directional and spot");
    if (!positioned) {
      not_for("position", "point and spot");
      not_for("range", "point and spot");
    }
    if (light.type != LightType::Spot) not_for("spot_angle", "spot");
    if (const toml::node* node = aimed ? table.get("direction") : nullptr) {
      auto direction = point(*node, path + ".direction");
      if (direction && glm::length(*direction) == 0.0f) {
        expected(*node, path + ".direction", "a non-zero vector");
        direction.reset();
      }
      if (direction)
        light.direction = glm::normalize(*direction);
      else
        ok = false;
    } else if (aimed) {
      missing(table, path + ".direction", "an array of 3 numbers pointing toward the light");
      ok = false;
    }
    if (const toml::node* node = positioned ? table.get("position") : nullptr) {
      if (auto position = point(*node, path + ".position"))
        light.position = *position;
      else
        ok = false;
    } else if (positioned) {
      missing(table, path + ".position", "an array of 3 numbers");
      ok = false;
    }
    if (positioned)
      ok &= optional_float(
          table, "range", path, "a number > 0", [](double v) { return v > 0.0; }, light.range);
    if (light.type == LightType::Spot)
      ok &= optional_float(
          table, "spot_angle", path, "a number of degrees in (0, 180)", [](double v) { return v > 0.0 && v < 180.0; },
          light.spot_angle);
    if (const toml::node* node = table.get("color")) {
      if (auto value = colour(*node, path + ".color")) light.color = *value;
    }
    optional_float(table, "intensity", path, "a number >= 0", non_negative, light.intensity);
    read_shadows(table, path, scene.lanes, light, ok);
    if (ok) scene.lights.push_back(light);
  }

  void read_shadows(const toml::table& table, const std::string& path, const std::vector<std::string>& lanes,
                    Light& light, bool& ok) {
    if (const toml::node* node = table.get("shadows")) {
      auto* mode = node->as_string();
      if (mode && mode->get() == "none")
        light.shadows = Light::Shadows::None;
      else if (mode && mode->get() == "hard")
        light.shadows = Light::Shadows::Hard;
      else if (mode && mode->get() == "soft")
        light.shadows = Light::Shadows::Soft;
      else {
        expected(*node, path + ".shadows", "\"none\", \"hard\" or \"soft\"");
        ok = false;
      }
      if (ok && light.shadows == Light::Shadows::Soft &&
          std::find(lanes.begin(), lanes.end(), "vk-hlsl") != lanes.end()) {
        report(node->source(),
               fmt::format(
                   "{}.shadows: \"soft\" is not drawn on the vk-hlsl lane: a soft shadow's comparisons are filtered "
                   "linearly, which lavapipe cannot do for a depth texture, and glslang's HLSL output cannot do "
                   "in the shader as xshade's does on vk; list the lanes without it (lanes = [\"gl\", \"vk\"]) or "
                   "use \"hard\"",
                   path));
        ok = false;
      }
      if (ok && light.shadows != Light::Shadows::None && light.type == LightType::Point) {
        report(node->source(),
               fmt::format("{}.shadows: a point light's shadows are not rendered yet (a cube map of six "
                           "views); directional and spot lights cast shadows",
                           path));
        ok = false;
      }
    }
    ok &= optional_float(
        table, "shadow_strength", path, "a number in [0, 1]", [](double v) { return v >= 0.0 && v <= 1.0; },
        light.shadow_strength);
    const auto bias_range = [](double v) { return v >= 0.0 && v <= 10.0; };
    ok &= optional_float(table, "shadow_bias", path, "a number of texels in [0, 10]", bias_range, light.shadow_bias);
    ok &= optional_float(table, "shadow_normal_bias", path, "a number of texels in [0, 10]", bias_range,
                         light.shadow_normal_bias);
    if (const toml::node* node = table.get("shadow_resolution")) {
      const auto* size = node->as_integer();
      const int64_t n = size ? size->get() : 0;
      if (n >= 64 && n <= 4096 && (n & (n - 1)) == 0)
        light.shadow_resolution = static_cast<uint32_t>(n);
      else {
        expected(*node, path + ".shadow_resolution", "a power of two from 64 to 4096");
        ok = false;
      }
    }
  }

  void read_fog(const toml::table& table, FogSpec& fog) {
    check_keys(table, "fog", {"mode", "color", "density", "start", "end"});
    const char* const modes = "\"linear\", \"exponential\" or \"exponential_squared\"";
    if (const toml::node* node = table.get("mode")) {
      const auto* name = node->as_string();
      if (name && name->get() == "linear")
        fog.mode = FogMode::Linear;
      else if (name && name->get() == "exponential")
        fog.mode = FogMode::Exponential;
      else if (name && name->get() == "exponential_squared")
        fog.mode = FogMode::ExponentialSquared;
      else
        expected(*node, "fog.mode", modes);
    }
    if (const toml::node* node = table.get("color")) {
      if (auto value = vector<4>(*node, "fog.color", "a number >= 0", non_negative)) fog.color = *value;
    }
    if (const toml::node* node = table.get("density")) {
      if (auto value = float_value(*node, "fog.density", "a number >= 0", non_negative)) fog.density = *value;
    }
    for (const auto& [key, out] : {std::pair{"start", &fog.start}, std::pair{"end", &fog.end}})
      if (const toml::node* node = table.get(key)) {
        if (auto value = float_value(*node, key_path("fog", key), "a distance >= 0", non_negative)) *out = *value;
      }
    // Unity divides by end - start.
    if (fog.mode == FogMode::Linear && fog.end <= fog.start)
      report(table.source(), fmt::format("fog: linear fog ends where it starts or before ({} to {}): give an end "
                                         "beyond the start",
                                         fog.start, fog.end));
  }

  void read_environment(const toml::table& table, EnvironmentSpec& environment) {
    const toml::node* kind_node = table.get("kind");
    std::optional<EnvironmentKind> kind;
    if (!kind_node) {
      missing(table, "environment.kind", "\"constant\", \"gradient\" or \"equirect\"");
    } else if (auto* name = kind_node->as_string(); name && name->get() == "constant") {
      kind = EnvironmentKind::Constant;
    } else if (name && name->get() == "gradient") {
      kind = EnvironmentKind::Gradient;
    } else if (name && name->get() == "equirect") {
      kind = EnvironmentKind::Equirect;
    } else {
      expected(*kind_node, "environment.kind", "\"constant\", \"gradient\" or \"equirect\"");
    }

    if (!kind) {
      check_keys(table, "environment", {"kind", "color", "sky", "horizon", "ground", "file", "intensity"});
    } else if (*kind == EnvironmentKind::Constant) {
      check_keys(table, "environment", {"kind", "color", "intensity"}, " for kind \"constant\"");
    } else if (*kind == EnvironmentKind::Gradient) {
      check_keys(table, "environment", {"kind", "sky", "horizon", "ground", "intensity"}, " for kind \"gradient\"");
    } else {
      check_keys(table, "environment", {"kind", "file", "intensity"}, " for kind \"equirect\"");
    }
    if (kind) environment.kind = *kind;

    auto required_colour = [&](std::string_view key, glm::vec3& out) {
      std::string path = key_path("environment", key);
      if (const toml::node* node = table.get(key)) {
        if (auto value = colour(*node, path)) out = *value;
      } else {
        missing(table, path, "an array of 3 numbers >= 0");
      }
    };
    if (kind == EnvironmentKind::Constant) required_colour("color", environment.color);
    if (kind == EnvironmentKind::Gradient) {
      required_colour("sky", environment.sky);
      required_colour("horizon", environment.horizon);
      required_colour("ground", environment.ground);
    }
    if (kind == EnvironmentKind::Equirect) {
      if (const toml::node* node = table.get("file")) {
        if (auto text = string(*node, "environment.file", "an image path relative to the scene file")) {
          if (auto file = scene_file_path(*node, "environment.file", *text)) environment.file = *file;
        }
      } else {
        missing(table, "environment.file", "an image path relative to the scene file");
      }
    }
    if (const toml::node* node = table.get("intensity")) {
      if (auto value = float_value(*node, "environment.intensity", "a number >= 0", non_negative))
        environment.intensity = *value;
    }
  }

  std::optional<MeshRef> mesh(const toml::node& node, std::string_view path) {
    constexpr std::string_view expectation = "sphere, torus, plane, cube or a path ending in .obj";
    auto* text = node.as_string();
    if (!text) {
      expected(node, path, expectation);
      return std::nullopt;
    }
    const std::string& name = text->get();
    if (name == "sphere") return MeshRef{MeshKind::Sphere, {}, where(node.source())};
    if (name == "torus") return MeshRef{MeshKind::Torus, {}, where(node.source())};
    if (name == "plane") return MeshRef{MeshKind::Plane, {}, where(node.source())};
    if (name == "cube") return MeshRef{MeshKind::Cube, {}, where(node.source())};
    if (name.size() > 4 && name.ends_with(".obj")) {
      auto file = scene_file_path(node, path, name);
      if (!file) return std::nullopt;
      return MeshRef{MeshKind::ObjFile, *file, where(node.source())};
    }
    std::string message = fmt::format("{}: expected {}, got {}", path, expectation, quote_text(name));
    if (auto suggestion = nearest(name, {"sphere", "torus", "plane", "cube"}))
      message += fmt::format("; did you mean \"{}\"?", *suggestion);
    report(node.source(), std::move(message));
    return std::nullopt;
  }

  static constexpr std::string_view texture_expectation =
      "white, black, checker, normal, gray, red, clear, environment, an image path or a table (file or faces)";

  std::optional<TextureRef> texture(const toml::node& node, std::string_view path) {
    if (const toml::table* table = node.as_table()) return texture_table(*table, std::string(path));
    auto* text = node.as_string();
    if (!text) {
      expected(node, path, texture_expectation);
      return std::nullopt;
    }
    TextureRef reference;
    reference.where = where(node.source());
    const std::string& name = text->get();
    if (auto origin = built_in_texture(name)) {
      reference.source = *origin;
      return reference;
    }
    // A file is told from a misspelt built-in by its extension.
    if (std::filesystem::path(name).has_extension()) {
      auto file = scene_file_path(node, path, name);
      if (!file) return std::nullopt;
      reference.source = TextureOrigin::File;
      reference.file = *file;
      return reference;
    }
    std::string message = fmt::format("{}: expected {}, got {}", path, texture_expectation, quote_text(name));
    if (auto suggestion = nearest(name, {"white", "black", "checker", "normal", "gray", "red", "clear", "environment"}))
      message += fmt::format("; did you mean \"{}\"?", *suggestion);
    report(node.source(), std::move(message));
    return std::nullopt;
  }

  // { file = "lut.png", srgb = false } or { faces = ["px.png", ...] }.
  std::optional<TextureRef> texture_table(const toml::table& table, const std::string& path) {
    check_keys(table, path, {"file", "faces", "srgb"});
    TextureRef reference;
    reference.where = where(table.source());
    bool ok = true;
    if (const toml::node* node = table.get("srgb")) {
      if (auto* flag = node->as_boolean()) {
        reference.srgb = flag->get();
      } else {
        expected(*node, path + ".srgb", "true (8-bit colour is sRGB-encoded) or false (linear data)");
        ok = false;
      }
    }
    const toml::node* file = table.get("file");
    const toml::node* faces = table.get("faces");
    if (file && faces) {
      report(faces->source(), fmt::format("{}: give either file or faces, not both", path));
      return std::nullopt;
    }
    if (file) {
      auto* text = file->as_string();
      auto resolved = text ? scene_file_path(*file, path + ".file", text->get()) : std::nullopt;
      if (!text) expected(*file, path + ".file", "an image path");
      if (!resolved) return std::nullopt;
      reference.source = TextureOrigin::File;
      reference.file = *resolved;
    } else if (faces) {
      auto* array = faces->as_array();
      if (!array || array->size() != 6) {
        expected(*faces, path + ".faces", "an array of 6 image paths: +x, -x, +y, -y, +z, -z");
        return std::nullopt;
      }
      reference.source = TextureOrigin::Faces;
      for (size_t i = 0; i < 6; ++i) {
        const toml::node& element = *array->get(i);
        const std::string element_path = index_path(path + ".faces", i);
        auto* text = element.as_string();
        if (!text) {
          expected(element, element_path, "an image path");
          ok = false;
          continue;
        }
        auto resolved = scene_file_path(element, element_path, text->get());
        if (!resolved) {
          ok = false;
          continue;
        }
        reference.faces.push_back(*resolved);
      }
    } else {
      missing(table, path + ".file", "an image path (or faces = [6 image paths])");
      return std::nullopt;
    }
    if (!ok) return std::nullopt;
    return reference;
  }

  void read_object(const toml::table& table, size_t index, Scene& scene) {
    std::string path = index_path("object", index);
    check_keys(table, path,
               {"name", "mesh", "material", "keywords", "position", "rotation", "scale", "properties", "textures",
                "buffers", "grid"});
    SceneObject object;
    object.name = fmt::format("object{}", index);
    object.where.fallback = where(table.source());
    const toml::node* name_node = table.get("name");
    if (name_node) {
      if (auto name = string(*name_node, path + ".name", "a non-empty string")) object.name = *name;
    }
    // A map, not a search of the objects before: a file of many thousand objects reads in
    // linear time.
    if (auto [earlier, added] = object_names_.emplace(object.name, index); !added) {
      report(
          name_node ? name_node->source() : table.source(),
          fmt::format("{}.name: {} is already the name of object[{}]", path, quote_text(object.name), earlier->second));
    }

    if (const toml::node* node = table.get("mesh")) {
      if (auto value = mesh(*node, path + ".mesh")) object.mesh = *value;
    } else {
      missing(table, path + ".mesh", "sphere, torus, plane, cube or a path ending in .obj");
    }
    if (const toml::node* node = table.get("material")) {
      if (auto value = library_path(*node, path + ".material")) object.material = *value;
      object.where.at["material"] = where(node->source());
    } else {
      missing(table, path + ".material", "a path in the shader folders, e.g. \"materials/standard_pbr.hlsl\"");
    }
    if (const toml::node* node = table.get("keywords")) object.keywords = keywords(*node, path + ".keywords");
    record_locations(table, object.where);
    if (const toml::node* node = table.get("position")) {
      if (auto value = point(*node, path + ".position")) object.position = *value;
    }
    if (const toml::node* node = table.get("rotation")) {
      if (auto value = point(*node, path + ".rotation")) object.rotation_degrees = *value;
    }
    if (const toml::node* node = table.get("scale")) read_scale(*node, path + ".scale", object.scale);
    if (const toml::node* node = table.get("properties")) object.properties = properties(*node, path + ".properties");
    if (const toml::node* node = table.get("textures")) read_textures(*node, path + ".textures", object.textures);
    if (const toml::node* node = table.get("buffers")) read_buffers(*node, path + ".buffers", object.buffers);
    if (const toml::node* node = table.get("grid")) {
      if (!node->is_table())
        expected(*node, path + ".grid", "a table");
      else
        object.grid = read_grid(*node->as_table(), path + ".grid", object.properties);
    }
    scene.objects.push_back(std::move(object));
  }

  // Positive only: a negative scale mirrors the mesh and turns its triangles' winding around,
  // which back-face culling would then remove.
  void read_scale(const toml::node& node, const std::string& path, glm::vec3& scale) {
    if (node.is_array()) {
      if (auto value = vector<3>(node, path, "a number > 0", positive)) scale = *value;
      return;
    }
    if (auto value = float_value(node, path, "a number > 0 or an array of 3 numbers > 0", positive))
      scale = glm::vec3(*value);
  }

  void read_textures(const toml::node& node, const std::string& path, std::map<std::string, TextureRef>& textures) {
    for_each_named(node, path, "a table of texture names", "a texture property name",
                   [&](const std::string& name, const toml::node& value, const std::string& name_path) {
                     if (auto reference = texture(value, name_path)) textures.emplace(name, *reference);
                   });
  }

  // NAME = [numbers] or NAME = "data.bin" (BufferRef).
  void read_buffers(const toml::node& node, const std::string& path, std::map<std::string, BufferRef>& buffers) {
    for_each_named(node, path, "a table of buffer names", "a buffer name",
                   [&](const std::string& name, const toml::node& value, const std::string& name_path) {
                     if (auto reference = buffer(value, name_path)) buffers.emplace(name, std::move(*reference));
                   });
  }

  std::optional<BufferRef> buffer(const toml::node& value, const std::string& path) {
    BufferRef reference;
    reference.where = where(value.source());
    if (auto* text = value.as_string()) {
      auto resolved = scene_file_path(value, path, text->get());
      if (!resolved) return std::nullopt;
      reference.file = *resolved;
      return reference;
    }
    auto* array = value.as_array();
    if (!array || array->empty()) {
      expected(value, path, "an array of numbers or the path of a file of the buffer's bytes");
      return std::nullopt;
    }
    for (const toml::node& element : *array) {
      auto number = element.value<double>();
      if (!number || element.is_boolean()) {
        expected(element, path, "numbers only");
        return std::nullopt;
      }
      reference.numbers.push_back(*number);
    }
    return reference;
  }

  std::optional<GridSpec> read_grid(const toml::table& table, const std::string& path,
                                    const std::map<std::string, PropertyValue>& base_properties) {
    check_keys(table, path, {"rows", "cols", "spacing", "vary"});
    GridSpec grid;
    bool ok = true;
    auto count = [&](std::string_view key, uint32_t& out) {
      std::string key_text = key_path(path, key);
      if (const toml::node* node = table.get(key)) {
        if (auto value = integer(*node, key_text, 1, max_grid_cells_per_axis))
          out = static_cast<uint32_t>(*value);
        else
          ok = false;
      } else {
        missing(table, key_text, fmt::format("an integer in 1..{}", max_grid_cells_per_axis));
        ok = false;
      }
    };
    count("rows", grid.rows);
    count("cols", grid.cols);
    if (const toml::node* node = table.get("spacing")) {
      std::string spacing_path = path + ".spacing";
      if (node->is_array()) {
        if (auto value = vector<2>(*node, spacing_path, "a number > 0", positive))
          grid.spacing = *value;
        else
          ok = false;
      } else if (auto value = float_value(*node, spacing_path, "a number > 0 or [dx, dy]", positive)) {
        grid.spacing = glm::vec2(*value);
      } else {
        ok = false;
      }
    } else {
      missing(table, path + ".spacing", "a number > 0 or [dx, dy]");
      ok = false;
    }
    if (const toml::node* node = table.get("vary")) {
      auto* vary = node->as_table();
      if (!vary) {
        expected(*node, path + ".vary", "a table of property = { along, from, to }");
        ok = false;
      } else {
        for (auto&& [key, value] : *vary) {
          std::string name(key.str());
          std::string rule_path = key_path(path + ".vary", name);
          if (!is_identifier(name)) {
            report(key.source(), fmt::format("{}: expected a property name (letters, digits and _)", rule_path));
            ok = false;
            continue;
          }
          auto rule = read_vary_rule(value, rule_path);
          if (!rule) {
            ok = false;
            continue;
          }
          auto base = base_properties.find(name);
          if (base != base_properties.end() && base->second.count != rule->from.count) {
            report(value.source(), fmt::format("{}: expected {} like the object's property, got {}", rule_path,
                                               numbers_text(base->second.count), numbers_text(rule->from.count)));
            ok = false;
            continue;
          }
          grid.vary.emplace(name, *rule);
        }
      }
    }
    if (!ok) return std::nullopt;
    return grid;
  }

  std::optional<VaryRule> read_vary_rule(const toml::node& node, const std::string& path) {
    auto* table = node.as_table();
    if (!table) {
      expected(node, path, "a table { along = \"rows\" or \"cols\", from = ..., to = ... }");
      return std::nullopt;
    }
    check_keys(*table, path, {"along", "from", "to"});
    VaryRule rule;
    bool ok = true;
    if (const toml::node* along = table->get("along")) {
      auto* text = along->as_string();
      if (text && text->get() == "rows") {
        rule.along = GridAxis::Rows;
      } else if (text && text->get() == "cols") {
        rule.along = GridAxis::Cols;
      } else {
        expected(*along, path + ".along", "\"rows\" or \"cols\"");
        ok = false;
      }
    } else {
      missing(*table, path + ".along", "\"rows\" or \"cols\"");
      ok = false;
    }
    auto end_value = [&](std::string_view key, PropertyValue& out) {
      std::string end_path = key_path(path, key);
      if (const toml::node* end = table->get(key)) {
        if (auto value = property_value(*end, end_path))
          out = *value;
        else
          ok = false;
      } else {
        missing(*table, end_path, "a number or an array of 2 to 4 numbers");
        ok = false;
      }
    };
    end_value("from", rule.from);
    end_value("to", rule.to);
    if (ok && rule.from.count != rule.to.count) {
      const toml::node& to = *table->get("to");
      expected(to, path + ".to", fmt::format("{} like from", numbers_text(rule.from.count)));
      ok = false;
    }
    if (!ok) return std::nullopt;
    return rule;
  }

  // Where each name the table gives a shader is written: the keys of its properties, parameters,
  // textures and grid.vary tables, and each keyword.
  void record_locations(const toml::table& table, SceneLocations& locations) {
    for (std::string_view group : {"properties", "parameters", "textures", "buffers"})
      if (const toml::table* names = table.get_as<toml::table>(group))
        for (auto&& [key, value] : *names)
          locations.at[std::string(group) + "." + std::string(key.str())] = where(key.source());
    if (const toml::table* grid = table.get_as<toml::table>("grid"))
      if (const toml::table* vary = grid->get_as<toml::table>("vary"))
        for (auto&& [key, value] : *vary) locations.at["grid.vary." + std::string(key.str())] = where(key.source());
    if (const toml::array* keywords = table.get_as<toml::array>("keywords"))
      for (const toml::node& keyword : *keywords)
        if (const auto* text = keyword.as_string()) locations.at["keywords." + text->get()] = where(keyword.source());
  }

  void read_post(const toml::table& table, const std::string& path, Scene& scene) {
    check_keys(table, path, {"effect", "keywords", "parameters", "textures", "passes"});
    PostEffect effect;
    effect.where.fallback = where(table.source());
    if (const toml::node* node = table.get("effect")) {
      if (auto value = library_path(*node, path + ".effect")) effect.effect = *value;
      effect.where.at["effect"] = where(node->source());
    } else {
      missing(table, path + ".effect", "a path in the shader folders, e.g. \"post/depth_of_field.hlsl\"");
    }
    if (const toml::node* node = table.get("keywords")) effect.keywords = keywords(*node, path + ".keywords");
    if (const toml::node* node = table.get("parameters")) effect.parameters = properties(*node, path + ".parameters");
    if (const toml::node* node = table.get("textures")) read_textures(*node, path + ".textures", effect.textures);
    if (const toml::node* node = table.get("passes")) read_post_steps(*node, path + ".passes", effect.passes);
    record_locations(table, effect.where);
    scene.post.push_back(std::move(effect));
  }

  // A post step's `sources = { TEXTURE = "scene.color" | "scene.depth" | a step in `earlier` }`.
  void read_step_sources(const toml::node& node, const std::string& path, const std::set<std::string>& earlier,
                         std::map<std::string, std::string>& sources) {
    const auto* table = node.as_table();
    if (!table) {
      expected(node, path, "a table of TEXTURE = \"scene.color\", \"scene.depth\" or an earlier step's name");
      return;
    }
    for (auto&& [texture, source] : *table) {
      const std::string source_path = key_path(path, texture.str());
      auto text = string(source, source_path, "\"scene.color\", \"scene.depth\" or an earlier step's name");
      if (!text) continue;
      if (*text != "scene.color" && *text != "scene.depth" && !earlier.count(*text))
        expected(source, source_path, "\"scene.color\", \"scene.depth\" or the name of an earlier step");
      sources[std::string(texture.str())] = *text;
    }
  }

  // `passes = [0, "Name", { pass = 1, name = "blurred", scale = "half", sources = { _CoCTex =
  // "coc" } }]`: each a pass of a .shader effect by index or Name, or a table that says more.
  void read_post_steps(const toml::node& node, const std::string& path, std::vector<PostStep>& steps) {
    const auto* array = node.as_array();
    if (!array || array->empty()) {
      expected(node, path, "an array of passes, each an index, a Name or a table { pass = ..., name, scale, sources }");
      return;
    }
    std::set<std::string> names;
    for (size_t i = 0; i < array->size(); ++i) {
      const toml::node& element = *array->get(i);
      const std::string element_path = index_path(path, i);
      PostStep step;
      step.where = where(element.source());
      const toml::node* pass = &element;
      if (const auto* table = element.as_table()) {
        check_keys(*table, element_path, {"pass", "name", "scale", "sources"});
        pass = table->get("pass");
        if (!pass) missing(*table, element_path + ".pass", "the pass's index or Name");
        if (const toml::node* name = table->get("name"))
          step.name = string(*name, element_path + ".name", "a name for the step's image").value_or("");
        if (const toml::node* scale = table->get("scale")) {
          const auto* text = scale->as_string();
          if (text && (text->get() == "full" || text->get() == "half"))
            step.half = text->get() == "half";
          else
            expected(*scale, element_path + ".scale", "\"full\" or \"half\"");
        }
        if (const toml::node* sources = table->get("sources"))
          read_step_sources(*sources, element_path + ".sources", names, step.sources);
      }
      if (pass) {
        if (const auto* index = pass->as_integer(); index && index->get() >= 0 && index->get() < 1024)
          step.pass = std::to_string(index->get());
        else if (const auto* name = pass->as_string(); name && !name->get().empty())
          step.pass = name->get();
        else
          expected(*pass, pass == &element ? element_path : element_path + ".pass",
                   "a pass's index (0 to 1023) or Name, or a table { pass = ..., name, scale, sources }");
      }
      const std::string& step_name = step.name.empty() ? step.pass : step.name;
      if (!step_name.empty() && !names.insert(step_name).second)
        report(element.source(),
               fmt::format("{}: a step named '{}' comes earlier; give this one its own name = \"...\"", element_path,
                           step_name));
      steps.push_back(std::move(step));
    }
  }

  void read_compare(const toml::table& table, Scene& scene) {
    CompareSettings& compare = scene.compare;
    check_keys(table, "compare",
               {"channel_tolerance", "max_failing_fraction", "position_radius", "float_tolerance", "metric",
                "metric_threshold", "pixel_threshold", "incorrect_fraction", "pixels_per_degree", "reason"});
    std::vector<std::string_view> given;
    read_compare_metric(table, scene, given);
    if (const toml::node* node = table.get("channel_tolerance")) {
      given.push_back("channel_tolerance");
      if (auto value = integer(*node, "compare.channel_tolerance", 0, 255))
        compare.channel_tolerance = static_cast<uint32_t>(*value);
    }
    if (const toml::node* node = table.get("max_failing_fraction")) {
      given.push_back("max_failing_fraction");
      if (auto value = number(*node, "compare.max_failing_fraction", "a number in [0, 1]",
                              [](double v) { return v >= 0.0 && v <= 1.0; }))
        compare.max_failing_fraction = *value;
    }
    if (const toml::node* node = table.get("position_radius")) {
      given.push_back("position_radius");
      if (auto value = integer(*node, "compare.position_radius", 0, 8))
        compare.position_radius = static_cast<uint32_t>(*value);
    }
    if (const toml::node* node = table.get("float_tolerance")) {
      given.push_back("float_tolerance");
      if (auto value = number(*node, "compare.float_tolerance", "a relative error in [0, 1]",
                              [](double v) { return v >= 0.0 && v <= 1.0; }))
        compare.float_tolerance = *value;
    }
    compare.tolerances_given = !given.empty();
    if (const toml::node* node = table.get("reason")) {
      auto* text = node->as_string();
      bool blank = !text || std::all_of(text->get().begin(), text->get().end(),
                                        [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
      if (blank)
        expected(*node, "compare.reason", "a string saying why these tolerances");
      else
        compare.reason = text->get();
    } else if (!given.empty()) {
      std::string keys;
      for (std::string_view key : given) keys += (keys.empty() ? "" : ", ") + std::string(key);
      report(table.source(),
             fmt::format("compare.reason: missing; a tolerance ({}) needs a reason saying why these numbers", keys));
    }
  }

  // [compare] metric and its thresholds (metric_settings.h). A metric's own key without the
  // metric, or one of another metric's, is a mistake; each given key needs the reason too.
  void read_compare_metric(const toml::table& table, Scene& scene, std::vector<std::string_view>& given) {
    std::optional<Metric> metric;
    if (const toml::node* node = table.get("metric")) {
      given.push_back("metric");
      const auto* name = node->as_string();
      metric = name ? metric_named(name->get()) : std::nullopt;
      if (!metric) expected(*node, "compare.metric", "\"flip\", \"ssim\" or \"deltae\"");
    }
    MetricSettings settings;
    if (metric) {
      settings.metric = *metric;
      settings.threshold = default_metric_threshold(*metric);
    }
    const auto option = [&](std::string_view key, std::optional<Metric> only, std::string_view expectation,
                            auto valid) -> std::optional<double> {
      const toml::node* node = table.get(key);
      if (!node) return std::nullopt;
      given.push_back(key);
      const std::string path = "compare." + std::string(key);
      if (!table.get("metric") || (metric && only && *metric != *only)) {
        report(node->source(), fmt::format("{}: belongs to {}; set compare.metric = \"{}\" or leave it out", path,
                                           only ? "metric " + std::string(metric_name(*only)) : "a metric",
                                           only ? metric_name(*only) : "flip"));
        return std::nullopt;
      }
      return number(*node, path, expectation, valid);
    };
    if (auto value =
            option("metric_threshold", std::nullopt,
                   "a number: flip's mean in [0, 1], ssim's in [-1, 1], deltae's average of 0 or more", [&](double v) {
                     return metric == Metric::Ssim   ? v >= -1.0 && v <= 1.0
                            : metric == Metric::Flip ? v >= 0.0 && v <= 1.0
                                                     : v >= 0.0;
                   }))
      settings.threshold = *value;
    if (auto value = option("pixel_threshold", Metric::DeltaE, "a CIEDE2000 difference of 0 or more",
                            [](double v) { return v >= 0.0; }))
      settings.pixel_threshold = *value;
    if (auto value = option("incorrect_fraction", Metric::DeltaE, "a fraction of the pixels in [0, 1]",
                            [](double v) { return v >= 0.0 && v <= 1.0; }))
      settings.incorrect_fraction = *value;
    if (auto value = option("pixels_per_degree", Metric::Flip, "a number of pixels per degree above 0",
                            [](double v) { return v > 0.0; }))
      settings.pixels_per_degree = *value;
    if (metric == Metric::Ssim && (scene.width < 11 || scene.height < 11))
      report(table.get("metric")->source(),
             fmt::format("compare.metric: ssim measures in 11x11 windows and this scene is {}x{}; choose flip or "
                         "deltae",
                         scene.width, scene.height));
    if (metric) scene.compare.metric = settings;
  }

  std::filesystem::path file_;
  std::map<std::string, size_t> object_names_;  // each object's name, the first object of that name
};

}  // namespace

Result<Scene> parse_scene(std::string_view text, const std::filesystem::path& file) {
  return SceneReader(file).read(text);
}

Result<Scene> load_scene(const std::filesystem::path& file) {
  auto text = read_input_file(file, kMaxSceneFileBytes, "the scene file");
  if (!text) return fail(text.error());
  return parse_scene(*text, file);
}

}  // namespace xshade::harness
