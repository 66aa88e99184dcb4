#include "shaderlab/shader_json.h"

#include <nlohmann/json.hpp>

namespace xshade::shaderlab {
namespace {

const char* type_name(PropertyType type) {
  switch (type) {
    case PropertyType::Float: return "Float";
    case PropertyType::Int: return "Int";
    case PropertyType::Integer: return "Integer";
    case PropertyType::Range: return "Range";
    case PropertyType::Color: return "Color";
    case PropertyType::Vector: return "Vector";
    case PropertyType::Texture2D: return "2D";
    case PropertyType::Texture2DArray: return "2DArray";
    case PropertyType::Texture3D: return "3D";
    case PropertyType::Cube: return "Cube";
    case PropertyType::CubeArray: return "CubeArray";
    case PropertyType::Any: return "Any";
  }
  return "Float";
}

}  // namespace

std::string properties_json(const Shader& shader) {
  nlohmann::json properties = nlohmann::json::array();
  for (const Property& property : shader.properties) {
    nlohmann::json entry = {
        {"name", property.name}, {"display_name", property.display_name}, {"type", type_name(property.type)}};
    if (property.is_texture())
      entry["default"] = property.texture_default;
    else if (property.type == PropertyType::Color || property.type == PropertyType::Vector)
      entry["default"] = property.value;
    else
      entry["default"] = property.value[0];
    if (property.type == PropertyType::Range) entry["range"] = {property.range_min, property.range_max};
    nlohmann::json attributes = nlohmann::json::array();
    for (const PropertyAttribute& attribute : property.attributes)
      attributes.push_back({{"name", attribute.name}, {"arguments", attribute.arguments}});
    entry["attributes"] = std::move(attributes);
    entry["line"] = property.where.line;
    properties.push_back(std::move(entry));
  }
  return properties.dump(2);
}

}  // namespace xshade::shaderlab
