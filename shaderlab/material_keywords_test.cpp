#include "shaderlab/material_keywords.h"

#include <map>

#include <gtest/gtest.h>

#include "shaderlab/reader.h"

namespace xshade::shaderlab {
namespace {

using Strings = std::vector<std::string>;

std::vector<Property> properties_of(const std::string& block) {
  auto shader = read_shader("Shader \"K\" { Properties {\n" + block + "\n} SubShader { Pass { } } }", "k.shader");
  EXPECT_TRUE(shader) << shader.error().to_string();
  return shader ? shader->properties : std::vector<Property>{};
}

PropertyValue values(std::map<std::string, float> given) {
  return [given](const std::string& name) -> std::optional<float> {
    if (auto it = given.find(name); it != given.end()) return it->second;
    return std::nullopt;
  };
}

TEST(MaterialKeywords, TogglesSetTheirKeywordAsTheValueSays) {
  const std::vector<Property> properties = properties_of(R"(
    [Toggle] _Glow ("Glow", Float) = 1
    [Toggle(_FADE_ON)] _Fade ("Fade", Float) = 0
    [MaterialToggle] _Snow ("Snow", Int) = 1
    [ToggleOff] _Specular ("Specular highlights", Float) = 0
    [ToggleOff(_NO_RIM)] _Rim ("Rim", Float) = 1
    _Plain ("Plain", Float) = 1)");
  // The defaults: on, off, on; ToggleOff on at 0, off at 1.
  EXPECT_EQ(material_keywords(properties, values({})), (Strings{"_GLOW_ON", "_SNOW_ON", "_SPECULAR_OFF"}));
  // A scene's values turn them over.
  EXPECT_EQ(material_keywords(properties, values({{"_Glow", 0}, {"_Fade", 1}, {"_Specular", 1}, {"_Rim", 0}})),
            (Strings{"_FADE_ON", "_SNOW_ON", "_NO_RIM"}));
}

TEST(MaterialKeywords, AKeywordEnumSetsTheKeywordOfItsValue) {
  const std::vector<Property> properties = properties_of(R"(
    [KeywordEnum(None, Add, Multiply Twice)] _Overlay ("Overlay mode", Float) = 1)");
  EXPECT_EQ(material_keywords(properties, values({})), Strings{"_OVERLAY_ADD"});
  EXPECT_EQ(material_keywords(properties, values({{"_Overlay", 0}})), Strings{"_OVERLAY_NONE"});
  EXPECT_EQ(material_keywords(properties, values({{"_Overlay", 2}})), Strings{"_OVERLAY_MULTIPLY_TWICE"});
  EXPECT_EQ(material_keywords(properties, values({{"_Overlay", 7}})), Strings{"_OVERLAY_MULTIPLY_TWICE"});  // the last
}

}  // namespace
}  // namespace xshade::shaderlab
