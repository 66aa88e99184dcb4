#include "glsl/lower/trace_sites.h"

namespace xshade::glsl::lower {

using namespace hlsl;

namespace {

std::string place_name_at(const Expr* e, int depth) {
  if (!e || depth > 16) return "a value";
  switch (e->kind) {
    case ExprKind::Name: return static_cast<const NameExpr*>(e)->name;
    case ExprKind::Member: {
      const auto* member = static_cast<const MemberExpr*>(e);
      return place_name_at(member->object.get(), depth + 1) + "." + member->member;
    }
    case ExprKind::Index: return place_name_at(static_cast<const IndexExpr*>(e)->object.get(), depth + 1) + "[...]";
    case ExprKind::Conversion: return place_name_at(static_cast<const ConversionExpr*>(e)->operand.get(), depth + 1);
    default: return "a value";
  }
}

bool reads_uniform_at(const Expr* e, int depth) {
  if (!e || depth > 16) return false;
  switch (e->kind) {
    case ExprKind::Name: {
      const Decl* decl = static_cast<const NameExpr*>(e)->decl;
      if (!decl || decl->kind != DeclKind::Var) return false;
      const auto* var = static_cast<const VarDecl*>(decl);
      return var->is_global && (var->storage == StorageClass::Default || var->storage == StorageClass::Uniform);
    }
    case ExprKind::Index: return reads_uniform_at(static_cast<const IndexExpr*>(e)->object.get(), depth + 1);
    case ExprKind::Member: return reads_uniform_at(static_cast<const MemberExpr*>(e)->object.get(), depth + 1);
    default: return false;
  }
}

bool calls_authors_function(const Expr* e) {
  return e && e->kind == ExprKind::Call && static_cast<const CallExpr*>(e)->call_kind == CallKind::Function;
}

}  // namespace

bool traceable(const Type& type) { return type.is_floating(); }

std::optional<ExpressionSite> expression_site(const Expr* e) {
  if (!e || !traceable(e->type)) return std::nullopt;
  if (e->kind == ExprKind::Assign) {
    const auto* assign = static_cast<const AssignExpr*>(e);
    if (assign->op == AssignOp::Assign && is_tested(assign->value.get())) return std::nullopt;
    return ExpressionSite{
        assign->op == AssignOp::Assign ? TraceSite::Kind::Assignment : TraceSite::Kind::CompoundAssignment,
        place_name(assign->target.get())};
  }
  if (e->kind == ExprKind::Call) {
    const auto* call = static_cast<const CallExpr*>(e);
    if (call->call_kind == CallKind::Intrinsic || call->call_kind == CallKind::Method)
      return ExpressionSite{TraceSite::Kind::Call, call->callee};
  }
  return std::nullopt;
}

bool is_tested(const Expr* e) { return calls_authors_function(e) || expression_site(e).has_value(); }

bool reads_uniform(const Expr* e) { return reads_uniform_at(e, 0); }

std::string place_name(const Expr* e) { return place_name_at(e, 0); }

}  // namespace xshade::glsl::lower
