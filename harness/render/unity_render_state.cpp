#include "harness/render/unity_render_state.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <utility>

namespace xshade::harness {
namespace {

using shaderlab::same_word;
using shaderlab::StateValue;

// A word of `words` (by Unity's spelling, ignoring case) or a property's number, as the value
// at that place of Unity's enum.
template <class T, size_t N>
Result<T> choose(const StateValue& value, const std::array<std::pair<const char*, T>, N>& words,
                 const std::array<std::optional<T>, 16>& by_number, const StatePropertyLookup& property,
                 const char* command) {
  if (value.is_property) {
    const std::optional<float> number = property(value.text);
    if (!number)
      return fail(ErrorKind::UserInput,
                  std::string(command) + " [" + value.text + "] names a property the material does not have",
                  value.where);
    const long index = std::lround(*number);
    if (index >= 0 && index < long(by_number.size()) && by_number[size_t(index)]) return *by_number[size_t(index)];
    char shown[32];
    std::snprintf(shown, sizeof shown, "%g", double(*number));
    return fail(
        ErrorKind::UserInput,
        std::string(command) + " [" + value.text + "] is " + shown + ", which is no value of Unity's enum for it",
        value.where);
  }
  for (const auto& [word, meaning] : words)
    if (same_word(value.text, word)) return meaning;
  return fail(ErrorKind::UserInput, std::string(command) + " " + value.text + " is not drawn by xshade yet",
              value.where);
}

constexpr std::array<std::pair<const char*, CullMode>, 3> kCullWords{
    {{"Off", CullMode::Off}, {"Front", CullMode::Front}, {"Back", CullMode::Back}}};
// UnityEngine.Rendering.CullMode: Off 0, Front 1, Back 2.
constexpr std::array<std::optional<CullMode>, 16> kCullNumbers{CullMode::Off, CullMode::Front, CullMode::Back};

constexpr std::array<std::pair<const char*, CompareOp>, 8> kCompareWords{{{"Never", CompareOp::Never},
                                                                          {"Less", CompareOp::Less},
                                                                          {"Equal", CompareOp::Equal},
                                                                          {"LEqual", CompareOp::LessEqual},
                                                                          {"Greater", CompareOp::Greater},
                                                                          {"NotEqual", CompareOp::NotEqual},
                                                                          {"GEqual", CompareOp::GreaterEqual},
                                                                          {"Always", CompareOp::Always}}};
// UnityEngine.Rendering.CompareFunction: Disabled 0 (no test: Always), Never 1 ... Always 8.
constexpr std::array<std::optional<CompareOp>, 16> kCompareNumbers{
    CompareOp::Always,  CompareOp::Never,    CompareOp::Less,         CompareOp::Equal, CompareOp::LessEqual,
    CompareOp::Greater, CompareOp::NotEqual, CompareOp::GreaterEqual, CompareOp::Always};

constexpr std::array<std::pair<const char*, bool>, 4> kSwitchWords{
    {{"On", true}, {"True", true}, {"Off", false}, {"False", false}}};
constexpr std::array<std::optional<bool>, 16> kSwitchNumbers{false, true};

constexpr std::array<std::pair<const char*, BlendFactor>, 11> kFactorWords{
    {{"Zero", BlendFactor::Zero},
     {"One", BlendFactor::One},
     {"SrcColor", BlendFactor::SrcColor},
     {"OneMinusSrcColor", BlendFactor::OneMinusSrcColor},
     {"DstColor", BlendFactor::DstColor},
     {"OneMinusDstColor", BlendFactor::OneMinusDstColor},
     {"SrcAlpha", BlendFactor::SrcAlpha},
     {"OneMinusSrcAlpha", BlendFactor::OneMinusSrcAlpha},
     {"DstAlpha", BlendFactor::DstAlpha},
     {"OneMinusDstAlpha", BlendFactor::OneMinusDstAlpha},
     {"SrcAlphaSaturate", BlendFactor::SrcAlphaSaturate}}};
// UnityEngine.Rendering.BlendMode: Zero 0, One 1, DstColor 2, SrcColor 3, OneMinusDstColor 4,
// SrcAlpha 5, OneMinusSrcColor 6, DstAlpha 7, OneMinusDstAlpha 8, SrcAlphaSaturate 9,
// OneMinusSrcAlpha 10.
constexpr std::array<std::optional<BlendFactor>, 16> kFactorNumbers{BlendFactor::Zero,
                                                                    BlendFactor::One,
                                                                    BlendFactor::DstColor,
                                                                    BlendFactor::SrcColor,
                                                                    BlendFactor::OneMinusDstColor,
                                                                    BlendFactor::SrcAlpha,
                                                                    BlendFactor::OneMinusSrcColor,
                                                                    BlendFactor::DstAlpha,
                                                                    BlendFactor::OneMinusDstAlpha,
                                                                    BlendFactor::SrcAlphaSaturate,
                                                                    BlendFactor::OneMinusSrcAlpha};

constexpr std::array<std::pair<const char*, BlendOp>, 5> kBlendOpWords{{{"Add", BlendOp::Add},
                                                                        {"Sub", BlendOp::Subtract},
                                                                        {"RevSub", BlendOp::ReverseSubtract},
                                                                        {"Min", BlendOp::Min},
                                                                        {"Max", BlendOp::Max}}};
// UnityEngine.Rendering.BlendOp: Add 0, Subtract 1, ReverseSubtract 2, Min 3, Max 4 (the logical
// and advanced operations after them are not drawn).
constexpr std::array<std::optional<BlendOp>, 16> kBlendOpNumbers{BlendOp::Add, BlendOp::Subtract,
                                                                 BlendOp::ReverseSubtract, BlendOp::Min, BlendOp::Max};

constexpr std::array<std::pair<const char*, StencilOp>, 8> kStencilOpWords{{{"Keep", StencilOp::Keep},
                                                                            {"Zero", StencilOp::Zero},
                                                                            {"Replace", StencilOp::Replace},
                                                                            {"IncrSat", StencilOp::IncrementClamp},
                                                                            {"DecrSat", StencilOp::DecrementClamp},
                                                                            {"Invert", StencilOp::Invert},
                                                                            {"IncrWrap", StencilOp::IncrementWrap},
                                                                            {"DecrWrap", StencilOp::DecrementWrap}}};
// UnityEngine.Rendering.StencilOp: Keep 0, Zero 1, Replace 2, IncrementSaturate 3,
// DecrementSaturate 4, Invert 5, IncrementWrap 6, DecrementWrap 7.
constexpr std::array<std::optional<StencilOp>, 16> kStencilOpNumbers{
    StencilOp::Keep,           StencilOp::Zero,   StencilOp::Replace,       StencilOp::IncrementClamp,
    StencilOp::DecrementClamp, StencilOp::Invert, StencilOp::IncrementWrap, StencilOp::DecrementWrap};

Result<float> number(const StateValue& value, const StatePropertyLookup& property, const char* what) {
  if (value.is_property) {
    if (auto given = property(value.text)) return *given;
    return fail(ErrorKind::UserInput,
                std::string(what) + " [" + value.text + "] names a property the material does not have", value.where);
  }
  float parsed = 0.0f;
  const auto [end, error] = std::from_chars(value.text.data(), value.text.data() + value.text.size(), parsed);
  if (error != std::errc() || end != value.text.data() + value.text.size())
    return fail(ErrorKind::UserInput, std::string(what) + " takes a number, not " + value.text, value.where);
  return parsed;
}

Result<uint8_t> color_mask(const StateValue& value, const StatePropertyLookup& property) {
  if (value.is_property) {
    auto given = number(value, property, "ColorMask");
    if (!given) return fail(given.error());
    // UnityEngine.Rendering.ColorWriteMask: Alpha 1, Blue 2, Green 4, Red 8.
    const long bits = std::lround(*given);
    if (bits < 0 || bits > 15)
      return fail(ErrorKind::UserInput, "ColorMask [" + value.text + "] is no ColorWriteMask", value.where);
    return uint8_t(((bits & 8) ? 1 : 0) | ((bits & 4) ? 2 : 0) | ((bits & 2) ? 4 : 0) | ((bits & 1) ? 8 : 0));
  }
  const std::string channels = value.text.substr(0, value.text.find(' '));  // "RGB 1": render target 1's
  if (value.text.find(' ') != std::string::npos && value.text.substr(value.text.find(' ') + 1) != "0")
    return fail(ErrorKind::UserInput,
                "ColorMask for render target " + value.text.substr(value.text.find(' ') + 1) +
                    ": xshade draws into one render target",
                value.where);
  uint8_t mask = 0;
  for (char c : channels) mask |= c == 'R' ? 1 : c == 'G' ? 2 : c == 'B' ? 4 : c == 'A' ? 8 : 0;
  return mask;
}

// A Stencil block's fields over Unity's defaults (Ref 0, ReadMask 255, WriteMask 255, Comp Always,
// Pass, Fail and ZFail Keep): Comp, Pass, Fail and ZFail set both faces, their Front and Back
// forms one face whichever comes first. A state that can neither fail nor write (every
// comparison Always, every operation Keep) is no test at all, so that a target needs no stencil
// buffer for it (Unity's UI shaders carry such a block by default).
Result<StencilState> stencil_state(const shaderlab::StencilState& block, const StatePropertyLookup& property) {
  StencilState out;
  out.enabled = true;
  for (const auto& [name, value] : block.fields) {
    if (name == "Ref" || name == "ReadMask" || name == "WriteMask") {
      auto given = number(value, property, name.c_str());
      if (!given) return fail(given.error());
      if (*given < 0.0f || *given > 255.0f || *given != std::floor(*given))
        return fail(ErrorKind::UserInput, "Stencil " + name + " takes a whole number from 0 to 255, not " + value.text,
                    value.where);
      const auto byte = uint8_t(*given);
      (name == "Ref" ? out.reference : name == "ReadMask" ? out.read_mask : out.write_mask) = byte;
    }
  }
  // The faces' own forms after the shared ones, so that they win wherever they are written.
  for (const bool own_face : {false, true})
    for (const auto& [name, value] : block.fields) {
      const bool front = name.ends_with("Front"), back = name.ends_with("Back");
      if (own_face != (front || back)) continue;
      const std::string field = name.substr(0, name.size() - (front ? 5 : back ? 4 : 0));
      std::vector<StencilFaceState*> faces;
      if (!back) faces.push_back(&out.front);
      if (!front) faces.push_back(&out.back);
      if (field == "Comp") {
        auto compare = choose(value, kCompareWords, kCompareNumbers, property, "Stencil Comp");
        if (!compare) return fail(compare.error());
        for (StencilFaceState* face : faces) face->compare = *compare;
      } else if (field == "Pass" || field == "Fail" || field == "ZFail") {
        auto op = choose(value, kStencilOpWords, kStencilOpNumbers, property, ("Stencil " + field).c_str());
        if (!op) return fail(op.error());
        for (StencilFaceState* face : faces)
          (field == "Pass" ? face->pass : field == "Fail" ? face->fail : face->depth_fail) = *op;
      }
    }
  const StencilFaceState inert;
  if (out.front == inert && out.back == inert) return StencilState{};
  return out;
}

}  // namespace

Result<DrawState> unity_draw_state(const shaderlab::RenderState& state, const StatePropertyLookup& property) {
  DrawState out;
  out.cull = CullMode::Back;
  out.depth_compare = CompareOp::LessEqual;
  if (state.cull) {
    auto cull = choose(*state.cull, kCullWords, kCullNumbers, property, "Cull");
    if (!cull) return fail(cull.error());
    out.cull = *cull;
  }
  if (state.zwrite) {
    auto write = choose(*state.zwrite, kSwitchWords, kSwitchNumbers, property, "ZWrite");
    if (!write) return fail(write.error());
    out.depth_write = *write;
  }
  if (state.ztest) {
    auto test = choose(*state.ztest, kCompareWords, kCompareNumbers, property, "ZTest");
    if (!test) return fail(test.error());
    out.depth_compare = *test;
  }
  if (state.offset) {
    auto factor = number(state.offset->first, property, "Offset's factor");
    if (!factor) return fail(factor.error());
    auto units = number(state.offset->second, property, "Offset's units");
    if (!units) return fail(units.error());
    out.depth_bias_slope = *factor;
    out.depth_bias_units = *units;
  }
  if (state.color_mask) {
    auto mask = color_mask(*state.color_mask, property);
    if (!mask) return fail(mask.error());
    out.color_write = *mask;
  }
  for (const shaderlab::BlendState& blend : state.blend) {
    if (blend.target > 0) {
      if (!blend.off)
        return fail(ErrorKind::UserInput,
                    "Blend " + std::to_string(blend.target) + ": xshade draws into one render target",
                    blend.source.where);
      continue;
    }
    if (blend.off) {
      out.blend = {};
      continue;
    }
    BlendState& b = out.blend;
    b.enabled = true;
    const auto factor = [&](const StateValue& value) {
      return choose(value, kFactorWords, kFactorNumbers, property, "Blend");
    };
    auto source = factor(blend.source);
    if (!source) return fail(source.error());
    auto destination = factor(blend.destination);
    if (!destination) return fail(destination.error());
    b.color_source = b.alpha_source = *source;
    b.color_destination = b.alpha_destination = *destination;
    if (blend.source_alpha && blend.destination_alpha) {
      auto source_alpha = factor(*blend.source_alpha);
      if (!source_alpha) return fail(source_alpha.error());
      auto destination_alpha = factor(*blend.destination_alpha);
      if (!destination_alpha) return fail(destination_alpha.error());
      b.alpha_source = *source_alpha;
      b.alpha_destination = *destination_alpha;
    }
  }
  if (state.blend_op) {
    auto colour = choose(state.blend_op->first, kBlendOpWords, kBlendOpNumbers, property, "BlendOp");
    if (!colour) return fail(colour.error());
    out.blend.color_op = out.blend.alpha_op = *colour;
    if (state.blend_op->second) {
      auto alpha = choose(*state.blend_op->second, kBlendOpWords, kBlendOpNumbers, property, "BlendOp");
      if (!alpha) return fail(alpha.error());
      out.blend.alpha_op = *alpha;
    }
  }
  if (auto alpha_to_mask = unity_alpha_to_mask(state, property); !alpha_to_mask) return fail(alpha_to_mask.error());
  if (state.stencil) {
    auto stencil = stencil_state(*state.stencil, property);
    if (!stencil) return fail(stencil.error());
    out.stencil = *stencil;
  }
  return out;
}

Result<bool> unity_alpha_to_mask(const shaderlab::RenderState& state, const StatePropertyLookup& property) {
  if (!state.alpha_to_mask) return false;
  return choose(*state.alpha_to_mask, kSwitchWords, kSwitchNumbers, property, "AlphaToMask");
}

Result<int> render_queue(const std::string& tag) {
  if (tag.empty()) return kGeometryQueue;
  const auto whole_number = [](std::string_view text, int& out) {
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
    return !text.empty() && error == std::errc() && end == text.data() + text.size();
  };
  int value = 0;
  if (whole_number(tag, value)) return value;  // "2500"
  static constexpr std::pair<const char*, int> kQueues[] = {
      {"Background", 1000}, {"Geometry", 2000}, {"AlphaTest", 2450}, {"Transparent", 3000}, {"Overlay", 4000}};
  const size_t sign = tag.find_first_of("+-");
  for (const auto& [queue, base] : kQueues) {
    if (!same_word(tag.substr(0, sign), queue)) continue;
    if (sign == std::string::npos) return base;
    int offset = 0;  // "+1" or "-1"; from_chars reads no plus sign
    if (whole_number(std::string_view(tag).substr(sign + (tag[sign] == '+' ? 1 : 0)), offset)) return base + offset;
  }
  return fail(ErrorKind::UserInput,
              "Queue \"" + tag +
                  "\" is none of Background, Geometry, AlphaTest, Transparent and Overlay (with an "
                  "offset such as \"Transparent+1\"), nor a number");
}

DrawState on_direct3d_render_target(DrawState state) {
  if (state.cull != CullMode::Off) state.cull = state.cull == CullMode::Back ? CullMode::Front : CullMode::Back;
  std::swap(state.stencil.front, state.stencil.back);
  switch (state.depth_compare) {
    case CompareOp::Less: state.depth_compare = CompareOp::Greater; break;
    case CompareOp::LessEqual: state.depth_compare = CompareOp::GreaterEqual; break;
    case CompareOp::Greater: state.depth_compare = CompareOp::Less; break;
    case CompareOp::GreaterEqual: state.depth_compare = CompareOp::LessEqual; break;
    case CompareOp::Never:
    case CompareOp::Equal:
    case CompareOp::NotEqual:
    case CompareOp::Always: break;
  }
  state.depth_bias_slope = -state.depth_bias_slope;
  state.depth_bias_units = -state.depth_bias_units;
  return state;
}

}  // namespace xshade::harness
