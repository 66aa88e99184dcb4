#include "shaderlab/shader_json.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include "shaderlab/reader.h"

namespace xshade::shaderlab {
namespace {

TEST(ShaderJson, EachPropertyWithItsTypeDefaultRangeAndAttributes) {
  auto shader = read_shader(R"SL(Shader "J" {
  Properties {
    [NoScaleOffset] _MainTex ("Albedo", 2D) = "bump" {}
    _Tint ("Tint", Color) = (0.5, 0.25, 1, 1)
    [IntRange] _Steps ("Steps", Range(1, 8)) = 3
  }
  SubShader { Pass { CGPROGRAM ENDCG } }
})SL",
                            "j.shader");
  ASSERT_TRUE(shader) << shader.error().to_string();
  const nlohmann::json properties = nlohmann::json::parse(properties_json(*shader));
  ASSERT_EQ(properties.size(), 3u);
  EXPECT_EQ(properties[0]["type"], "2D");
  EXPECT_EQ(properties[0]["default"], "bump");
  EXPECT_EQ(properties[0]["attributes"][0]["name"], "NoScaleOffset");
  EXPECT_EQ(properties[1]["display_name"], "Tint");
  EXPECT_EQ(properties[1]["default"], nlohmann::json({0.5, 0.25, 1.0, 1.0}));
  EXPECT_EQ(properties[2]["type"], "Range");
  EXPECT_EQ(properties[2]["range"], nlohmann::json({1.0, 8.0}));
  EXPECT_EQ(properties[2]["default"], 3.0);
  EXPECT_EQ(properties[2]["line"], 5);
}

}  // namespace
}  // namespace xshade::shaderlab
