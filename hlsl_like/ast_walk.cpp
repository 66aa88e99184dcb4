#include "hlsl_like/ast_walk.h"

#include <unordered_set>

namespace xshade::hlsl {

void walk_expressions(const Expr* expr, const std::function<void(const Expr&)>& visit) {
  if (!expr) return;
  visit(*expr);
  switch (expr->kind) {
    case ExprKind::Unary: walk_expressions(static_cast<const UnaryExpr*>(expr)->operand.get(), visit); break;
    case ExprKind::Binary: {
      auto* e = static_cast<const BinaryExpr*>(expr);
      walk_expressions(e->lhs.get(), visit);
      walk_expressions(e->rhs.get(), visit);
      break;
    }
    case ExprKind::Assign: {
      auto* e = static_cast<const AssignExpr*>(expr);
      walk_expressions(e->target.get(), visit);
      walk_expressions(e->value.get(), visit);
      break;
    }
    case ExprKind::Conditional: {
      auto* e = static_cast<const ConditionalExpr*>(expr);
      walk_expressions(e->condition.get(), visit);
      walk_expressions(e->then_value.get(), visit);
      walk_expressions(e->else_value.get(), visit);
      break;
    }
    case ExprKind::Call: {
      auto* e = static_cast<const CallExpr*>(expr);
      walk_expressions(e->object.get(), visit);
      for (const ExprPtr& arg : e->args) walk_expressions(arg.get(), visit);
      break;
    }
    case ExprKind::Member: walk_expressions(static_cast<const MemberExpr*>(expr)->object.get(), visit); break;
    case ExprKind::Index: {
      auto* e = static_cast<const IndexExpr*>(expr);
      walk_expressions(e->object.get(), visit);
      walk_expressions(e->index.get(), visit);
      break;
    }
    case ExprKind::Cast: walk_expressions(static_cast<const CastExpr*>(expr)->operand.get(), visit); break;
    case ExprKind::InitList:
      for (const ExprPtr& element : static_cast<const InitListExpr*>(expr)->elements)
        walk_expressions(element.get(), visit);
      break;
    case ExprKind::Conversion:
      walk_expressions(static_cast<const ConversionExpr*>(expr)->operand.get(), visit);
      break;
    case ExprKind::IntLiteral:
    case ExprKind::FloatLiteral:
    case ExprKind::BoolLiteral:
    case ExprKind::Name: break;
  }
}

void walk_expressions(const Stmt* stmt, const std::function<void(const Expr&)>& visit) {
  if (!stmt) return;
  switch (stmt->kind) {
    case StmtKind::Block:
      for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) walk_expressions(child.get(), visit);
      break;
    case StmtKind::Expr: walk_expressions(static_cast<const ExprStmt*>(stmt)->expr.get(), visit); break;
    case StmtKind::Decl:
      for (const auto& var : static_cast<const DeclStmt*>(stmt)->vars)
        if (var) walk_expressions(var->initializer.get(), visit);
      break;
    case StmtKind::If: {
      auto* s = static_cast<const IfStmt*>(stmt);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->then_branch.get(), visit);
      walk_expressions(s->else_branch.get(), visit);
      break;
    }
    case StmtKind::For: {
      auto* s = static_cast<const ForStmt*>(stmt);
      walk_expressions(s->init.get(), visit);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->step.get(), visit);
      walk_expressions(s->body.get(), visit);
      break;
    }
    case StmtKind::While: {
      auto* s = static_cast<const WhileStmt*>(stmt);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->body.get(), visit);
      break;
    }
    case StmtKind::DoWhile: {
      auto* s = static_cast<const DoWhileStmt*>(stmt);
      walk_expressions(s->body.get(), visit);
      walk_expressions(s->condition.get(), visit);
      break;
    }
    case StmtKind::Switch: {
      auto* s = static_cast<const SwitchStmt*>(stmt);
      walk_expressions(s->condition.get(), visit);
      for (const SwitchCase& c : s->cases) {
        walk_expressions(c.value.get(), visit);
        for (const StmtPtr& child : c.statements) walk_expressions(child.get(), visit);
      }
      break;
    }
    case StmtKind::Return: walk_expressions(static_cast<const ReturnStmt*>(stmt)->value.get(), visit); break;
    case StmtKind::Break:
    case StmtKind::Continue:
    case StmtKind::Discard:
    case StmtKind::Empty: break;
  }
}

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
