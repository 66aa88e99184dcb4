// Lowering: what a stage declares. GLSL gets only what the entry point reaches (its functions, the
// statics they and the statics' initializers read, and the structs any of those or the constant
// buffers use), so that what the target cannot express is an error only where it is reached
// (docs/hlsl_like.md section 15), and a function is defined before its callers.
#pragma once

#include <unordered_set>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {

struct UsedDeclarations {
  // The functions the entry point reaches, callees before callers, the entry point last; then
  // those the statics' initializers call.
  std::vector<const hlsl::FunctionDecl*> functions;
  std::vector<const hlsl::VarDecl*> statics;  // static (and groupshared) globals, in source order
  std::unordered_set<const hlsl::StructDecl*> structs;
};

// For `entry`, one of the module's entry points (none: nothing is used).
UsedDeclarations used_declarations(const hlsl::Module& module, const hlsl::FunctionDecl* entry);

}  // namespace xshade::glsl::lower
