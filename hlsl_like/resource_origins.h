// Which global or parameter each resource a function reads is. HLSL lets a local variable or a
// struct field hold a texture or a sampler (FXAA's `struct FxaaTex { SamplerState smpl;
// Texture2D tex; }`, `Texture2D t = _MainTex;`); GLSL has no opaque locals, so a target follows
// every such local back, when compiling, to the one global or parameter it names, as glslang
// flattens them. A local must be given its resource once, outside branches and loops.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/sema.h"

namespace xshade::hlsl {

struct ResourceOrigin {
  const Decl* root = nullptr;    // a global VarDecl, or a ParamDecl of the function
  std::vector<uint32_t> fields;  // field indices below a parameter of struct type; empty otherwise
};

// One resource inside a value: its field path below the value (empty for a resource itself).
struct ResourceLeaf {
  std::vector<uint32_t> path;
  ResourceOrigin origin;
};

// For every expression of the functions the entry points reach that reads a resource or a
// struct holding resources (a name or a field of one): where each of its resources comes from.
using ResourceOrigins = std::unordered_map<const Expr*, std::vector<ResourceLeaf>>;

// The paths of the resources inside `type`: {{}} for a resource, one per resource field of a
// struct (nested structs too), none for anything else.
std::vector<std::vector<uint32_t>> resource_paths(const Type& type);

// Whether a value of `type` may hold resources (a resource, or a struct that may have resource
// fields): only such expressions have ResourceOrigins, and the question is asked of every
// expression, most of them numeric, before resource_paths.
inline bool may_hold_resources(const Type& type) { return type.is_resource() || type.kind() == TypeKind::Struct; }

// Follows the locals of the functions `entry_points` reach; reports a local whose resource is
// not known when compiling (given in a branch or a loop, read before it is given, chosen by ?:).
ResourceOrigins resolve_resource_origins(const EntryPoints& entry_points, DiagnosticEngine& diagnostics);

}  // namespace xshade::hlsl
