// Lowering: which textures OpenGL reads with comparison. A GLSL for OpenGL texture is one combined
// sampler uniform, and one read with comparison must be declared a shadow sampler
// (sampler2DShadow), where HLSL's texture is the same Texture2D whichever sampler reads it.
#pragma once

#include <unordered_set>

#include "hlsl_like/compiler.h"
#include "hlsl_like/intrinsics.h"

namespace xshade::glsl::lower {

// SampleCmp, SampleCmpLevelZero and the GatherCmp methods.
bool is_comparison_method(hlsl::IntrinsicId id);
// The variable or parameter `e` names (through implicit conversions), or null.
const hlsl::Decl* named_decl(const hlsl::Expr* e);

// The textures (globals and parameters) a comparison method reads, and, back through the calls,
// what is passed for such a parameter. Over both stages' reached functions: a texture is one
// uniform of one type in the linked program, so one the fragment stage compares is a shadow
// sampler in the vertex stage too.
std::unordered_set<const hlsl::Decl*> compared_textures(const hlsl::Module& module);

}  // namespace xshade::glsl::lower
