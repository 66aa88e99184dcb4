// The keywords Unity's material inspector sets from a material's property values: a property
// drawn as [Toggle], [MaterialToggle], [ToggleOff] or [KeywordEnum(...)] turns a keyword on as its
// value says, so a material built from the Properties defaults (or a scene's values) compiles the
// variant Unity would draw for it.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "shaderlab/shader.h"

namespace xshade::shaderlab {

// A property's value: the scene's where it gives one, else nullopt for the property's default.
using PropertyValue = std::function<std::optional<float>(const std::string& name)>;

// Each keyword `properties` turn on, in their order:
//   [Toggle] _Name, [MaterialToggle] _Name: _NAME_ON when the value is not 0; [Toggle(KW)]: KW.
//   [ToggleOff] _Name: _NAME_OFF when the value is 0; [ToggleOff(KW)]: KW.
//   [KeywordEnum(A, B, C)] _Name: _NAME_A, _NAME_B or _NAME_C as the value is 0, 1 or 2 (names in
//   upper case, spaces as underscores; a value past the list takes its last).
std::vector<std::string> material_keywords(const std::vector<Property>& properties, const PropertyValue& value);

}  // namespace xshade::shaderlab
