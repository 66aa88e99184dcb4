// A .shader's Properties as JSON, for `xshade compile X.shader --reflect` (docs/unity.md).
#pragma once

#include <string>

#include "shaderlab/shader.h"

namespace xshade::shaderlab {

// An array: each property's name, label, type ("Float", "Range", "Color", "2D", ...), default
// (a number, four numbers, or a texture's default name), range and attributes, in file order.
std::string properties_json(const Shader& shader);

}  // namespace xshade::shaderlab
