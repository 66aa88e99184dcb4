// Offset-loop unrolling (unroll_offset_loops.h).
#include "glsl/lower/unroll_offset_loops.h"

#include <cstdlib>

#include "hlsl_like/ast_walk.h"
#include "hlsl_like/intrinsics.h"

namespace xshade::glsl::lower {

using namespace hlsl;

namespace {

// The value of an integer constant expression: literals, arithmetic and const locals or statics
// with constant initializers.
std::optional<int64_t> fold_constant(const Expr* e, int depth = 0) {
  if (!e || depth > 64) return std::nullopt;
  switch (e->kind) {
    case ExprKind::IntLiteral: return int64_t(static_cast<const IntLiteralExpr*>(e)->value);
    case ExprKind::Conversion:
      if (!e->type.is_integer()) return std::nullopt;
      return fold_constant(static_cast<const ConversionExpr*>(e)->operand.get(), depth + 1);
    case ExprKind::Unary: {
      const auto* unary = static_cast<const UnaryExpr*>(e);
      const std::optional<int64_t> value = fold_constant(unary->operand.get(), depth + 1);
      if (!value) return std::nullopt;
      if (unary->op == UnaryOp::Minus) return -*value;
      if (unary->op == UnaryOp::Plus) return *value;
      return std::nullopt;
    }
    case ExprKind::Binary: {
      const auto* binary = static_cast<const BinaryExpr*>(e);
      const std::optional<int64_t> a = fold_constant(binary->lhs.get(), depth + 1);
      const std::optional<int64_t> b = fold_constant(binary->rhs.get(), depth + 1);
      if (!a || !b || std::abs(*a) > (int64_t(1) << 31) || std::abs(*b) > (int64_t(1) << 31)) return std::nullopt;
      switch (binary->op) {
        case BinaryOp::Add: return *a + *b;
        case BinaryOp::Sub: return *a - *b;
        case BinaryOp::Mul: return *a * *b;
        case BinaryOp::Div: return *b == 0 ? std::nullopt : std::optional<int64_t>(*a / *b);
        default: return std::nullopt;
      }
    }
    case ExprKind::Name: {
      const Decl* decl = static_cast<const NameExpr*>(e)->decl;
      if (!decl || decl->kind != DeclKind::Var) return std::nullopt;
      const auto* var = static_cast<const VarDecl*>(decl);
      if (!var->is_const || !var->initializer || (var->is_global && var->storage != StorageClass::Static))
        return std::nullopt;
      return fold_constant(var->initializer.get(), depth + 1);
    }
    default: return std::nullopt;
  }
}

bool names(const Expr* e, const Decl* decl) {
  bool found = false;
  hlsl::walk_expressions(e, [&](const Expr& x) {
    if (x.kind == ExprKind::Name && static_cast<const NameExpr&>(x).decl == decl) found = true;
  });
  return found;
}

// The argument index of a sampling method's texel offset (which GLSL needs constant), or -1.
int offset_argument(const CallExpr& call) {
  if (call.call_kind != CallKind::Method) return -1;
  switch (IntrinsicId(call.intrinsic)) {
    case IntrinsicId::Sample: return 2;
    case IntrinsicId::SampleBias:
    case IntrinsicId::SampleLevel:
    case IntrinsicId::SampleCmp:
    case IntrinsicId::SampleCmpLevelZero: return 3;
    case IntrinsicId::SampleGrad: return 4;
    default: return -1;
  }
}

// Whether `stmt` leaves or skips the loop around it, or writes `var` (not counting nested loops'
// own breaks and continues).
bool disturbs_loop(const Stmt* stmt, const Decl* var, int depth = 0) {
  if (!stmt || depth > 256) return false;
  bool writes = false;
  hlsl::walk_expressions(stmt, [&](const Expr& e) {
    if (e.kind == ExprKind::Assign && names(static_cast<const AssignExpr&>(e).target.get(), var)) writes = true;
    if (e.kind == ExprKind::Unary) {
      const auto& unary = static_cast<const UnaryExpr&>(e);
      if (unary.op >= UnaryOp::PreIncrement && names(unary.operand.get(), var)) writes = true;
    }
  });
  if (writes) return true;
  switch (stmt->kind) {
    case StmtKind::Break:
    case StmtKind::Continue: return true;
    case StmtKind::Block:
      for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements)
        if (disturbs_loop(child.get(), var, depth + 1)) return true;
      return false;
    case StmtKind::If:
      return disturbs_loop(static_cast<const IfStmt*>(stmt)->then_branch.get(), var, depth + 1) ||
             disturbs_loop(static_cast<const IfStmt*>(stmt)->else_branch.get(), var, depth + 1);
    case StmtKind::Switch:  // its breaks are its own; a continue would be the loop's
      for (const SwitchCase& c : static_cast<const SwitchStmt*>(stmt)->cases)
        for (const StmtPtr& child : c.statements)
          if (child && child->kind != StmtKind::Break && disturbs_loop(child.get(), var, depth + 1)) return true;
      return false;
    default: return false;  // inner loops own their breaks
  }
}

}  // namespace

