#include "shaderlab/material_keywords.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace xshade::shaderlab {
namespace {

std::string keyword_case(std::string text) {
  for (char& c : text) c = c == ' ' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

}  // namespace

std::vector<std::string> material_keywords(const std::vector<Property>& properties, const PropertyValue& value) {
  std::vector<std::string> keywords;
  for (const Property& property : properties) {
    const float number = value(property.name).value_or(property.value[0]);
    for (const PropertyAttribute& attribute : property.attributes) {
      const bool toggle = same_word(attribute.name, "Toggle") || same_word(attribute.name, "MaterialToggle");
      const bool toggle_off = same_word(attribute.name, "ToggleOff");
      if ((toggle && number != 0.0f) || (toggle_off && number == 0.0f)) {
        keywords.push_back(!attribute.arguments.empty() && !attribute.arguments[0].empty()
                               ? attribute.arguments[0]
                               : keyword_case(property.name) + (toggle ? "_ON" : "_OFF"));
      } else if (same_word(attribute.name, "KeywordEnum") && !attribute.arguments.empty()) {
        const float index = std::clamp(std::floor(number), 0.0f, float(attribute.arguments.size() - 1));
        keywords.push_back(keyword_case(property.name) + "_" + keyword_case(attribute.arguments[size_t(index)]));
      }
    }
  }
  return keywords;
}

}  // namespace xshade::shaderlab
