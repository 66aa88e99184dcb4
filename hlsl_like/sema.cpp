// Semantic analysis: declarations, scopes, statements, entry points and the call graph.
// Expressions are in sema_expressions.cpp, calls in sema_calls.cpp, conversion rules in
// sema_conversions.cpp.
#include "hlsl_like/sema.h"

#include <algorithm>

#include "base/spelling.h"
#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl {

namespace sema_detail {

namespace {

bool is_unsized_array(const Type& type) { return type.kind() == TypeKind::Array && type.array_length() == 0; }

// Whether control cannot fall off the end of `stmt` (returns, discards, or loops forever).
bool contains_break(const Stmt* stmt, int depth);

bool constant_true(const Sema& sema, const Expr* condition) {
  if (!condition) return true;  // for (;;)
  const Expr* expr = condition;
  if (expr->kind == ExprKind::Conversion) expr = static_cast<const ConversionExpr*>(expr)->operand.get();
  if (expr && expr->kind == ExprKind::BoolLiteral) return static_cast<const BoolLiteralExpr*>(expr)->value;
  const std::optional<int64_t> value = sema.fold_int(expr);
  return value && *value != 0;
}

bool always_returns(const Sema& sema, const Stmt* stmt, int depth) {
  if (!stmt || depth > kMaxNesting) return false;
  switch (stmt->kind) {
    case StmtKind::Return:
    case StmtKind::Discard: return true;
    case StmtKind::Block:
      for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) {
        if (always_returns(sema, child.get(), depth + 1)) return true;
      }
      return false;
    case StmtKind::If: {
      const auto* branch = static_cast<const IfStmt*>(stmt);
      return branch->else_branch && always_returns(sema, branch->then_branch.get(), depth + 1) &&
             always_returns(sema, branch->else_branch.get(), depth + 1);
    }
    case StmtKind::While: {
      const auto* loop = static_cast<const WhileStmt*>(stmt);
      return loop->condition && constant_true(sema, loop->condition.get()) && !contains_break(loop->body.get(), 0);
    }
    case StmtKind::For: {
      const auto* loop = static_cast<const ForStmt*>(stmt);
      return constant_true(sema, loop->condition.get()) && !contains_break(loop->body.get(), 0);
    }
    case StmtKind::Switch: {
      // Returns when there is a default and every label's statements return, or fall through
      // to ones that do, without a break.
      const auto* sw = static_cast<const SwitchStmt*>(stmt);
      bool has_default = false;
      for (const SwitchCase& c : sw->cases) has_default |= !c.value;
      if (!has_default || sw->cases.empty()) return false;
      bool returns = false;
      for (auto c = sw->cases.rbegin(); c != sw->cases.rend(); ++c) {
        bool this_returns = false;
        for (const StmtPtr& child : c->statements) {
          if (contains_break(child.get(), depth + 1)) return false;
          if (always_returns(sema, child.get(), depth + 1)) this_returns = true;
        }
        if (c->statements.empty() ? !returns : !this_returns) return false;
        returns = true;
      }
      return returns;
    }
    case StmtKind::DoWhile: {
      const auto* loop = static_cast<const DoWhileStmt*>(stmt);
      if (always_returns(sema, loop->body.get(), depth + 1)) return true;
      return loop->condition && constant_true(sema, loop->condition.get()) && !contains_break(loop->body.get(), 0);
    }
    default: return false;
  }
}

// A `break` that leaves the loop whose body is `stmt` (not one of an inner loop).
bool contains_break(const Stmt* stmt, int depth) {
  if (!stmt || depth > kMaxNesting) return false;
  switch (stmt->kind) {
    case StmtKind::Break: return true;
    case StmtKind::Block:
      for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) {
        if (contains_break(child.get(), depth + 1)) return true;
      }
      return false;
    case StmtKind::If: {
      const auto* branch = static_cast<const IfStmt*>(stmt);
      return contains_break(branch->then_branch.get(), depth + 1) ||
             contains_break(branch->else_branch.get(), depth + 1);
    }
    default: return false;  // loops own their breaks
  }
}

enum class Stage { Vertex, Fragment };

bool semantic_allowed(SemanticKind kind, Stage stage, bool input) {
  switch (kind) {
    case SemanticKind::Unknown: return false;
    case SemanticKind::User: return !(stage == Stage::Fragment && !input);  // a pixel shader writes targets
    case SemanticKind::Position: return true;  // an attribute in, the clip position out (DX9)
    case SemanticKind::Normal:
    case SemanticKind::Tangent:
    case SemanticKind::Binormal:
    case SemanticKind::Texcoord: return !(stage == Stage::Fragment && !input);
    case SemanticKind::Color: return true;  // a fragment output COLORn is SV_Targetn (DX9)
    case SemanticKind::SvPosition: return !(stage == Stage::Vertex && input) && !(stage == Stage::Fragment && !input);
    case SemanticKind::SvTarget:
    case SemanticKind::SvDepth: return stage == Stage::Fragment && !input;
    case SemanticKind::SvIsFrontFace: return stage == Stage::Fragment && input;
    case SemanticKind::SvVertexId:
    case SemanticKind::SvInstanceId: return stage == Stage::Vertex && input;
    case SemanticKind::Vface: return stage == Stage::Fragment && input;
    case SemanticKind::SvClipDistance:
    case SemanticKind::SvCullDistance: return stage == Stage::Vertex ? !input : input;
    case SemanticKind::SvShadingRate: return stage == Stage::Fragment && input;
  }
  return false;
}

