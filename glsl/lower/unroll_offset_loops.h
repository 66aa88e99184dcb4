// Lowering: offset-loop unrolling. A sampling method's texel offset must be a constant expression
// in GLSL, where HLSL (as DXC and fxc compile it) lets it be a loop variable whose values are
// known when compiling; such a loop is written out once per value, its variable a constant in
// each copy (docs/hlsl_like.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "hlsl_like/ast.h"

namespace xshade::glsl::lower {

// The most copies a loop is unrolled to; a longer loop stays a loop (and its offset an error).
inline constexpr size_t kMaxUnrolledIterations = 256;

// The values of a for loop's int variable, when the loop is to be unrolled: its variable is a
// texel offset in the body, its trip is known when compiling (at most kMaxUnrolledIterations),
// and the body neither writes the variable nor breaks or continues the loop.
std::optional<std::vector<int64_t>> unrolled_values(const hlsl::ForStmt& loop);

// Every loop of `functions`' bodies to unroll, with its variable's values.
using UnrolledLoops = std::unordered_map<const hlsl::ForStmt*, std::vector<int64_t>>;
UnrolledLoops unroll_offset_loops(const std::vector<const hlsl::FunctionDecl*>& functions);

}  // namespace xshade::glsl::lower
