// Every expression of a statement tree, in hlsl::walk_expressions's order (parents before
// children, null children skipped), with the visitor called directly: the emitter walks every
// function of a stage, and a std::function call per expression cost as much as the rest of
// the walk.
#pragma once

#include "hlsl_like/ast.h"

namespace xshade::glsl::detail {

template <class Visit>
void each_expression(const hlsl::Expr* expr, const Visit& visit) {
  if (!expr) return;
  visit(*expr);
  switch (expr->kind) {
    case hlsl::ExprKind::Unary: each_expression(static_cast<const hlsl::UnaryExpr*>(expr)->operand.get(), visit); break;
    case hlsl::ExprKind::Binary: {
      const auto* e = static_cast<const hlsl::BinaryExpr*>(expr);
      each_expression(e->lhs.get(), visit);
      each_expression(e->rhs.get(), visit);
      break;
    }
    case hlsl::ExprKind::Assign: {
      const auto* e = static_cast<const hlsl::AssignExpr*>(expr);
      each_expression(e->target.get(), visit);
      each_expression(e->value.get(), visit);
      break;
    }
    case hlsl::ExprKind::Conditional: {
      const auto* e = static_cast<const hlsl::ConditionalExpr*>(expr);
      each_expression(e->condition.get(), visit);
      each_expression(e->then_value.get(), visit);
      each_expression(e->else_value.get(), visit);
      break;
    }
    case hlsl::ExprKind::Call: {
      const auto* e = static_cast<const hlsl::CallExpr*>(expr);
      each_expression(e->object.get(), visit);
      for (const hlsl::ExprPtr& arg : e->args) each_expression(arg.get(), visit);
      break;
    }
    case hlsl::ExprKind::Member:
      each_expression(static_cast<const hlsl::MemberExpr*>(expr)->object.get(), visit);
      break;
    case hlsl::ExprKind::Index: {
      const auto* e = static_cast<const hlsl::IndexExpr*>(expr);
      each_expression(e->object.get(), visit);
      each_expression(e->index.get(), visit);
      break;
    }
    case hlsl::ExprKind::Cast: each_expression(static_cast<const hlsl::CastExpr*>(expr)->operand.get(), visit); break;
    case hlsl::ExprKind::InitList:
      for (const hlsl::ExprPtr& element : static_cast<const hlsl::InitListExpr*>(expr)->elements)
        each_expression(element.get(), visit);
      break;
    case hlsl::ExprKind::Conversion:
      each_expression(static_cast<const hlsl::ConversionExpr*>(expr)->operand.get(), visit);
      break;
    case hlsl::ExprKind::IntLiteral:
    case hlsl::ExprKind::FloatLiteral:
    case hlsl::ExprKind::BoolLiteral:
    case hlsl::ExprKind::Name: break;
  }
}

template <class Visit>
void each_expression(const hlsl::Stmt* stmt, const Visit& visit) {
  if (!stmt) return;
  switch (stmt->kind) {
    case hlsl::StmtKind::Block:
      for (const hlsl::StmtPtr& child : static_cast<const hlsl::BlockStmt*>(stmt)->statements)
        each_expression(child.get(), visit);
      break;
    case hlsl::StmtKind::Expr: each_expression(static_cast<const hlsl::ExprStmt*>(stmt)->expr.get(), visit); break;
    case hlsl::StmtKind::Decl:
      for (const auto& var : static_cast<const hlsl::DeclStmt*>(stmt)->vars)
        if (var) each_expression(var->initializer.get(), visit);
      break;
    case hlsl::StmtKind::If: {
      const auto* s = static_cast<const hlsl::IfStmt*>(stmt);
      each_expression(s->condition.get(), visit);
      each_expression(s->then_branch.get(), visit);
      each_expression(s->else_branch.get(), visit);
      break;
    }
    case hlsl::StmtKind::For: {
      const auto* s = static_cast<const hlsl::ForStmt*>(stmt);
      each_expression(s->init.get(), visit);
      each_expression(s->condition.get(), visit);
      each_expression(s->step.get(), visit);
      each_expression(s->body.get(), visit);
      break;
    }
    case hlsl::StmtKind::While: {
      const auto* s = static_cast<const hlsl::WhileStmt*>(stmt);
      each_expression(s->condition.get(), visit);
      each_expression(s->body.get(), visit);
      break;
    }
    case hlsl::StmtKind::DoWhile: {
      const auto* s = static_cast<const hlsl::DoWhileStmt*>(stmt);
      each_expression(s->body.get(), visit);
      each_expression(s->condition.get(), visit);
      break;
    }
    case hlsl::StmtKind::Switch: {
      const auto* s = static_cast<const hlsl::SwitchStmt*>(stmt);
      each_expression(s->condition.get(), visit);
      for (const hlsl::SwitchCase& c : s->cases) {
        each_expression(c.value.get(), visit);
        for (const hlsl::StmtPtr& child : c.statements) each_expression(child.get(), visit);
      }
      break;
    }
    case hlsl::StmtKind::Return: each_expression(static_cast<const hlsl::ReturnStmt*>(stmt)->value.get(), visit); break;
    case hlsl::StmtKind::Break:
    case hlsl::StmtKind::Continue:
    case hlsl::StmtKind::Discard:
    case hlsl::StmtKind::Empty: break;
  }
}

}  // namespace xshade::glsl::detail
