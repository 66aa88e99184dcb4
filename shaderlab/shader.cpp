#include "shaderlab/shader.h"

#include <cctype>

namespace xshade::shaderlab {
namespace {

template <class T>
void take_unset(std::optional<T>& mine, const std::optional<T>& outer) {
  if (!mine) mine = outer;
}

}  // namespace

bool same_word(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

const PropertyAttribute* Property::attribute(std::string_view wanted) const {
  for (const PropertyAttribute& attribute : attributes)
    if (same_word(attribute.name, wanted)) return &attribute;
  return nullptr;
}

const StateValue* StencilState::field(std::string_view name) const {
  for (const auto& [field_name, value] : fields)
    if (field_name == name) return &value;
  return nullptr;
}

RenderState RenderState::over(const RenderState& outer) const {
  RenderState state = *this;
  take_unset(state.cull, outer.cull);
  take_unset(state.zwrite, outer.zwrite);
  take_unset(state.ztest, outer.ztest);
  take_unset(state.color_mask, outer.color_mask);
  take_unset(state.alpha_to_mask, outer.alpha_to_mask);
  take_unset(state.zclip, outer.zclip);
  take_unset(state.conservative, outer.conservative);
  take_unset(state.offset, outer.offset);
  take_unset(state.blend_op, outer.blend_op);
  take_unset(state.stencil, outer.stencil);
  if (state.blend.empty()) state.blend = outer.blend;
  return state;
}

std::string tag(const Tags& tags, std::string_view name) {
  for (const auto& [tag_name, value] : tags)
    if (same_word(tag_name, name)) return value;
  return {};
}

const Property* Shader::property(std::string_view wanted) const {
  for (const Property& property : properties)
    if (property.name == wanted) return &property;
  return nullptr;
}

}  // namespace xshade::shaderlab
