// Lowering: renaming. What each of the author's names is called in GLSL: names GLSL reserves and
// the emitter's own prefixes renamed, overloads that GLSL would confuse told apart, a local that
// would hide a function and a struct hidden by a variable given names of their own; a renamed
// name never collides with another of the author's (docs/hlsl_like.md).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "base/string_index.h"
#include "glsl/flavour.h"
#include "hlsl_like/ast.h"

namespace xshade::glsl::lower {

// The GLSL names of the author's declarations, the same in both stages of a program.
class Names {
 public:
  Names(const hlsl::TranslationUnit& unit, Flavour flavour);

  // The GLSL spelling of an author's name: unchanged unless GLSL reserves it (glsl_names.h);
  // a renamed name never collides with another name of the author's.
  std::string of(const std::string& name) const;
  // A function's name: of(name), or with a type suffix when two overloads have the same GLSL
  // signature (half and float parameters are both float in GLSL).
  std::string function(const hlsl::FunctionDecl* function) const;
  // A variable's or parameter's name. A local or parameter named like one of the author's
  // functions is renamed too: in GLSL it would hide the function for the rest of its scope.
  // Every use of a variable asks for its name, so each renamed one is worked out once.
  const std::string& variable(const hlsl::Decl* decl) const;
  // The scalar `index` of a constant-buffer vector declared as scalars: `_Offset_0`.
  std::string split_member(const std::string& name, uint32_t index) const;
  // A struct's name: of(name), or a name of its own when a variable, parameter or field is named
  // like it (HLSL lets a variable hide a type, as C does; GLSL refuses a global beside the struct).
  const std::string& type(const hlsl::StructDecl* decl) const;

 private:
  // Whether the author declared `name` anywhere. Only a renaming asks, so the names (views of
  // the tree's strings) are gathered on first use.
  bool is_user_name(std::string_view name) const;
  // Whether a variable, parameter or field is named `name`; gathered on first use too.
  bool is_value_name(std::string_view name) const;

  const hlsl::TranslationUnit& unit_;
  mutable bool user_gathered_ = false;
  mutable StringIndex user_names_;
  std::unordered_set<std::string_view> function_names_;
  // Overloads whose GLSL signatures coincide; every other function is of(name).
  std::unordered_map<const hlsl::FunctionDecl*, std::string> functions_;
  mutable std::unordered_map<std::string, std::string> cache_;
  mutable std::unordered_map<const hlsl::Decl*, std::string> variables_;
  mutable bool values_gathered_ = false;
  mutable StringIndex value_names_;
  mutable std::unordered_map<const hlsl::StructDecl*, std::string> types_;
};

// The GLSL spelling of a type for overload comparison; no diagnostics (the printer's spelling,
// StageEmitter::type_name, defined beside it in emit_expressions.cpp).
std::string type_key(const hlsl::Type& type, Flavour flavour);

}  // namespace xshade::glsl::lower
