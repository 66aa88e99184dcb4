// Lowering: resources held in structs, parameters and locals. GLSL has no opaque values in a
// struct or a local, so a parameter that is a resource or a struct of resources becomes one
// parameter per resource (`tex_smpl` for `tex.smpl`), a local resource is another name for what
// it was given, and each read of a resource names the global or the flattened parameter the front
// end followed it back to (hlsl_like/resource_origins.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "glsl/flavour.h"
#include "glsl/lower/rename.h"
#include "hlsl_like/compiler.h"

namespace xshade::glsl::lower {

// The type of the field at `path` inside `type` (`type` itself for an empty path).
const hlsl::Type& leaf_type(const hlsl::Type& type, const std::vector<uint32_t>& path);

// One GLSL parameter a parameter holding resources becomes.
struct FlattenedParameter {
  std::vector<uint32_t> path;  // the resource's field path inside the parameter
  const hlsl::Type* type;      // the resource's type
  std::string name;            // the parameter's name with the path's field names: tex_smpl
};
// The parameters `param` becomes on `flavour`, in field order: none when it holds no resource,
// and none for a SamplerState on gl, whose state belongs to the texture unit.
std::vector<FlattenedParameter> flattened_parameters(const hlsl::ParamDecl& param, const Names& names, Flavour flavour);

// The GLSL name of the resource at `leaf` (a field path) inside the value `e`: the global, or the
// flattened parameter, it was followed back to. None when the front end found none for it.
std::optional<std::string> resource_name(const hlsl::Module& module, const hlsl::Expr* e,
                                         const std::vector<uint32_t>& leaf, const Names& names);

// A struct holding resources must hold nothing else: its values would need a GLSL struct of their
// own beside the flattened resources. The message for the first value `type` (or a struct of
// resources inside it) holds, or none.
std::optional<std::string> mixed_struct_message(const hlsl::Type& type);

}  // namespace xshade::glsl::lower
