// What a scene file expands to and what it may ask: the instances of its objects (a grid's cells
// with their varied properties), their model matrices, the built-in textures' names, the fog's
// keyword and the scene's work budget.
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "harness/scene/scene.h"
#include "harness/scene/toml_reader.h"

namespace xshade::harness {
namespace {

using namespace toml_text;

PropertyValue interpolate(const VaryRule& rule, uint32_t index, uint32_t count) {
  PropertyValue value = rule.from;
  if (count <= 1) return value;
  float t = static_cast<float>(index) / static_cast<float>(count - 1);
  for (uint32_t i = 0; i < value.count; ++i)
    value.components[i] = rule.from.components[i] + (rule.to.components[i] - rule.from.components[i]) * t;
  return value;
}

ObjectInstance instance_of(const SceneObject& object, size_t index, const glm::vec3& position) {
  ObjectInstance instance;
  instance.object_name = object.name;
  instance.object_index = index;
  instance.model = model_matrix(position, object.rotation_degrees, object.scale);
  instance.mesh = object.mesh;
  instance.material = object.material;
  instance.keywords = object.keywords;
  instance.textures = object.textures;
  instance.buffers = object.buffers;
  instance.properties = object.properties;
  return instance;
}

}  // namespace

const char* fog_keyword(FogMode mode) {
  switch (mode) {
    case FogMode::Linear: return "FOG_LINEAR";
    case FogMode::Exponential: return "FOG_EXP";
    case FogMode::ExponentialSquared: return "FOG_EXP2";
  }
  return "FOG_EXP2";
}

Result<void> check_scene_work(const Scene& scene) {
  struct Step {
    uint64_t draws = 0;  // up to and with this object or effect
    std::string path;    // "object[3]", "post[0]"
    SourceLocation where;
  };
  // The draws up to each object and post effect, so that the error points at where a budget is
  // passed.
  std::vector<Step> steps;
  uint64_t draws = 0;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    draws += object.grid ? uint64_t(object.grid->rows) * object.grid->cols : 1;
    steps.push_back({draws, index_path("object", i), object.where.fallback});
  }
  for (size_t i = 0; i < scene.post.size(); ++i)
    steps.push_back({++draws, index_path("post", i), scene.post[i].where.fallback});
  auto passing = [&](uint64_t limit, uint64_t per_draw) -> const Step& {
    for (const Step& step : steps)
      if (step.draws * per_draw > limit) return step;
    return steps.back();
  };
  const uint64_t pixels = uint64_t(scene.width) * scene.height;
  const std::string counted =
      fmt::format("{} objects, a draw for each without a grid and for each cell of a grid, and {} post effects",
                  scene.objects.size(), scene.post.size());
  if (draws > kMaxSceneDraws) {
    const Step& step = passing(kMaxSceneDraws, 1);
    return fail(ErrorKind::UserInput,
                fmt::format("{}: here the scene passes {} draws, the most a scene may make; it makes {} in all ({})",
                            step.path, kMaxSceneDraws, draws, counted),
                step.where);
  }
  if (draws * pixels > kMaxScenePixelDraws) {
    const Step& step = passing(kMaxScenePixelDraws, pixels);
    return fail(
        ErrorKind::UserInput,
        fmt::format("{}: here the scene passes {} pixel-draws (draws times the {} x {} = {} pixels each may "
                    "cover), the most a scene may make; it makes {} in all ({} draws: {})",
                    step.path, kMaxScenePixelDraws, scene.width, scene.height, pixels, draws * pixels, draws, counted),
        step.where);
  }
  return {};
}

glm::mat4 model_matrix(const glm::vec3& position, const glm::vec3& rotation_degrees, const glm::vec3& scale) {
  glm::mat4 model = glm::translate(glm::mat4(1.0f), position);
  // Matrices apply right to left: the vertex turns about X first, then Y, then Z.
  model = glm::rotate(model, glm::radians(rotation_degrees.z), glm::vec3(0.0f, 0.0f, 1.0f));
  model = glm::rotate(model, glm::radians(rotation_degrees.y), glm::vec3(0.0f, 1.0f, 0.0f));
  model = glm::rotate(model, glm::radians(rotation_degrees.x), glm::vec3(1.0f, 0.0f, 0.0f));
  return glm::scale(model, scale);
}

std::optional<TextureOrigin> built_in_texture(std::string_view name) {
  const std::pair<std::string_view, TextureOrigin> built_ins[] = {
      {"white", TextureOrigin::White},     {"black", TextureOrigin::Black},
      {"checker", TextureOrigin::Checker}, {"normal", TextureOrigin::Normal},
      {"gray", TextureOrigin::Gray},       {"red", TextureOrigin::Red},
      {"clear", TextureOrigin::Clear},     {"environment", TextureOrigin::Environment}};
  for (const auto& [built_in, origin] : built_ins)
    if (name == built_in) return origin;
  return std::nullopt;
}

std::vector<ObjectInstance> expand_instances(const Scene& scene) {
  std::vector<ObjectInstance> instances;
  for (size_t index = 0; index < scene.objects.size(); ++index) {
    const SceneObject& object = scene.objects[index];
    if (!object.grid) {
      instances.push_back(instance_of(object, index, object.position));
      continue;
    }
    const GridSpec& grid = *object.grid;
    for (uint32_t row = 0; row < grid.rows; ++row) {
      for (uint32_t col = 0; col < grid.cols; ++col) {
        // Centred on the object's position, row 0 on top: y falls as the row index grows.
        glm::vec3 offset((static_cast<float>(col) - static_cast<float>(grid.cols - 1) / 2.0f) * grid.spacing.x,
                         (static_cast<float>(grid.rows - 1) / 2.0f - static_cast<float>(row)) * grid.spacing.y, 0.0f);
        ObjectInstance instance = instance_of(object, index, object.position + offset);
        instance.in_grid = true;
        instance.row = row;
        instance.col = col;
        for (const auto& [name, rule] : grid.vary) {
          bool along_rows = rule.along == GridAxis::Rows;
          instance.properties[name] = interpolate(rule, along_rows ? row : col, along_rows ? grid.rows : grid.cols);
        }
        instances.push_back(std::move(instance));
      }
    }
  }
  return instances;
}

}  // namespace xshade::harness
