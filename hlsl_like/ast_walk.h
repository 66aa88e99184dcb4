// Visiting every expression of a statement tree, and the functions an entry point reaches.
#pragma once

#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/sema.h"

namespace xshade::hlsl {

// Calls `visit` on every expression in `stmt` (or `expr`), parents before children. Null
// children, which a tree with parse errors may have, are skipped. A template rather than a
// std::function: the emitter and reflection walk every function of a stage, and an indirect call
// per expression cost as much as the rest of the walk.
template <class Visit>
void walk_expressions(const Expr* expr, const Visit& visit) {
  if (!expr) return;
  visit(*expr);
  switch (expr->kind) {
    case ExprKind::Unary: walk_expressions(static_cast<const UnaryExpr*>(expr)->operand.get(), visit); break;
    case ExprKind::Binary: {
      const auto* e = static_cast<const BinaryExpr*>(expr);
      walk_expressions(e->lhs.get(), visit);
      walk_expressions(e->rhs.get(), visit);
      break;
    }
    case ExprKind::Assign: {
      const auto* e = static_cast<const AssignExpr*>(expr);
      walk_expressions(e->target.get(), visit);
      walk_expressions(e->value.get(), visit);
      break;
    }
    case ExprKind::Conditional: {
      const auto* e = static_cast<const ConditionalExpr*>(expr);
      walk_expressions(e->condition.get(), visit);
      walk_expressions(e->then_value.get(), visit);
      walk_expressions(e->else_value.get(), visit);
      break;
    }
    case ExprKind::Call: {
      const auto* e = static_cast<const CallExpr*>(expr);
      walk_expressions(e->object.get(), visit);
      for (const ExprPtr& arg : e->args) walk_expressions(arg.get(), visit);
      break;
    }
    case ExprKind::Member: walk_expressions(static_cast<const MemberExpr*>(expr)->object.get(), visit); break;
    case ExprKind::Index: {
      const auto* e = static_cast<const IndexExpr*>(expr);
      walk_expressions(e->object.get(), visit);
      walk_expressions(e->index.get(), visit);
      break;
    }
    case ExprKind::Cast: walk_expressions(static_cast<const CastExpr*>(expr)->operand.get(), visit); break;
    case ExprKind::InitList:
      for (const ExprPtr& element : static_cast<const InitListExpr*>(expr)->elements)
        walk_expressions(element.get(), visit);
      break;
    case ExprKind::Conversion: walk_expressions(static_cast<const ConversionExpr*>(expr)->operand.get(), visit); break;
    case ExprKind::IntLiteral:
    case ExprKind::FloatLiteral:
    case ExprKind::BoolLiteral:
    case ExprKind::Name: break;
  }
}

template <class Visit>
void walk_expressions(const Stmt* stmt, const Visit& visit) {
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
      const auto* s = static_cast<const IfStmt*>(stmt);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->then_branch.get(), visit);
      walk_expressions(s->else_branch.get(), visit);
      break;
    }
    case StmtKind::For: {
      const auto* s = static_cast<const ForStmt*>(stmt);
      walk_expressions(s->init.get(), visit);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->step.get(), visit);
      walk_expressions(s->body.get(), visit);
      break;
    }
    case StmtKind::While: {
      const auto* s = static_cast<const WhileStmt*>(stmt);
      walk_expressions(s->condition.get(), visit);
      walk_expressions(s->body.get(), visit);
      break;
    }
    case StmtKind::DoWhile: {
      const auto* s = static_cast<const DoWhileStmt*>(stmt);
      walk_expressions(s->body.get(), visit);
      walk_expressions(s->condition.get(), visit);
      break;
    }
    case StmtKind::Switch: {
      const auto* s = static_cast<const SwitchStmt*>(stmt);
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

// Calls visit(statement) for `stmt` and every statement inside it (a block's, a branch's, a
// loop's init and body, a switch case's), outer before inner, in source order.
template <class Visit>
void walk_statements(const Stmt* stmt, const Visit& visit) {
  if (!stmt) return;
  visit(*stmt);
  switch (stmt->kind) {
    case StmtKind::Block:
      for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) walk_statements(child.get(), visit);
      break;
    case StmtKind::If:
      walk_statements(static_cast<const IfStmt*>(stmt)->then_branch.get(), visit);
      walk_statements(static_cast<const IfStmt*>(stmt)->else_branch.get(), visit);
      break;
    case StmtKind::For:
      walk_statements(static_cast<const ForStmt*>(stmt)->init.get(), visit);
      walk_statements(static_cast<const ForStmt*>(stmt)->body.get(), visit);
      break;
    case StmtKind::While: walk_statements(static_cast<const WhileStmt*>(stmt)->body.get(), visit); break;
    case StmtKind::DoWhile: walk_statements(static_cast<const DoWhileStmt*>(stmt)->body.get(), visit); break;
    case StmtKind::Switch:
      for (const SwitchCase& c : static_cast<const SwitchStmt*>(stmt)->cases)
        for (const StmtPtr& child : c.statements) walk_statements(child.get(), visit);
      break;
    default: break;
  }
}

// The user functions `entry` calls, directly or not, callees before callers, `entry` last: the
// order a GLSL file must define them in.
std::vector<const FunctionDecl*> reachable_functions(const FunctionDecl* entry);

}  // namespace xshade::hlsl
