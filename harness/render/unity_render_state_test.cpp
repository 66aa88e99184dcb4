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
  const BlendState expected{true,
                            BlendFactor::SrcAlpha,
                            BlendFactor::OneMinusSrcAlpha,
                            BlendFactor::One,
                            BlendFactor::Zero,
                            BlendOp::ReverseSubtract,
                            BlendOp::Max};
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
TEST(UnityRenderState, ADirect3DRenderTargetTurnsFacesDepthTestAndBiasRound) {
  DrawState state;
  state.cull = CullMode::Back;
  state.depth_compare = CompareOp::LessEqual;
  state.depth_bias_slope = -1.0f;
  state.depth_bias_units = -2.0f;
  state.stencil.enabled = true;
  state.stencil.front.compare = CompareOp::Equal;
  state.stencil.back.pass = StencilOp::Replace;
  const DrawState turned = on_direct3d_render_target(state);
  EXPECT_EQ(turned.cull, CullMode::Front);
  EXPECT_EQ(turned.depth_compare, CompareOp::GreaterEqual);
  EXPECT_EQ(turned.depth_bias_slope, 1.0f);
  EXPECT_EQ(turned.depth_bias_units, 2.0f);
  EXPECT_EQ(turned.stencil.front, state.stencil.back);
  EXPECT_EQ(turned.stencil.back, state.stencil.front);
  EXPECT_EQ(on_direct3d_render_target(turned), state) << "twice is as it was";
  for (CompareOp kept : {CompareOp::Always, CompareOp::Equal, CompareOp::NotEqual, CompareOp::Never}) {
    state.depth_compare = kept;
    EXPECT_EQ(on_direct3d_render_target(state).depth_compare, kept);
  }
  state.cull = CullMode::Off;
  EXPECT_EQ(on_direct3d_render_target(state).cull, CullMode::Off);
}

TEST(UnityRenderState, APropertyInBracketsIsReadAsUnitysEnum) {
  auto state = unity_draw_state(pass_state("Cull [_Cull] ZWrite [_ZWrite] ZTest [_ZTest] Blend [_Src] [_Dst] "
                                           "BlendOp [_Op] ColorMask [_Mask] Offset [_Factor], [_Units]"),
                                properties({{"_Cull", 1},
                                            {"_ZWrite", 0},
                                            {"_ZTest", 4},
                                            {"_Src", 5},
                                            {"_Dst", 10},
                                            {"_Op", 2},
                                            {"_Mask", 14},
                                            {"_Factor", 1},
                                            {"_Units", 2}}));
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

TEST(UnityRenderState, AStencilBlockSetsBothFacesAndItsFaceFormsOne) {
  auto state = unity_draw_state(pass_state("Stencil { PassFront IncrWrap Ref 3 ReadMask 7 WriteMask 240 Comp Equal "
                                           "Pass Replace ZFail Invert CompBack Greater FailBack DecrSat }"),
                                properties({}));
  ASSERT_TRUE(state) << state.error().to_string();
  const StencilState& s = state->stencil;
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.reference, 3);
  EXPECT_EQ(s.read_mask, 7);
  EXPECT_EQ(s.write_mask, 0xF0);
  // PassFront, written before Pass, still wins on the front face.
  EXPECT_EQ(s.front,
            (StencilFaceState{CompareOp::Equal, StencilOp::IncrementWrap, StencilOp::Keep, StencilOp::Invert}));
  EXPECT_EQ(s.back,
            (StencilFaceState{CompareOp::Greater, StencilOp::Replace, StencilOp::DecrementClamp, StencilOp::Invert}));
}

// Unity's UI shaders: Stencil { Ref [_Stencil] Comp [_StencilComp] Pass [_StencilOp] ... } with
// the properties' numbers; at their defaults (Always, Keep) the block tests nothing.
TEST(UnityRenderState, StencilPropertiesAreUnitysEnumsAndAnInertBlockIsNoTest) {
  const std::string block =
      "Stencil { Ref [_Stencil] Comp [_StencilComp] Pass [_StencilOp] ReadMask [_Read] WriteMask [_Write] }";
  auto inert = unity_draw_state(
      pass_state(block),
      properties({{"_Stencil", 0}, {"_StencilComp", 8}, {"_StencilOp", 0}, {"_Read", 255}, {"_Write", 255}}));
  ASSERT_TRUE(inert) << inert.error().to_string();
  EXPECT_EQ(inert->stencil, StencilState{});
  auto masking = unity_draw_state(
      pass_state(block),
      properties({{"_Stencil", 2}, {"_StencilComp", 3}, {"_StencilOp", 2}, {"_Read", 255}, {"_Write", 255}}));
  ASSERT_TRUE(masking) << masking.error().to_string();
  EXPECT_TRUE(masking->stencil.enabled);
  EXPECT_EQ(masking->stencil.reference, 2);
  EXPECT_EQ(masking->stencil.front.compare, CompareOp::Equal);
  EXPECT_EQ(masking->stencil.back.pass, StencilOp::Replace);
}

TEST(UnityRenderState, AlphaToMaskIsReadAsAWordOrAPropertyAndLeavesTheDrawStateAlone) {
  EXPECT_EQ(unity_alpha_to_mask(pass_state(""), properties({})).value_or(true), false);
  EXPECT_EQ(unity_alpha_to_mask(pass_state("AlphaToMask True"), properties({})).value_or(false), true);
  EXPECT_EQ(unity_alpha_to_mask(pass_state("AlphaToMask [_A2C]"), properties({{"_A2C", 0}})).value_or(true), false);
  auto state = unity_draw_state(pass_state("AlphaToMask On"), properties({}));
  ASSERT_TRUE(state) << state.error().to_string();
  EXPECT_EQ(*state, unity_draw_state(pass_state(""), properties({})).value_or(DrawState{}));
}

TEST(UnityRenderState, WhatIsNotDrawnIsAnErrorAtItsCommand) {
  const auto error_of = [](const std::string& commands, std::map<std::string, float> values = {}) {
    auto state = unity_draw_state(pass_state(commands), properties(std::move(values)));
    return state ? std::string("(drawn)") : state.error().where.to_string() + ": " + state.error().message;
  };
  EXPECT_EQ(error_of("Stencil { Ref 256 }"), "s.shader:4:21: Stencil Ref takes a whole number from 0 to 255, not 256");
  EXPECT_EQ(error_of("Stencil { Pass [_Op] }", {{"_Op", 9}}),
            "s.shader:4:22: Stencil Pass [_Op] is 9, which is no value of Unity's enum for it");
  EXPECT_EQ(error_of("BlendOp Multiply"), "s.shader:4:15: BlendOp Multiply is not drawn by xshade yet");
  EXPECT_EQ(error_of("Cull [_Cull]"), "s.shader:4:12: Cull [_Cull] names a property the material does not have");
  EXPECT_EQ(error_of("Cull [_Cull]", {{"_Cull", 7}}),
            "s.shader:4:12: Cull [_Cull] is 7, which is no value of Unity's enum for it");
  EXPECT_EQ(error_of("AlphaToMask [_A2C]", {{"_A2C", 2}}),
            "s.shader:4:19: AlphaToMask [_A2C] is 2, which is no value of Unity's enum for it");
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
