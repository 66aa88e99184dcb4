// Renaming (rename.h), with the checks that a renamed name collides with none of the author's.
#include "glsl/lower/rename.h"

#include <algorithm>
#include <map>

#include "glsl/glsl_names.h"
#include "hlsl_like/ast_walk.h"

namespace xshade::glsl::lower {

using namespace hlsl;

namespace {

// "half3" -> "half3", "float[4]" -> "float4": a suffix that tells overloads apart.
std::string type_suffix(const Type& type) {
  std::string suffix;
  for (char c : type.name())
    if (std::isalnum(static_cast<unsigned char>(c))) suffix += c;
  return suffix;
}

// Every name the unit declares for a value (a global, field, cbuffer member, parameter or local),
// and with `every_declaration` the names of its structs, typedefs and functions too.
std::vector<std::string_view> names_in(const TranslationUnit& unit, bool every_declaration) {
  std::vector<std::string_view> names;
  for (const auto& decl : unit.decls) {
    if (!decl) continue;
    if (every_declaration || decl->kind == DeclKind::Var) names.push_back(decl->name);
    switch (decl->kind) {
      case DeclKind::Struct:
        for (const FieldDecl& field : static_cast<const StructDecl&>(*decl).fields) names.push_back(field.name);
        break;
      case DeclKind::CBuffer:
        for (const auto& member : static_cast<const CBufferDecl&>(*decl).members)
          if (member) names.push_back(member->name);
        break;
      case DeclKind::Function: {
        const auto& function = static_cast<const FunctionDecl&>(*decl);
        for (const auto& param : function.params)
          if (param) names.push_back(param->name);
        // Its locals and for-loop variables.
        hlsl::walk_statements(function.body.get(), [&](const Stmt& stmt) {
          if (stmt.kind == StmtKind::Decl)
            for (const auto& var : static_cast<const DeclStmt&>(stmt).vars)
              if (var) names.push_back(var->name);
        });
        break;
      }
      default: break;
    }
  }
  return names;
}

// Whether `index` holds `name`, the index made of names_in(unit, every_declaration) on the first
// question: most units rename nothing and never ask.
bool gathered_contains(const TranslationUnit& unit, bool every_declaration, bool& gathered, StringIndex& index,
                       std::string_view name) {
  if (!gathered) {
    gathered = true;
    const std::vector<std::string_view> names = names_in(unit, every_declaration);
    index = StringIndex(names.size());
    for (std::string_view each : names) index.insert(each);
  }
  return index.find(name) != StringIndex::kAbsent;
}

}  // namespace

Names::Names(const TranslationUnit& unit, Flavour flavour) : unit_(unit) {
  std::vector<const FunctionDecl*> functions;
  for (const auto& decl : unit.decls) {
    if (!decl || decl->kind != DeclKind::Function) continue;
    const auto& function = static_cast<const FunctionDecl&>(*decl);
    function_names_.insert(function.name);
    if (function.body) functions.push_back(&function);
  }

  // Overloads whose GLSL signatures coincide get a suffix of their HLSL parameter types. Only
  // functions that share their GLSL name with another can coincide, so only those are compared:
  // most shaders have none, and then neither the signatures nor the author's names are needed.
  std::vector<std::string> glsl_names;
  glsl_names.reserve(functions.size());
  for (const FunctionDecl* function : functions) glsl_names.push_back(of(function->name));
  // Overloads keep their source order, in which their suffixes are chosen.
  std::vector<uint32_t> by_name(functions.size());
  for (uint32_t i = 0; i < by_name.size(); ++i) by_name[i] = i;
  std::sort(by_name.begin(), by_name.end(), [&](uint32_t a, uint32_t b) {
    const int order = glsl_names[a].compare(glsl_names[b]);
    return order < 0 || (order == 0 && a < b);
  });
  std::map<std::string, std::vector<const FunctionDecl*>> by_signature;  // ordered: deterministic
  for (size_t i = 0; i < by_name.size(); ++i) {
    const std::string& name = glsl_names[by_name[i]];
    const bool shared =
        (i > 0 && glsl_names[by_name[i - 1]] == name) || (i + 1 < by_name.size() && glsl_names[by_name[i + 1]] == name);
    if (!shared) continue;
    const FunctionDecl* function = functions[by_name[i]];
    std::string signature = name + "(";
    for (const auto& param : function->params) {
      if (!param) continue;
      if (flavour == Flavour::Gl && param->type.kind() == TypeKind::SamplerState) continue;
      signature += type_key(param->type, flavour) + ",";
    }
    by_signature[signature].push_back(function);
  }
  std::unordered_set<std::string> suffixed;  // the names given so far, which later ones avoid
  for (const auto& [signature, group] : by_signature) {
    if (group.size() == 1) continue;  // of(name), which function() falls back to
    for (const FunctionDecl* function : group) {
      std::string name = of(function->name);
      for (const auto& param : function->params)
        if (param) name += "_" + type_suffix(param->type);
      std::string candidate = name;
      for (int k = 1; is_user_name(candidate) || suffixed.count(candidate) > 0; ++k)
        candidate = name + std::to_string(k);
      suffixed.insert(candidate);
      functions_[function] = candidate;
    }
  }
}

bool Names::is_user_name(std::string_view name) const {
  return gathered_contains(unit_, true, user_gathered_, user_names_, name);
}

std::string Names::of(const std::string& name) const {
  if (!needs_renaming(name)) return name;
  if (auto it = cache_.find(name); it != cache_.end()) return it->second;
  const std::string base = renamed(name);
  std::string candidate = base;
  for (int k = 1; is_user_name(candidate); ++k) candidate = base + std::to_string(k);
  cache_.emplace(name, candidate);
  return candidate;
}

const std::string& Names::variable(const Decl* decl) const {
  const bool global = decl->kind == DeclKind::Var && static_cast<const VarDecl*>(decl)->is_global;
  const bool may_hide_function = !global && function_names_.count(decl->name) > 0;
  // Most names are GLSL's as written: the tree's own string is the answer, with nothing to remember.
  if (!may_hide_function && !needs_renaming(decl->name)) return decl->name;
  auto [known, inserted] = variables_.try_emplace(decl);
  if (!inserted) return known->second;
  std::string& name = known->second;
  if (!may_hide_function) {
    name = of(decl->name);
    return name;
  }
  const std::string base = of(decl->name);
  const std::string stem = (base.back() == '_' ? base : base + "_") + "v";
  std::string candidate = stem;
  for (int k = 1; is_user_name(candidate) || function_names_.count(candidate) > 0; ++k)
    candidate = stem + std::to_string(k);
  name = std::move(candidate);
  return name;
}

bool Names::is_value_name(std::string_view name) const {
  return gathered_contains(unit_, false, values_gathered_, value_names_, name);
}

const std::string& Names::type(const StructDecl* decl) const {
  auto [known, inserted] = types_.try_emplace(decl);
  if (!inserted) return known->second;
  std::string& name = known->second;
  name = of(decl->name);
  if (!is_value_name(decl->name)) return name;
  const std::string stem = (name.back() == '_' ? name : name + "_") + "t";
  name = stem;
  for (int k = 1; is_user_name(name); ++k) name = stem + std::to_string(k);
  return name;
}

std::string Names::split_member(const std::string& name, uint32_t index) const {
  const std::string base = of(name);
  const std::string stem = base.back() == '_' ? base : base + "_";  // never `__`
  std::string candidate = stem + std::to_string(index);
  while (is_user_name(candidate)) candidate += "x";
  return candidate;
}

std::string Names::function(const FunctionDecl* function) const {
  const FunctionDecl* definition = function->definition ? function->definition : function;
  if (auto it = functions_.find(definition); it != functions_.end()) return it->second;
  return of(function->name);
}

}  // namespace xshade::glsl::lower
