#include "hlsl_like/ast_walk.h"

#include <unordered_set>

namespace xshade::hlsl {

std::vector<const FunctionDecl*> reachable_functions(const FunctionDecl* entry) {
  std::vector<const FunctionDecl*> order;
  if (!entry) return order;
  std::unordered_set<const FunctionDecl*> seen;
  // Depth-first with an explicit stack; sema rejects recursion, and `seen` ends any cycle anyway.
  struct Frame {
    const FunctionDecl* function;
    std::vector<const FunctionDecl*> callees;
    size_t next = 0;
  };
  auto callees_of = [](const FunctionDecl* function) {
    std::vector<const FunctionDecl*> callees;
    const FunctionDecl* body_owner = function->definition ? function->definition : function;
    walk_expressions(body_owner->body.get(), [&](const Expr& expr) {
      if (expr.kind != ExprKind::Call) return;
      const auto& call = static_cast<const CallExpr&>(expr);
      if (call.call_kind == CallKind::Function && call.function) {
        const FunctionDecl* callee = call.function->definition ? call.function->definition : call.function;
        callees.push_back(callee);
      }
    });
    return callees;
  };
  const FunctionDecl* root = entry->definition ? entry->definition : entry;
  std::vector<Frame> stack;
  seen.insert(root);
  stack.push_back({root, callees_of(root)});
  while (!stack.empty()) {
    Frame& top = stack.back();
    if (top.next < top.callees.size()) {
      const FunctionDecl* callee = top.callees[top.next++];
      if (seen.insert(callee).second) stack.push_back({callee, callees_of(callee)});
      continue;
    }
    order.push_back(top.function);
    stack.pop_back();
  }
  return order;
}

}  // namespace xshade::hlsl
