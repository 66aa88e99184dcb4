#include "glsl/lower/flatten_resources.h"

#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/resource_origins.h"

namespace xshade::glsl::lower {

using namespace hlsl;

namespace {

std::string flattened_name(const ParamDecl& param, const std::vector<uint32_t>& path, const Names& names) {
  std::string name = names.variable(&param);
  const Type* at = &param.type;
  for (uint32_t field : path) {
    if (at->kind() != TypeKind::Struct || !at->struct_decl() || field >= at->struct_decl()->fields.size()) break;
    const FieldDecl& f = at->struct_decl()->fields[field];
    name += "_" + names.of(f.name);
    at = &f.type;
  }
  return name;
}

}  // namespace

const Type& leaf_type(const Type& type, const std::vector<uint32_t>& path) {
  const Type* at = &type;
  for (uint32_t field : path) {
    if (at->kind() != TypeKind::Struct || !at->struct_decl() || field >= at->struct_decl()->fields.size()) break;
    at = &at->struct_decl()->fields[field].type;
  }
  return *at;
}

std::vector<FlattenedParameter> flattened_parameters(const ParamDecl& param, const Names& names, Flavour flavour) {
  std::vector<FlattenedParameter> parameters;
  for (std::vector<uint32_t>& path : resource_paths(param.type)) {
    const Type& leaf = leaf_type(param.type, path);
    if (flavour == Flavour::Gl && leaf.kind() == TypeKind::SamplerState) continue;
    std::string name = flattened_name(param, path, names);
    parameters.push_back({std::move(path), &leaf, std::move(name)});
  }
  return parameters;
}

std::optional<std::string> resource_name(const Module& module, const Expr* e, const std::vector<uint32_t>& leaf,
                                         const Names& names) {
  auto it = module.resource_origins.find(e);
  if (it == module.resource_origins.end()) return std::nullopt;
  for (const ResourceLeaf& known : it->second) {
    if (known.path != leaf) continue;
    const ResourceOrigin& origin = known.origin;
    if (origin.root->kind == DeclKind::Param)
      return flattened_name(static_cast<const ParamDecl&>(*origin.root), origin.fields, names);
    return names.variable(origin.root);
  }
  return std::nullopt;
}

std::optional<std::string> mixed_struct_message(const Type& type) {
  const StructDecl* decl = type.struct_decl();
  if (!decl) return std::nullopt;
  for (const FieldDecl& field : decl->fields) {
    if (field.type.is_resource()) continue;
    if (field.type.kind() == TypeKind::Struct && !resource_paths(field.type).empty()) {
      if (std::optional<std::string> inner = mixed_struct_message(field.type)) return inner;
      continue;
    }
    return "struct " + in_quotes(decl->name) + " holds both resources and the value " + in_quotes(field.name) +
           ", which this target cannot keep together: keep its resources in a struct of their own";
  }
  return std::nullopt;
}

}  // namespace xshade::glsl::lower