std::optional<std::vector<int64_t>> unrolled_values(const ForStmt& loop) {
  // for (int i = A; i < B; ++i): the form whose trip is known when compiling.
  if (!loop.init || loop.init->kind != StmtKind::Decl || !loop.condition || !loop.step) return std::nullopt;
  const auto& vars = static_cast<const DeclStmt&>(*loop.init).vars;
  if (vars.size() != 1 || !vars[0] || !vars[0]->type.is_scalar() || !vars[0]->type.is_integer()) return std::nullopt;
  const VarDecl* var = vars[0].get();
  // Only where GLSL needs it: the variable is a sampling method's texel offset in the body.
  bool feeds_offset = false;
  hlsl::walk_expressions(loop.body.get(), [&](const Expr& e) {
    if (e.kind != ExprKind::Call) return;
    const auto& call = static_cast<const CallExpr&>(e);
    const int index = offset_argument(call);
    if (index >= 0 && size_t(index) < call.args.size() && names(call.args[size_t(index)].get(), var))
      feeds_offset = true;
  });
  if (!feeds_offset) return std::nullopt;
  const std::optional<int64_t> first = fold_constant(var->initializer.get());
  if (!first) return std::nullopt;
  const Expr* condition = loop.condition.get();
  while (condition->kind == ExprKind::Conversion)
    condition = static_cast<const ConversionExpr*>(condition)->operand.get();
  if (condition->kind != ExprKind::Binary) return std::nullopt;
  const auto& compare = static_cast<const BinaryExpr&>(*condition);
  auto is_var = [&](const Expr* e) {
    while (e && e->kind == ExprKind::Conversion) e = static_cast<const ConversionExpr*>(e)->operand.get();
    return e && e->kind == ExprKind::Name && static_cast<const NameExpr*>(e)->decl == var;
  };
  BinaryOp op = compare.op;
  std::optional<int64_t> bound;
  if (is_var(compare.lhs.get())) {
    bound = fold_constant(compare.rhs.get());
  } else if (is_var(compare.rhs.get())) {
    bound = fold_constant(compare.lhs.get());
    op = op == BinaryOp::Less           ? BinaryOp::Greater
         : op == BinaryOp::Greater      ? BinaryOp::Less
         : op == BinaryOp::LessEqual    ? BinaryOp::GreaterEqual
         : op == BinaryOp::GreaterEqual ? BinaryOp::LessEqual
                                        : op;
  }
  if (!bound) return std::nullopt;
  int64_t step = 0;
  const Expr* step_expr = loop.step.get();
  if (step_expr->kind == ExprKind::Unary) {
    const auto& unary = static_cast<const UnaryExpr&>(*step_expr);
    if (!is_var(unary.operand.get())) return std::nullopt;
    if (unary.op == UnaryOp::PreIncrement || unary.op == UnaryOp::PostIncrement) step = 1;
    if (unary.op == UnaryOp::PreDecrement || unary.op == UnaryOp::PostDecrement) step = -1;
  } else if (step_expr->kind == ExprKind::Assign) {
    const auto& assign = static_cast<const AssignExpr&>(*step_expr);
    const std::optional<int64_t> amount = fold_constant(assign.value.get());
    if (!is_var(assign.target.get()) || !amount) return std::nullopt;
    if (assign.op == AssignOp::Add) step = *amount;
    if (assign.op == AssignOp::Sub) step = -*amount;
  }
  if (step == 0 || disturbs_loop(loop.body.get(), var)) return std::nullopt;
  std::vector<int64_t> values;
  for (int64_t i = *first; values.size() <= kMaxUnrolledIterations; i += step) {
    const bool go = op == BinaryOp::Less           ? i < *bound
                    : op == BinaryOp::LessEqual    ? i <= *bound
                    : op == BinaryOp::Greater      ? i > *bound
                    : op == BinaryOp::GreaterEqual ? i >= *bound
                    : op == BinaryOp::NotEqual     ? i != *bound
                                                   : false;
    if (!go) return values;
    values.push_back(i);
  }
  return std::nullopt;  // too long to unroll
}

UnrolledLoops unroll_offset_loops(const std::vector<const FunctionDecl*>& functions) {
  UnrolledLoops loops;
  for (const FunctionDecl* function : functions)
    hlsl::walk_statements(function->body.get(), [&](const Stmt& stmt) {
      if (stmt.kind != StmtKind::For) return;
      const auto& loop = static_cast<const ForStmt&>(stmt);
      if (std::optional<std::vector<int64_t>> values = unrolled_values(loop)) loops.emplace(&loop, std::move(*values));
    });
  return loops;
}

}  // namespace xshade::glsl::lower