// The type a system value needs, or nothing when any numeric type will do.
std::optional<std::string> required_type(SemanticKind kind, const Type& type) {
  // DX9's POSITION is the clip position only as a float4 (is_clip_position_alias), otherwise a
  // varying of any numeric type.
  if (kind == SemanticKind::SvPosition) {
    if (!(type.is_vector() && type.cols() == 4 && type.is_floating())) return "float4";
    return std::nullopt;
  }
  switch (kind) {
    case SemanticKind::SvDepth:
      if (!(type.is_scalar() && type.is_floating())) return "float";
      break;
    case SemanticKind::SvIsFrontFace:
      if (!(type.is_scalar() && type.is_bool())) return "bool";
      break;
    case SemanticKind::SvVertexId:
    case SemanticKind::SvInstanceId:
    case SemanticKind::SvShadingRate:
      if (!(type.is_scalar() && type.is_integer())) return "uint";
      break;
    case SemanticKind::Vface:
      if (!(type.is_scalar() && type.is_floating())) return "float";
      break;
    case SemanticKind::SvClipDistance:
    case SemanticKind::SvCullDistance:
      if (!((type.is_scalar() || type.is_vector()) && type.is_floating())) return "a float or a float vector";
      break;
    default:
      // A float matrix takes a location per row, as DXC gives it; GLSL has no integer matrices.
      if (!type.is_numeric() || (type.is_matrix() && !type.is_floating())) {
        if (type.kind() == TypeKind::Array && type.element().is_numeric()) break;
        return "a scalar, vector or float matrix";
      }
      break;
  }
  return std::nullopt;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Scopes

const Symbol* SymbolTable::lookup(std::string_view name) const {
  const uint32_t number = names_.find(name);
  if (number == StringIndex::kAbsent || innermost_[number] == 0) return nullptr;
  return &bindings_[innermost_[number] - 1].symbol;
}

const Symbol* SymbolTable::add(std::string_view name, Symbol symbol) {
  const auto [number, added] = names_.insert(name);
  if (added) innermost_.push_back(0);
  const uint32_t innermost = innermost_[number];
  if (innermost != 0 && bindings_[innermost - 1].depth == scope_starts_.size()) {
    // A variable named like a struct or typedef of its scope hides it, as in C (the parser
    // already reads the name as the variable from there on); anything else is a redefinition.
    const Symbol::Kind previous = bindings_[innermost - 1].symbol.kind;
    const bool hides_type = symbol.kind == Symbol::Kind::Variable &&
                            (previous == Symbol::Kind::Struct || previous == Symbol::Kind::Typedef);
    if (!hides_type) return &bindings_[innermost - 1].symbol;
  }
  bindings_.push_back({name, symbol, number, innermost, uint32_t(scope_starts_.size())});
  innermost_[number] = uint32_t(bindings_.size());
  return nullptr;
}

void SymbolTable::pop_scope() {
  const size_t start = scope_starts_.back();
  scope_starts_.pop_back();
  while (bindings_.size() > start) {
    const Binding& binding = bindings_.back();
    innermost_[binding.name_number] = binding.shadowed;
    bindings_.pop_back();
  }
}

bool Sema::declare(const std::string& name, Symbol symbol, Loc loc) {
  if (name.empty() || scopes_.empty()) return true;
  const Symbol* previous = scopes_.add(name, symbol);
  if (!previous) return true;
  diag_.error(loc, "redefinition of " + in_quotes(name));
  if (previous->decl) diag_.note(previous->decl->loc, "previous definition of " + in_quotes(name) + " is here");
  return false;
}

const Symbol* Sema::lookup(const std::string& name) const { return scopes_.lookup(name); }

std::string Sema::suggestion(const std::string& name, bool functions) const {
  // Suggestions cost a comparison with every name; not worth it once errors are being dropped.
  if (name.size() > 64 || diag_.error_count() >= DiagnosticEngine::kErrorLimit) return "";
  const size_t limit = std::max<size_t>(1, name.size() / 3);
  std::string best;
  size_t best_distance = limit + 1;
  auto consider = [&](std::string_view candidate) {
    if (candidate.size() > 64 || candidate == name) return;
    const size_t difference =
        candidate.size() > name.size() ? candidate.size() - name.size() : name.size() - candidate.size();
    if (difference >= best_distance) return;
    const size_t distance = edit_distance(name, candidate);
    if (distance < best_distance && distance < candidate.size()) {
      best = candidate;
      best_distance = distance;
    }
  };
  if (functions) {
    for (const auto& [candidate, overloads] : functions_) consider(candidate);
    for (uint16_t id = 1;; ++id) {
      const IntrinsicInfo& info = intrinsic_info(IntrinsicId(id));
      if (info.id == IntrinsicId::None) break;
      if (!info.is_method) consider(info.name);
    }
  } else {
    // Each scope's names in the order a hash map of them iterates, the order suggestions have
    // always been searched in (the first of equally close names wins).
    for (size_t depth = 0; depth < scopes_.depth(); ++depth) {
      std::unordered_map<std::string, Symbol> scope;
      scopes_.for_each_in_scope(depth, [&](std::string_view candidate, const Symbol& symbol) {
        scope.emplace(std::string(candidate), symbol);
      });
      for (const auto& [candidate, symbol] : scope) {
        if (symbol.kind == Symbol::Kind::Variable) consider(candidate);
      }
    }
  }
  return best;
}

// ---------------------------------------------------------------------------------------------
// Declarations

bool Sema::check_type_usable(const Type& type, std::string_view kind, std::string_view name, Loc loc,
                             bool allow_resource, bool allow_resource_array) {
  auto what = [&] { return std::string(kind) + in_quotes(name); };
  if (type.is_void()) {
    diag_.error(loc, what() + " cannot have type 'void'");
    return false;
  }
  if (!allow_resource && facts_.contains_resource(type)) {
    diag_.error(loc, what() + " cannot have type " + in_quotes(type.name()) +
                         "; resources are only allowed at global scope or as parameters");
    return false;
  }
  // A global array of textures, samplers or constant buffers is one binding of that many
  // descriptors (register t2 and the next ones on Direct3D); GLSL holds no other array of them.
  if (type.kind() == TypeKind::Array && facts_.contains_resource(type)) {
    const Type& element = type.element();
    const bool bindable = element.kind() == TypeKind::Texture || element.kind() == TypeKind::SamplerState ||
                          element.kind() == TypeKind::Sampler || element.kind() == TypeKind::ConstantBuffer;
    if (!allow_resource_array || !bindable) {
      diag_.error(loc, what() + " cannot have type " + in_quotes(type.name()) +
                           "; arrays of resources are supported as globals of textures, samplers and constant buffers "
                           "only: declare each one separately");
      return false;
    }
  }
  return true;
}

void Sema::declare_struct(StructDecl& decl) {
  std::unordered_map<std::string, const FieldDecl*> names;
  for (const FieldDecl& field : decl.fields) {
    if (!field.name.empty()) {
      auto [it, inserted] = names.emplace(field.name, &field);
      if (!inserted) {
        diag_.error(field.loc, "redefinition of " + in_quotes(field.name));
        diag_.note(it->second->loc, "previous definition of " + in_quotes(field.name) + " is here");
      }
    }
    if (field.type.kind() == TypeKind::Struct && field.type.struct_decl() == &decl) {
      diag_.error(field.loc, "field " + in_quotes(field.name) + " cannot have the type of its own struct");
      continue;
    }
    // A struct may hold resources (FXAA's `struct FxaaTex { SamplerState smpl; Texture2D tex; }`):
    // a local or parameter of it names globals, resolved when compiling (resource_origins.h).
    if (!check_type_usable(field.type, "field ", field.name, field.loc, true)) continue;
    if (is_unsized_array(field.type)) diag_.error(field.loc, "field " + in_quotes(field.name) + " needs an array size");
  }
  // Learn the struct's facts now, while its fields' structs are already known: later queries
  // then never walk a chain of nested structs.
  facts_.component_count(Type::structure(&decl));
  facts_.contains_resource(Type::structure(&decl));
  declare(decl.name, {Symbol::Kind::Struct, &decl}, decl.loc);
}

void Sema::declare_typedef(TypedefDecl& decl) { declare(decl.name, {Symbol::Kind::Typedef, &decl}, decl.loc); }

void Sema::analyze_var_initializer(VarDecl& var) {
  for (Annotation& annotation : var.annotations) analyze(annotation.value.get());
  if (var.initializer) {
    analyze_initializer(var.initializer, var.type, var.name);
  } else if (is_unsized_array(var.type)) {
    diag_.error(var.loc, "unsized array " + in_quotes(var.name) + " needs an initializer list");
  }
}

void Sema::declare_global_var(VarDecl& var, bool in_cbuffer) {
  const std::string_view kind = in_cbuffer ? "cbuffer member " : "variable ";
  if (var.type.kind() == TypeKind::Struct && facts_.contains_resource(var.type)) {
    // A struct's resources would need registers of their own; HLSL 5.1 gives none to a field.
    diag_.error(var.loc, std::string(kind) + in_quotes(var.name) + " of struct " + in_quotes(var.type.name()) +
                             " holds resources: declare each resource as a global of its own");
  } else if (check_type_usable(var.type, kind, var.name, var.loc, !in_cbuffer, !in_cbuffer)) {
    if (var.type.is_resource() && var.initializer) {
      diag_.error(var.initializer->loc, in_quotes(var.type.name()) + " variables cannot have an initializer");
    } else {
      analyze_var_initializer(var);
    }
  }
  if (var.is_const && var.storage == StorageClass::Static && !var.initializer) {
    diag_.error(var.loc, "static const " + in_quotes(var.name) + " needs an initializer");
  }
  // As DXC: a subpass input names its input attachment, and only a subpass input has one.
  const Type& resource = var.type.is_resource_array() ? var.type.element() : var.type;
  const bool subpass = resource.kind() == TypeKind::Texture && (resource.texture_shape() == TextureShape::Subpass ||
                                                                resource.texture_shape() == TextureShape::SubpassMS);
  if (subpass && !var.vk.input_attachment_index)
    diag_.error(var.loc, in_quotes(resource.name()) + " " + in_quotes(var.name) +
                             " needs [[vk::input_attachment_index(N)]]: the input attachment of the subpass it reads");
  if (!subpass && var.vk.input_attachment_index)
    diag_.error(var.vk.loc, "vk::input_attachment_index belongs on a SubpassInput, not on " + in_quotes(var.name));
  declare(var.name, {Symbol::Kind::Variable, &var}, var.loc);
}

void Sema::declare_cbuffer(CBufferDecl& decl) {
  for (auto& member : decl.members) {
    if (member) declare_global_var(*member, true);
  }
}

void Sema::analyze_local_var(VarDecl& var) {
  // A local resource (or struct of them) is another name for a global one: `Texture2D t = _MainTex;`.
  if (check_type_usable(var.type, "variable ", var.name, var.loc, var.storage != StorageClass::Static)) {
    analyze_var_initializer(var);
  } else if (var.initializer) {
    analyze(var.initializer.get());
  }
  if (var.is_const && !var.initializer) diag_.error(var.loc, "const " + in_quotes(var.name) + " needs an initializer");
  declare(var.name, {Symbol::Kind::Variable, &var}, var.loc);
}

void Sema::declare_function(FunctionDecl& function) {
  all_functions_.push_back(&function);
  analyze_attributes(function.attributes);
  if (function.return_type.is_resource() || function.return_type.kind() == TypeKind::Array) {
    diag_.error(function.loc,
                "function " + in_quotes(function.name) + " cannot return " + in_quotes(function.return_type.name()));
  }
  std::vector<Type> param_types;
  param_types.reserve(function.params.size());
  for (const auto& param : function.params) param_types.push_back(param ? param->type : Type::error());

  // One signature, several declarations: the first is canonical.
  const FunctionDecl* canonical = nullptr;
  std::vector<const FunctionDecl*>& overloads = functions_[function.name];
  for (const FunctionDecl* other : overloads) {
    const FunctionInfo& info = function_info_[other];
    if (info.param_types == param_types) {
      canonical = other;
      break;
    }
  }
  if (canonical) {
    FunctionInfo& info = function_info_[canonical];
    if (!(canonical->return_type == function.return_type)) {
      diag_.error(function.loc,
                  in_quotes(function.name) + " differs from a previous declaration only in its return type");
      diag_.note(canonical->loc, "previous declaration of " + in_quotes(function.name) + " is here");
    } else if (function.body && info.definition) {
      diag_.error(function.loc, "redefinition of " + in_quotes(function.name));
      diag_.note(info.definition->loc, "previous definition of " + in_quotes(function.name) + " is here");
    } else if (function.body) {
      info.definition = &function;
    }
  } else if (!overloads.empty() || declare(function.name, {Symbol::Kind::Function, &function}, function.loc)) {
    canonical = &function;
    overloads.push_back(&function);
  } else {
    // Its name clashes with a variable, struct or typedef (reported): it is analyzed for its own
    // errors but cannot be called.
    canonical = &function;
    functions_.erase(function.name);
  }
  if (canonical == &function) {
    FunctionInfo& info = function_info_[&function];
    info.canonical = &function;
    info.param_types = std::move(param_types);
    if (function.body) info.definition = &function;
  }
  canonical_of_[&function] = canonical;

  const FunctionDecl* const canonical_decl = canonical_of_[&function];
  push_scope();
  for (auto& param : function.params) {
    if (!param) continue;
    check_type_usable(param->type, "parameter ", param->name, param->loc, true);
    if (is_unsized_array(param->type))
      diag_.error(param->loc, "parameter " + in_quotes(param->name) + " needs an array size");
    if (param->default_value) {
      analyze(param->default_value.get());
      coerce(param->default_value, param->type);
    }
    declare(param->name, {Symbol::Kind::Variable, param.get()}, param->loc);
  }
  if (function.body) {
    current_function_ = &function;
    current_info_ = &function_info_[canonical_decl];
    loop_depth_ = 0;
    switch_depth_ = 0;
    analyze_block(*function.body, false);  // parameters and the body's locals share a scope
    // After an error the tree may have lost statements (the parser drops what it cannot read),
    // so the warning would only add noise.
    if (!function.return_type.is_void() && !function.return_type.is_error() && !diag_.has_errors() &&
        !always_returns(*this, function.body.get(), 0)) {
      diag_.warning(function.loc, "not all paths return a value");
    }
    current_function_ = nullptr;
    current_info_ = nullptr;
  }
  pop_scope();
}

// ---------------------------------------------------------------------------------------------
// Statements

void Sema::analyze_attributes(std::vector<Attribute>& attributes) {
  for (Attribute& attribute : attributes) {
    for (ExprPtr& arg : attribute.args) analyze(arg.get());
  }
}

void Sema::analyze_condition(ExprPtr& condition) {
  const Type type = analyze(condition.get());
  if (!condition || type.is_error()) return;
  if (type.is_numeric() && type.component_count() > 1) {
    diag_.error(condition->loc, "condition must be a scalar, not " + in_quotes(type.name()) + "; use any() or all()");
    return;
  }
  coerce(condition, Type::scalar(ScalarType::Bool));
}

void Sema::analyze_block(BlockStmt& block, bool new_scope) {
  if (new_scope) push_scope();
  for (StmtPtr& stmt : block.statements) analyze_stmt(stmt.get());
  if (new_scope) pop_scope();
}

void Sema::analyze_stmt(Stmt* stmt) {
  if (!stmt) return;
  DepthGuard guard(*this);
  if (nesting_exceeded(stmt->loc)) return;
  analyze_attributes(stmt->attributes);
  // A statement that is a branch or a loop body gets a scope of its own (`if (c) float x = 1;`).
  auto scoped = [&](Stmt* child) {
    push_scope();
    analyze_stmt(child);
    pop_scope();
  };
  switch (stmt->kind) {
    case StmtKind::Block: analyze_block(static_cast<BlockStmt&>(*stmt), true); break;
    case StmtKind::Expr: analyze(static_cast<ExprStmt&>(*stmt).expr.get()); break;
    case StmtKind::Decl:
      for (auto& var : static_cast<DeclStmt&>(*stmt).vars) {
        if (var) analyze_local_var(*var);
      }
      break;
    case StmtKind::If: {
      auto& branch = static_cast<IfStmt&>(*stmt);
      analyze_condition(branch.condition);
      scoped(branch.then_branch.get());
      scoped(branch.else_branch.get());
      break;
    }
    case StmtKind::For: {
      auto& loop = static_cast<ForStmt&>(*stmt);
      push_scope();  // the init's variables live in the loop
      analyze_stmt(loop.init.get());
      if (loop.condition) analyze_condition(loop.condition);
      analyze(loop.step.get());
      ++loop_depth_;
      scoped(loop.body.get());
      --loop_depth_;
      pop_scope();
      break;
    }
    case StmtKind::While: {
      auto& loop = static_cast<WhileStmt&>(*stmt);
      analyze_condition(loop.condition);
      ++loop_depth_;
      scoped(loop.body.get());
      --loop_depth_;
      break;
    }
    case StmtKind::DoWhile: {
      auto& loop = static_cast<DoWhileStmt&>(*stmt);
      ++loop_depth_;
      scoped(loop.body.get());
      --loop_depth_;
      analyze_condition(loop.condition);
      break;
    }
    case StmtKind::Switch: {
      auto& sw = static_cast<SwitchStmt&>(*stmt);
      const Type type = analyze(sw.condition.get());
      if (sw.condition && !type.is_error()) {
        if (type.component_count() == 1 && type.is_floating()) {
          // fxc converts a floating-point condition to int, as a cast does (toward zero); DXC
          // refuses it. Unity's own shaders switch on a float so, and Unity compiles with fxc.
          diag_.warning(sw.condition->loc, "the condition of a switch is " + in_quotes(type.name()) +
                                               ": converted to int toward zero, as fxc does (DXC refuses it); "
                                               "write (int)(...) to say so");
          wrap_conversion(sw.condition, Type::scalar(ScalarType::Int));
        } else if (!type.is_numeric() || type.component_count() != 1 || !(type.is_integer() || type.is_bool())) {
          diag_.error(sw.condition->loc,
                      "the condition of a switch must be an integer scalar, not " + in_quotes(type.name()));
        } else if (!type.is_integer() || !type.is_scalar()) {
          wrap_conversion(sw.condition, Type::scalar(type.is_integer() ? type.scalar_type() : ScalarType::Int));
        }
      }
      std::unordered_map<int64_t, Loc> seen;
      bool has_default = false;
      push_scope();  // the cases share one scope, as in C
      ++switch_depth_;
      for (SwitchCase& c : sw.cases) {
        if (c.value) {
          analyze(c.value.get());
          const std::optional<int64_t> value = c.value->type.is_error() ? std::nullopt : fold_int(c.value.get());
          if (!c.value->type.is_error() && (!value || !c.value->type.is_integer())) {
            diag_.error(c.value->loc, "a case value must be an integer constant");
          } else if (value && !seen.emplace(*value, c.loc).second) {
            diag_.error(c.loc, "case value " + std::to_string(*value) + " appears twice");
            diag_.note(seen[*value], "the first is here");
          }
        } else if (has_default) {
          diag_.error(c.loc, "a switch has one 'default'");
        } else {
          has_default = true;
        }
        for (StmtPtr& child : c.statements) analyze_stmt(child.get());
      }
      --switch_depth_;
      pop_scope();
      break;
    }
    case StmtKind::Break:
      if (loop_depth_ == 0 && switch_depth_ == 0)
        diag_.error(stmt->loc, "'break' is only allowed inside a loop or a switch");
      break;
    case StmtKind::Continue:
      if (loop_depth_ == 0) diag_.error(stmt->loc, "'continue' is only allowed inside a loop");
      break;
    case StmtKind::Return: {
      auto& ret = static_cast<ReturnStmt&>(*stmt);
      const Type value = analyze(ret.value.get());
      if (!current_function_) break;
      const Type& expected = current_function_->return_type;
      if (expected.is_error()) break;
      if (expected.is_void()) {
        if (ret.value && !value.is_error()) {
          diag_.error(ret.value->loc, "void function " + in_quotes(current_function_->name) + " cannot return a value");
        }
      } else if (!ret.value) {
        diag_.error(stmt->loc,
                    in_quotes(current_function_->name) + " must return a value of type " + in_quotes(expected.name()));
      } else {
        coerce(ret.value, expected);
      }
      break;
    }
    case StmtKind::Discard: note_fragment_only("'discard'", stmt->loc); break;
    case StmtKind::Empty: break;
  }
}

// ---------------------------------------------------------------------------------------------
// The call graph

void Sema::check_recursion() {
  // Depth-first search over canonical functions; a call to a function still on the path closes
  // a cycle. Iterative, so that a long chain of calls cannot overflow the stack. The marks live
  // in the functions' FunctionInfo, which every canonical function has.
  enum Mark : uint8_t { kUnvisited, kOnPath, kDone };
  struct Frame {
    const FunctionDecl* function;
    FunctionInfo* info;
    size_t next_call;
  };
  std::vector<Frame> stack;
  for (const FunctionDecl* root : all_functions_) {
    const FunctionDecl* canonical = canonical_of_[root];
    if (!canonical) continue;
    FunctionInfo& root_info = function_info_[canonical];
    if (root_info.recursion_mark != kUnvisited) continue;
    stack.push_back({canonical, &root_info, 0});
    root_info.recursion_mark = kOnPath;
    while (!stack.empty()) {
      Frame& frame = stack.back();
      if (frame.next_call >= frame.info->calls.size()) {
        frame.info->recursion_mark = kDone;
        stack.pop_back();
        continue;
      }
      const FunctionInfo::Call& call = frame.info->calls[frame.next_call++];
      FunctionInfo& callee = function_info_[call.callee];
      if (callee.recursion_mark == kOnPath) {
        diag_.error(call.loc, "recursive call to " + in_quotes(call.callee->name) + " is not supported");
      } else if (callee.recursion_mark == kUnvisited) {
        callee.recursion_mark = kOnPath;
        stack.push_back({call.callee, &callee, 0});
      }
    }
  }
}

void Sema::fix_up_calls() {
  for (FunctionDecl* function : all_functions_) {
    const FunctionDecl* canonical = canonical_of_[function];
    const FunctionInfo& info = function_info_[canonical];
    if (!function->body && info.definition) function->definition = info.definition;
  }
  for (CallExpr* call : user_calls_) {
    const FunctionInfo& info = function_info_[call->function];
    if (info.definition) call->function = info.definition;
  }
  for (const FunctionDecl* function : all_functions_) {
    if (canonical_of_[function] != function) continue;
    const FunctionInfo& info = function_info_[function];
    if (info.called && !info.definition) {
      diag_.error(info.first_call, "function " + in_quotes(function->name) + " is called but never defined");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Entry points

// DXC's rule (SemaHLSL.cpp, DiagnoseTranslationUnit): the entry point's name must name one
// function. Declarations of one parameter list are one function (a prototype and its
// definition); two parameter lists are two functions, and then the name is ambiguous whether
// or not each has a body, since nothing in the pragma says which one is meant.
const FunctionDecl* Sema::find_entry_point(const std::string& name, Loc pragma_loc, const char* stage) {
  if (name.empty()) return nullptr;
  auto it = functions_.find(name);
  if (it == functions_.end() || it->second.empty()) {
    diag_.error(pragma_loc, "entry point " + in_quotes(name) + " is not defined");
    return nullptr;
  }
  // Each function by its definition where it has one, or else its first declaration.
  std::vector<const FunctionDecl*> overloads;
  for (const FunctionDecl* canonical : it->second) {
    const FunctionDecl* definition = function_info_[canonical].definition;
    overloads.push_back(definition ? definition : canonical);
  }
  if (overloads.size() > 1) {
    const FunctionDecl& first = *overloads[0];
    const FunctionDecl& second = *overloads[1];
    const auto kind = [](const FunctionDecl& f) { return f.body ? "defined" : "declared"; };
    diag_.error(second.loc, std::string(stage) + " entry point " + in_quotes(name) + " is ambiguous: '" +
                                function_signature(second) + "' is " + kind(second) + " here and '" +
                                function_signature(first) + "' at " + diag_.sources().resolve(first.loc).to_string() +
                                "; an entry point cannot be overloaded: rename or remove all but one of them");
    for (const FunctionDecl* other : overloads)
      if (other != &second) diag_.note(other->loc, "'" + function_signature(*other) + "' is " + kind(*other) + " here");
    diag_.note(pragma_loc, "named the " + std::string(stage) + " entry point here");
    return nullptr;
  }
  const FunctionDecl* definition = function_info_[it->second[0]].definition;
  if (!definition) {
    diag_.error(pragma_loc, "entry point " + in_quotes(name) + " is not defined");
    diag_.note(it->second[0]->loc,
               "'" + function_signature(*it->second[0]) + "' is declared here, without a body; give it one");
  }
  return definition;
}

void Sema::check_entry_point(const FunctionDecl& function, bool vertex) {
  const Stage stage = vertex ? Stage::Vertex : Stage::Fragment;
  const char* stage_name = vertex ? "vertex" : "fragment";
  bool outputs_position = false, outputs_target = false, return_failed = false;
  std::unordered_map<std::string, Loc> seen[2];  // inputs, outputs
  auto report = [&](Loc loc, const std::string& message) {
    const std::string key =
        std::to_string(loc.file) + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) + ":" + message;
    if (reported_.insert(key).second) diag_.error(loc, message);
  };
  // One value crossing the stage boundary: a parameter, a field of a struct, the return value.
  struct Item {
    const Type* type;
    const std::string* semantic;
    Loc semantic_loc;
    // Reported as "input 'uv'" (role and quoted name), or the bare name when no role.
    std::string_view role;
    std::string_view name;
    Loc loc;
    int depth;
  };
  auto check = [&](const Type& root_type, const std::string& root_semantic, Loc root_semantic_loc,
                   std::string_view root_role, std::string_view root_name, Loc root_loc, bool input) {
    std::vector<Item> items{{&root_type, &root_semantic, root_semantic_loc, root_role, root_name, root_loc, 0}};
    size_t budget = 4096;  // far beyond a real signature; a hostile one stops here
    while (!items.empty()) {
      if (--budget == 0) {
        report(function.loc, "entry point " + in_quotes(function.name) + " has too many inputs or outputs");
        return;
      }
      const Item item = items.back();
      items.pop_back();
      const Type& type = *item.type;
      if (type.is_error()) {
        if (!input) return_failed = true;
        continue;
      }
      if (type.kind() == TypeKind::Struct && type.struct_decl() && item.depth < kMaxNesting) {
        const auto& fields = type.struct_decl()->fields;
        for (auto field = fields.rbegin(); field != fields.rend(); ++field) {
          items.push_back({&field->type, &field->semantic, field->semantic_loc, input ? "input " : "output ",
                           field->name, field->loc, item.depth + 1});
        }
        continue;
      }
      if (item.semantic->empty()) {
        const std::string name =
            item.role.empty() ? std::string(item.name) : std::string(item.role) + in_quotes(item.name);
        report(item.loc, name + " of entry point " + in_quotes(function.name) + " needs a semantic");
        continue;
      }
      const ParsedSemantic semantic = parse_semantic(*item.semantic);
      if (semantic.kind == SemanticKind::Unknown) {
        report(item.semantic_loc, "unknown semantic " + in_quotes(*item.semantic) +
                                      ": a system value's name starts SV_ and names one of Direct3D's, any other "
                                      "identifier (with an index of at most two digits) names a varying");
        continue;
      }
      if (semantic.kind == SemanticKind::User) {
        // Any identifier is a semantic, so a misspelt TEXCOORD0 is one too: worth a warning.
        const std::string key = "user semantic " + std::to_string(item.semantic_loc.file) + ":" +
                                std::to_string(item.semantic_loc.line) + ":" + std::to_string(item.semantic_loc.column);
        // Closer than base/spelling's nearest: PREVPOSITION is a name of its own, not a typo.
        std::optional<std::string_view> meant;
        for (std::string_view known : {"POSITION", "NORMAL", "TANGENT", "BINORMAL", "TEXCOORD", "COLOR"})
          if (edit_distance(semantic.user_name, known) <= (known.size() >= 6 ? 2u : 1u)) meant = known;
        if (meant && reported_.insert(key).second)
          diag_.warning(item.semantic_loc, in_quotes(*item.semantic) + " is a user-defined semantic; did you mean " +
                                               in_quotes(std::string(*meant) + std::to_string(semantic.index)) + "?");
      }
      if (!semantic_allowed(semantic.kind, stage, input)) {
        report(item.semantic_loc, "semantic " + in_quotes(*item.semantic) + " is not allowed on a " + stage_name +
                                      " shader " + (input ? "input" : "output"));
        continue;
      }
      if (auto needed = required_type(semantic.kind, type)) {
        report(item.loc, "semantic " + in_quotes(*item.semantic) + " needs " +
                             (needed->front() == 'a' ? "" : "type '") + *needed + (needed->front() == 'a' ? "" : "'") +
                             ", not " + in_quotes(type.name()));
        continue;
      }
      const std::string canonical = canonical_semantic(semantic);
      if (!seen[input ? 0 : 1].emplace(canonical, item.semantic_loc).second) {
        report(item.semantic_loc, "semantic " + in_quotes(*item.semantic) + " is used twice in the " +
                                      (input ? "inputs" : "outputs") + " of entry point " + in_quotes(function.name));
        continue;
      }
      if (!input && vertex && (semantic.kind == SemanticKind::SvPosition || is_clip_position_alias(semantic, type))) {
        outputs_position = true;
      }
      if (!input && !vertex &&
          (semantic.kind == SemanticKind::SvTarget || semantic.kind == SemanticKind::SvDepth ||
           semantic.kind == SemanticKind::Color)) {
        outputs_target = true;
      }
    }
  };
  for (const auto& param : function.params) {
    if (!param || param->is_uniform || param->type.is_resource()) continue;
    if (param->direction != ParamDirection::Out) {
      check(param->type, param->semantic, param->semantic_loc, "input ", param->name, param->loc, true);
    }
    if (param->direction != ParamDirection::In) {
      check(param->type, param->semantic, param->semantic_loc, "output ", param->name, param->loc, false);
    }
  }
  if (!function.return_type.is_void()) {
    check(function.return_type, function.semantic, function.semantic_loc, "", "return value", function.loc, false);
  }
  if (vertex && !outputs_position && !return_failed) {
    report(function.loc, "vertex entry point " + in_quotes(function.name) + " does not output SV_Position");
  }
  if (!vertex && !outputs_target && !return_failed) {
    report(function.loc, "fragment entry point " + in_quotes(function.name) + " does not output SV_Target or SV_Depth");
  }
}

void Sema::check_fragment_only_reachable(const FunctionDecl& vertex_entry) {
  const FunctionDecl* root = canonical_of_[&vertex_entry];
  if (!root) return;
  std::unordered_set<const FunctionDecl*> visited{root};
  std::vector<const FunctionDecl*> stack{root};
  while (!stack.empty()) {
    const FunctionDecl* function = stack.back();
    stack.pop_back();
    const FunctionInfo& info = function_info_[function];
    for (const FunctionInfo::Use& use : info.fragment_only_uses) {
      diag_.error(use.loc, use.what + " is only available in fragment shaders");
    }
    for (const FunctionInfo::Call& call : info.calls) {
      if (visited.insert(call.callee).second) stack.push_back(call.callee);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The driver

EntryPoints Sema::run(TranslationUnit& unit, const EntryPointNames& names) {
  for (const auto& decl : unit.decls) {
    if (decl && decl->kind == DeclKind::Function) all_function_names_.insert(decl->name);
  }
  push_scope();
  for (auto& decl : unit.decls) {
    if (!decl) continue;
    switch (decl->kind) {
      case DeclKind::Struct: declare_struct(static_cast<StructDecl&>(*decl)); break;
      case DeclKind::Typedef: declare_typedef(static_cast<TypedefDecl&>(*decl)); break;
      case DeclKind::Var: declare_global_var(static_cast<VarDecl&>(*decl), false); break;
      case DeclKind::CBuffer: declare_cbuffer(static_cast<CBufferDecl&>(*decl)); break;
      case DeclKind::Function: declare_function(static_cast<FunctionDecl&>(*decl)); break;
      case DeclKind::Param: break;
    }
  }
  check_recursion();
  EntryPoints entry_points;
  entry_points.vertex = find_entry_point(names.vertex, names.vertex_loc, "vertex");
  entry_points.fragment = find_entry_point(names.fragment, names.fragment_loc, "fragment");
  if (entry_points.vertex) {
    check_entry_point(*entry_points.vertex, true);
    check_fragment_only_reachable(*entry_points.vertex);
  }
  if (entry_points.fragment) check_entry_point(*entry_points.fragment, false);
  fix_up_calls();
  pop_scope();
  return entry_points;
}

}  // namespace sema_detail

EntryPoints analyze(TranslationUnit& unit, const EntryPointNames& entry_points, DiagnosticEngine& diagnostics) {
  sema_detail::Sema sema(diagnostics);
  return sema.run(unit, entry_points);
}

}  // namespace xshade::hlsl
