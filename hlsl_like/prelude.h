// The prelude: the Unity-isms every hlsl_like source may use, as macros defined before it.
//
// Being macros, the same list feeds xshade's preprocessor and glslang's (the vk-hlsl lane), so
// both compilers see one language. `fixed` is half: on these drivers both compute in fp32, and
// half-precision emulation treats them alike.
#pragma once

#include <memory>
#include <vector>

#include "hlsl_like/preprocessor.h"

namespace xshade::hlsl {

const std::vector<MacroDefinition>& prelude_macros();
// The same macros read once, for every compile's preprocessor to share.
const Result<std::shared_ptr<const PredefinedMacros>>& prelude_table();

}  // namespace xshade::hlsl
