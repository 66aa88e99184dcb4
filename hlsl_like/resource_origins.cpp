#include "hlsl_like/resource_origins.h"

#include <map>
#include <set>
#include <unordered_set>

#include "hlsl_like/ast_walk.h"

namespace xshade::hlsl {

namespace {

void collect_paths(const Type& type, std::vector<uint32_t>& prefix, std::vector<std::vector<uint32_t>>& out,
                   int depth) {
  if (depth > 64) return;  // sema has refused deeper nesting already
  if (type.is_resource()) {
    out.push_back(prefix);
    return;
  }
  if (type.kind() != TypeKind::Struct || !type.struct_decl()) return;
  const auto& fields = type.struct_decl()->fields;
  for (uint32_t i = 0; i < fields.size(); ++i) {
    prefix.push_back(i);
    collect_paths(fields[i].type, prefix, out, depth + 1);
    prefix.pop_back();
  }
}

class Resolver {
 public:
  Resolver(DiagnosticEngine& diagnostics, ResourceOrigins& out) : diag_(diagnostics), out_(out) {}

  void function(const FunctionDecl& function) {
    slots_.clear();
    unknown_.clear();
    conditional_ = 0;
    statement(function.body.get());
  }

 private:
  using Slot = std::pair<const Decl*, std::vector<uint32_t>>;

  void error(Loc loc, const std::string& message) {
    if (reported_.insert({loc.file, loc.line, loc.column}).second) diag_.error(loc, message);
  }

  // Where the resource `below` the value `e` comes from.
  std::optional<ResourceOrigin> resolve(const Expr* e, std::vector<uint32_t> below, Loc loc) {
    for (int step = 0; e && step < 256; ++step) {
      switch (e->kind) {
        case ExprKind::Conversion: e = static_cast<const ConversionExpr*>(e)->operand.get(); continue;
        case ExprKind::Member: {
          const auto* member = static_cast<const MemberExpr*>(e);
          if (member->field_index < 0) return std::nullopt;
          below.insert(below.begin(), uint32_t(member->field_index));
          e = member->object.get();
          continue;
        }
        case ExprKind::Name: {
          const Decl* decl = static_cast<const NameExpr*>(e)->decl;
          if (!decl) return std::nullopt;
          const bool local = decl->kind == DeclKind::Var && !static_cast<const VarDecl*>(decl)->is_global;
          if (!local) return ResourceOrigin{decl, below};
          auto it = slots_.find({decl, below});
          if (it == slots_.end() && unknown_.count(decl)) return std::nullopt;  // its giving failed, reported
          if (it == slots_.end()) {
            error(loc, "resource " + in_quotes(describe_slot(decl, below)) +
                           " is read before it is given one: a local resource names a global or a parameter, "
                           "assigned before it is read");
            return std::nullopt;
          }
          return it->second;
        }
        default:
          error(loc, "a resource here must be a variable, a parameter or a field of one, known when compiling");
          return std::nullopt;
      }
    }
    return std::nullopt;
  }

  std::string describe_slot(const Decl* decl, const std::vector<uint32_t>& path) {
    std::string text = decl->name;
    const Type* type = decl->kind == DeclKind::Var ? &static_cast<const VarDecl*>(decl)->type
                                                   : &static_cast<const ParamDecl*>(decl)->type;
    for (uint32_t field : path) {
      if (type->kind() != TypeKind::Struct || !type->struct_decl() || field >= type->struct_decl()->fields.size())
        break;
      const FieldDecl& f = type->struct_decl()->fields[field];
      text += "." + f.name;
      type = &f.type;
    }
    return text;
  }

  // Records where the resources of the read `e` come from.
  void read(const Expr* e) {
    std::vector<ResourceLeaf> leaves;
    for (const std::vector<uint32_t>& path : resource_paths(e->type)) {
      std::optional<ResourceOrigin> origin = resolve(e, path, e->loc);
      if (!origin) return;
      leaves.push_back({path, std::move(*origin)});
    }
    out_[e] = std::move(leaves);
  }

  // `target = value` (or an initializer) for a local holding resources.
  void assign(const Decl* local, std::vector<uint32_t> target_path, const Expr* value, Loc loc) {
    if (conditional_ > 0) {
      unknown_.insert(local);
      error(loc, "resource " + in_quotes(describe_slot(local, target_path)) +
                     " is given inside a branch or a loop; its resource must be known when compiling: give it once, "
                     "before any branch");
      return;
    }
    auto it = out_.find(value);
    if (it == out_.end()) {  // reported; reads of the local would only repeat it
      unknown_.insert(local);
      return;
    }
    for (const ResourceLeaf& leaf : it->second) {
      std::vector<uint32_t> path = target_path;
      path.insert(path.end(), leaf.path.begin(), leaf.path.end());
      slots_[{local, path}] = leaf.origin;
    }
  }

  // Asked of every expression: most are numeric, answered before the walk.
  static bool holds_resources(const Type& type) { return may_hold_resources(type) && !resource_paths(type).empty(); }

