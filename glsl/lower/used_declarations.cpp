// What a stage declares (used_declarations.h).
#include "glsl/lower/used_declarations.h"

#include <unordered_map>

#include "hlsl_like/ast_walk.h"

namespace xshade::glsl::lower {

using namespace hlsl;

namespace {

const FunctionDecl* defined(const FunctionDecl* function) {
  return function->definition ? function->definition : function;
}

}  // namespace

UsedDeclarations used_declarations(const Module& module, const FunctionDecl* entry) {
  UsedDeclarations used;
  std::vector<const StructDecl*> struct_queue;
  auto use_type = [&](const Type& type) {
    const Type* base = &type;
    for (int depth = 0; base->kind() == TypeKind::Array && depth < 64; ++depth) base = &base->element();
    if (base->kind() == TypeKind::Struct && base->struct_decl() && used.structs.insert(base->struct_decl()).second)
      struct_queue.push_back(base->struct_decl());
  };
  auto named_static = [](const Expr& expr) -> const VarDecl* {
    if (expr.kind != ExprKind::Name) return nullptr;
    const Decl* decl = static_cast<const NameExpr&>(expr).decl;
    if (!decl || decl->kind != DeclKind::Var) return nullptr;
    const auto* var = static_cast<const VarDecl*>(decl);
    // groupshared goes with them, to be refused where it is reached.
    const bool is_static = var->storage == StorageClass::Static || var->storage == StorageClass::GroupShared;
    return var->is_global && is_static ? var : nullptr;
  };

  // One walk of each function's body finds what the rest asks of it: the functions it calls
  // (as hlsl::reachable_functions counts them) and the statics it names, in order; the types
  // of its expressions make their structs used as it goes.
  struct FunctionUses {
    std::vector<const FunctionDecl*> callees;
    std::vector<const VarDecl*> statics;
  };
  std::unordered_map<const FunctionDecl*, FunctionUses> uses;
  auto uses_of = [&](const FunctionDecl* function) -> const FunctionUses& {
    auto [known, inserted] = uses.try_emplace(function);
    if (inserted) {
      FunctionUses& found = known->second;
      auto visit = [&](const Expr& expr) {
        use_type(expr.type);
        if (const VarDecl* var = named_static(expr)) {
          found.statics.push_back(var);
        } else if (expr.kind == ExprKind::Call) {
          const auto& call = static_cast<const CallExpr&>(expr);
          if (call.call_kind == CallKind::Function && call.function) found.callees.push_back(defined(call.function));
        }
      };
      hlsl::walk_expressions(function->body.get(), visit);
    }
    return known->second;
  };
  // hlsl::reachable_functions, from the walks above: callees before callers, `root` last.
  auto reachable = [&](const FunctionDecl* root_decl) {
    std::vector<const FunctionDecl*> order;
    const FunctionDecl* root = defined(root_decl);
    struct Frame {
      const FunctionDecl* function;
      const std::vector<const FunctionDecl*>* callees;
      size_t next = 0;
    };
    std::unordered_set<const FunctionDecl*> visited{root};
    std::vector<Frame> stack{{root, &uses_of(root).callees}};
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.next < top.callees->size()) {
        const FunctionDecl* callee = (*top.callees)[top.next++];
        if (visited.insert(callee).second) stack.push_back({callee, &uses_of(callee).callees});
        continue;
      }
      order.push_back(top.function);
      stack.pop_back();
    }
    return order;
  };

  // Functions the entry point reaches, then those that static initializers call.
  std::unordered_set<const FunctionDecl*> seen;
  std::vector<const FunctionDecl*> to_scan;
  auto add_tree = [&](const FunctionDecl* root) {
    for (const FunctionDecl* function : reachable(root)) {
      if (seen.insert(function).second) {
        used.functions.push_back(function);
        to_scan.push_back(function);
      }
    }
  };
  std::unordered_set<const Decl*> used_statics;
  std::vector<const VarDecl*> statics_to_scan;
  auto use_static = [&](const VarDecl* var) {
    if (used_statics.insert(var).second) statics_to_scan.push_back(var);
  };
  auto visit_initializer = [&](const Expr& expr) {
    if (const VarDecl* var = named_static(expr)) {
      use_static(var);
    } else if (expr.kind == ExprKind::Call) {
      const auto& call = static_cast<const CallExpr&>(expr);
      // A function seen already came with everything it reaches: its tree adds nothing.
      if (call.call_kind == CallKind::Function && call.function && !seen.count(defined(call.function)))
        add_tree(call.function);
    }
  };
  if (entry) add_tree(entry);
  while (!to_scan.empty() || !statics_to_scan.empty()) {
    if (!to_scan.empty()) {
      // Its calls add nothing: what it calls came in the same tree.
      const FunctionDecl* function = to_scan.back();
      to_scan.pop_back();
      for (const VarDecl* var : uses_of(function).statics) use_static(var);
    } else {
      const VarDecl* var = statics_to_scan.back();
      statics_to_scan.pop_back();
      hlsl::walk_expressions(var->initializer.get(), visit_initializer);
    }
  }
  for (const auto& decl : module.unit.decls)
    if (decl && used_statics.count(decl.get())) used.statics.push_back(static_cast<const VarDecl*>(decl.get()));

  // The structs those use, with the structs inside them: only these are declared, so that an
  // unreached struct of what this target cannot hold does not matter. (The types of the
  // functions' expressions were taken as their bodies were walked above.)
  for (const FunctionDecl* function : used.functions) {
    use_type(function->return_type);
    for (const auto& param : function->params)
      if (param) use_type(param->type);
    hlsl::walk_statements(function->body.get(), [&](const Stmt& stmt) {
      if (stmt.kind == StmtKind::Decl)
        for (const auto& var : static_cast<const DeclStmt&>(stmt).vars)
          if (var) use_type(var->type);
    });
  }
  for (const VarDecl* var : used.statics) use_type(var->type);
  for (const ConstantBuffer& buffer : module.reflection.constant_buffers)
    for (const ConstantBufferMember& member : buffer.members) use_type(member.type);
  while (!struct_queue.empty()) {
    const StructDecl* decl = struct_queue.back();
    struct_queue.pop_back();
    for (const FieldDecl& field : decl->fields) use_type(field.type);
  }
  return used;
}

}  // namespace xshade::glsl::lower
