// Which identifiers GLSL does not let an author's HLSL names keep, and how they are renamed.
#pragma once

#include <string>
#include <string_view>
#include <unordered_set>

namespace xshade::glsl {

// A GLSL 4.50 keyword, reserved word, type name, built-in function name (both flavours), or a
// name xshade uses itself (`main`).
bool is_glsl_reserved_word(std::string_view name);

// True when `name` cannot be used as is in GLSL: a reserved word, a `gl_` prefix, a `__` anywhere,
// or xshade's own `xs_` prefix (the names the emitter generates).
bool needs_renaming(std::string_view name);

// The GLSL spelling of an author's name, ignoring collisions: reserved words get a trailing `_`;
// `gl_x` becomes `xs_gl_x_`, `a__b` becomes `a_0b`, `xs_x` becomes `xs_x_` (see the definition).
std::string renamed(std::string_view name);

}  // namespace xshade::glsl