  void expression(const Expr* e) {
    if (!e) return;
    if (holds_resources(e->type)) {
      switch (e->kind) {
        case ExprKind::Name:
        case ExprKind::Member:
        case ExprKind::Conversion: read(e); return;
        case ExprKind::Assign: {
          const auto* assignment = static_cast<const AssignExpr*>(e);
          expression(assignment->value.get());
          std::vector<uint32_t> path;
          const Expr* target = assignment->target.get();
          while (target && target->kind == ExprKind::Member) {
            const auto* member = static_cast<const MemberExpr*>(target);
            path.insert(path.begin(), uint32_t(std::max(member->field_index, 0)));
            target = member->object.get();
          }
          if (target && target->kind == ExprKind::Name && static_cast<const NameExpr*>(target)->decl)
            assign(static_cast<const NameExpr*>(target)->decl, path, assignment->value.get(), assignment->target->loc);
          return;
        }
        case ExprKind::Conditional:
          error(e->loc, "'?:' cannot choose between resources here: which one is read must be known when compiling");
          return;
        default: break;
      }
    }
    switch (e->kind) {
      case ExprKind::Unary: expression(static_cast<const UnaryExpr*>(e)->operand.get()); break;
      case ExprKind::Binary:
        expression(static_cast<const BinaryExpr*>(e)->lhs.get());
        expression(static_cast<const BinaryExpr*>(e)->rhs.get());
        break;
      case ExprKind::Assign:
        expression(static_cast<const AssignExpr*>(e)->value.get());
        expression(static_cast<const AssignExpr*>(e)->target.get());
        break;
      case ExprKind::Conditional: {
        const auto* c = static_cast<const ConditionalExpr*>(e);
        expression(c->condition.get());
        expression(c->then_value.get());
        expression(c->else_value.get());
        break;
      }
      case ExprKind::Call: {
        const auto* call = static_cast<const CallExpr*>(e);
        expression(call->object.get());
        for (const ExprPtr& arg : call->args) expression(arg.get());
        break;
      }
      case ExprKind::Member: expression(static_cast<const MemberExpr*>(e)->object.get()); break;
      case ExprKind::Index:
        expression(static_cast<const IndexExpr*>(e)->object.get());
        expression(static_cast<const IndexExpr*>(e)->index.get());
        break;
      case ExprKind::Cast: expression(static_cast<const CastExpr*>(e)->operand.get()); break;
      case ExprKind::InitList:
        for (const ExprPtr& element : static_cast<const InitListExpr*>(e)->elements) expression(element.get());
        break;
      case ExprKind::Conversion: expression(static_cast<const ConversionExpr*>(e)->operand.get()); break;
      default: break;
    }
  }

  void branch(const Stmt* stmt) {
    ++conditional_;
    statement(stmt);
    --conditional_;
  }

  void statement(const Stmt* stmt) {
    if (!stmt) return;
    switch (stmt->kind) {
      case StmtKind::Block:
        for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) statement(child.get());
        break;
      case StmtKind::Expr: expression(static_cast<const ExprStmt*>(stmt)->expr.get()); break;
      case StmtKind::Decl:
        for (const auto& var : static_cast<const DeclStmt*>(stmt)->vars) {
          if (!var || !var->initializer) continue;
          expression(var->initializer.get());
          if (holds_resources(var->type)) assign(var.get(), {}, var->initializer.get(), var->loc);
        }
        break;
      case StmtKind::If: {
        const auto* s = static_cast<const IfStmt*>(stmt);
        expression(s->condition.get());
        branch(s->then_branch.get());
        branch(s->else_branch.get());
        break;
      }
      case StmtKind::For: {
        const auto* s = static_cast<const ForStmt*>(stmt);
        statement(s->init.get());  // runs once, before the loop
        ++conditional_;
        expression(s->condition.get());
        expression(s->step.get());
        statement(s->body.get());
        --conditional_;
        break;
      }
      case StmtKind::While: {
        const auto* s = static_cast<const WhileStmt*>(stmt);
        ++conditional_;
        expression(s->condition.get());
        statement(s->body.get());
        --conditional_;
        break;
      }
      case StmtKind::DoWhile: {
        const auto* s = static_cast<const DoWhileStmt*>(stmt);
        ++conditional_;
        statement(s->body.get());
        expression(s->condition.get());
        --conditional_;
        break;
      }
      case StmtKind::Switch: {
        const auto* s = static_cast<const SwitchStmt*>(stmt);
        expression(s->condition.get());
        for (const SwitchCase& c : s->cases)
          for (const StmtPtr& child : c.statements) branch(child.get());
        break;
      }
      case StmtKind::Return: expression(static_cast<const ReturnStmt*>(stmt)->value.get()); break;
      default: break;
    }
  }

  DiagnosticEngine& diag_;
  ResourceOrigins& out_;
  std::map<Slot, ResourceOrigin> slots_;
  std::unordered_set<const Decl*> unknown_;  // locals whose resource could not be followed
  std::set<std::tuple<uint32_t, uint32_t, uint32_t>> reported_;
  int conditional_ = 0;
};

}  // namespace

std::vector<std::vector<uint32_t>> resource_paths(const Type& type) {
  // Most expressions are numeric: answered without the walk's buffers.
  if (!type.is_resource() && type.kind() != TypeKind::Struct) return {};
  std::vector<std::vector<uint32_t>> out;
  std::vector<uint32_t> prefix;
  collect_paths(type, prefix, out, 0);
  return out;
}

ResourceOrigins resolve_resource_origins(const EntryPoints& entry_points, DiagnosticEngine& diagnostics) {
  ResourceOrigins origins;
  Resolver resolver(diagnostics, origins);
  std::unordered_set<const FunctionDecl*> done;
  for (const FunctionDecl* entry : {entry_points.vertex, entry_points.fragment})
    for (const FunctionDecl* function : reachable_functions(entry))
      if (function->body && done.insert(function).second) resolver.function(*function);
  return origins;
}

}  // namespace xshade::hlsl
