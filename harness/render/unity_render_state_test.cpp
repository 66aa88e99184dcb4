#include "harness/render/unity_render_state.h"

#include <map>

#include <gtest/gtest.h>

#include "shaderlab/reader.h"

namespace xshade::harness {
namespace {

// The render state of the first pass of a shader whose pass holds `commands`.
shaderlab::RenderState pass_state(const std::string& commands) {
  auto shader = shaderlab::read_shader("Shader \"S\" {\n  SubShader {\n    Pass {\n      " + commands +
                                           "\n      HLSLPROGRAM\n      ENDHLSL\n    }\n  }\n}\n",
                                       "s.shader");
  EXPECT_TRUE(shader) << shader.error().to_string();
  return shader ? shader->subshaders[0].passes[0].state.over(shader->subshaders[0].state) : shaderlab::RenderState{};
}

StatePropertyLookup properties(std::map<std::string, float> values) {
  return [values](const std::string& name) -> std::optional<float> {
    auto found = values.find(name);
    return found == values.end() ? std::nullopt : std::optional<float>(found->second);
  };
}

TEST(UnityRenderState, NothingSetIsUnitysDefault) {
  auto state = unity_draw_state(pass_state(""), properties({}));
  ASSERT_TRUE(state) << state.error().to_string();
  EXPECT_EQ(state->cull, CullMode::Back);
  EXPECT_TRUE(state->depth_write);
  EXPECT_EQ(state->depth_compare, CompareOp::LessEqual);
  EXPECT_FALSE(state->blend.enabled);
  EXPECT_EQ(state->color_write, kColorWriteAll);
  EXPECT_EQ(state->depth_bias_slope, 0.0f);
}

TEST(UnityRenderState, WordsAreTheirDirect3DMeaning) {
  auto state = unity_draw_state(
      pass_state("Cull Front ZWrite Off ZTest Always Blend SrcAlpha OneMinusSrcAlpha, One Zero BlendOp RevSub, Max "
                 "ColorMask RB Offset -1, -2"),
      properties({}));
  ASSERT_TRUE(state) << state.error().to_string();
  EXPECT_EQ(state->cull, CullMode::Front);
  EXPECT_FALSE(state->depth_write);
  EXPECT_EQ(state->depth_compare, CompareOp::Always);
  const BlendState expected{true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha, BlendFactor::One, BlendFactor::Zero,
                            BlendOp::ReverseSubtract, BlendOp::Max};
  EXPECT_EQ(state->blend, expected);
  EXPECT_EQ(state->color_write, 1 | 4);  // red and blue
  EXPECT_EQ(state->depth_bias_slope, -1.0f);
  EXPECT_EQ(state->depth_bias_units, -2.0f);

  // Two factors blend alpha as colour.
  auto two = unity_draw_state(pass_state("Blend One One"), properties({}));
  ASSERT_TRUE(two);
  EXPECT_EQ(two->blend, (BlendState{true, BlendFactor::One, BlendFactor::One, BlendFactor::One, BlendFactor::One}));
}

// The numbers a material holds for a state, as UnityEngine.Rendering's enums number them.
TEST(UnityRenderState, APropertyInBracketsIsReadAsUnitysEnum) {
  auto state = unity_draw_state(pass_state("Cull [_Cull] ZWrite [_ZWrite] ZTest [_ZTest] Blend [_Src] [_Dst] "
                                           "BlendOp [_Op] ColorMask [_Mask] Offset [_Factor], [_Units]"),
                                properties({{"_Cull", 1}, {"_ZWrite", 0}, {"_ZTest", 4}, {"_Src", 5}, {"_Dst", 10},
                                            {"_Op", 2}, {"_Mask", 14}, {"_Factor", 1}, {"_Units", 2}}));
  ASSERT_TRUE(state) << state.error().to_string();
  EXPECT_EQ(state->cull, CullMode::Front);
  EXPECT_FALSE(state->depth_write);
  EXPECT_EQ(state->depth_compare, CompareOp::LessEqual);
  EXPECT_EQ(state->blend.color_source, BlendFactor::SrcAlpha);
  EXPECT_EQ(state->blend.color_destination, BlendFactor::OneMinusSrcAlpha);
  EXPECT_EQ(state->blend.color_op, BlendOp::ReverseSubtract);
  EXPECT_EQ(state->color_write, 1 | 2 | 4);  // Red 8 + Green 4 + Blue 2
  EXPECT_EQ(state->depth_bias_units, 2.0f);
}

TEST(UnityRenderState, WhatIsNotDrawnIsAnErrorAtItsCommand) {
  const auto error_of = [](const std::string& commands, std::map<std::string, float> values = {}) {
    auto state = unity_draw_state(pass_state(commands), properties(std::move(values)));
    return state ? std::string("(drawn)") : state.error().where.to_string() + ": " + state.error().message;
  };
  EXPECT_EQ(error_of("Stencil { Ref 1 Comp Always Pass Replace }"),
            "s.shader:4:21: Stencil is not drawn yet: xshade's targets have no stencil buffer");
  EXPECT_EQ(error_of("BlendOp Multiply"), "s.shader:4:15: BlendOp Multiply is not drawn by xshade yet");
  EXPECT_EQ(error_of("Cull [_Cull]"), "s.shader:4:12: Cull [_Cull] names a property the material does not have");
  EXPECT_EQ(error_of("Cull [_Cull]", {{"_Cull", 7}}), "s.shader:4:12: Cull [_Cull] is 7, which is no value of Unity's enum for it");
  EXPECT_NE(error_of("AlphaToMask On").find("AlphaToMask On is not drawn yet"), std::string::npos);
}

TEST(UnityRenderState, QueuesAreUnitysNumbers) {
  EXPECT_EQ(render_queue(""), kGeometryQueue);
  EXPECT_EQ(render_queue("Transparent"), 3000);
  EXPECT_EQ(render_queue("Transparent+1"), 3001);
  EXPECT_EQ(render_queue("geometry-10"), 1990);
  EXPECT_EQ(render_queue("AlphaTest"), 2450);
  EXPECT_EQ(render_queue("2450"), 2450);
  auto misspelt = render_queue("Transparnt");
  ASSERT_FALSE(misspelt);
  EXPECT_NE(misspelt.error().message.find("Queue \"Transparnt\" is none of"), std::string::npos);
}

}  // namespace
}  // namespace xshade::harness
