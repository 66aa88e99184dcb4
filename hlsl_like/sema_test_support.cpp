#include "hlsl_like/sema_test_support.h"

#include <gtest/gtest.h>

#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl::sema_test {

std::unique_ptr<Analyzed> analyze_source(const std::string& text) {
  auto analyzed = std::make_unique<Analyzed>();
  const uint32_t file = analyzed->sources.add("test.hlsl", text);
  analyzed->preprocessor =
      std::make_unique<Preprocessor>(analyzed->sources, analyzed->diagnostics, PreprocessorOptions{});
  analyzed->tokens = analyzed->preprocessor->run(file);
  analyzed->unit = parse(analyzed->tokens, analyzed->diagnostics);
  EntryPointNames names;
  for (const Pragma& pragma : analyzed->preprocessor->pragmas()) {
    if (pragma.args.empty()) continue;
    if (pragma.name == "vertex") {
      names.vertex = std::string(pragma.args[0].text);
      names.vertex_loc = pragma.args[0].loc;
    } else if (pragma.name == "fragment") {
      names.fragment = std::string(pragma.args[0].text);
      names.fragment_loc = pragma.args[0].loc;
    }
  }
  analyzed->entry_points = analyze(analyzed->unit, names, analyzed->diagnostics);
  return analyzed;
}

Strings messages_of(const std::string& text) { return analyze_source(text)->messages(); }

static std::string dump_list(const AstVector<ExprPtr>& list) {
  std::string out;
  for (const ExprPtr& item : list) out += " " + dump(item.get());
  return out;
}

std::string dump(const Expr* e) {
  if (!e) return "null";
  switch (e->kind) {
    case ExprKind::IntLiteral: return std::to_string(static_cast<const IntLiteralExpr*>(e)->value);
    case ExprKind::FloatLiteral: return static_cast<const FloatLiteralExpr*>(e)->spelling;
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr*>(e)->value ? "true" : "false";
    case ExprKind::Name: return static_cast<const NameExpr*>(e)->name;
    case ExprKind::Unary: {
      const auto* x = static_cast<const UnaryExpr*>(e);
      static const char* const kOps[] = {"+", "-", "!", "~", "pre++", "pre--", "post++", "post--"};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->operand.get()) + ")";
    }
    case ExprKind::Binary: {
      const auto* x = static_cast<const BinaryExpr*>(e);
      static const char* const kOps[] = {"+",  "-",  "*", "/", "%",  "<<", ">>", "&",  "|", "^",
                                         "&&", "||", "<", ">", "<=", ">=", "==", "!=", ","};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->lhs.get()) + " " + dump(x->rhs.get()) + ")";
    }
    case ExprKind::Assign: {
      const auto* x = static_cast<const AssignExpr*>(e);
      static const char* const kOps[] = {"=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="};
      return std::string("(") + kOps[int(x->op)] + " " + dump(x->target.get()) + " " + dump(x->value.get()) + ")";
    }
    case ExprKind::Conditional: {
      const auto* x = static_cast<const ConditionalExpr*>(e);
      return "(? " + dump(x->condition.get()) + " " + dump(x->then_value.get()) + " " + dump(x->else_value.get()) + ")";
    }
    case ExprKind::Call: {
      const auto* x = static_cast<const CallExpr*>(e);
      if (x->object) return "(." + x->callee + " " + dump(x->object.get()) + dump_list(x->args) + ")";
      if (x->call_kind == CallKind::Constructor) return "(" + x->constructed.name() + dump_list(x->args) + ")";
      return "(" + x->callee + dump_list(x->args) + ")";
    }
    case ExprKind::Member: {
      const auto* x = static_cast<const MemberExpr*>(e);
      return "(. " + dump(x->object.get()) + " " + x->member + ")";
    }
    case ExprKind::Index: {
      const auto* x = static_cast<const IndexExpr*>(e);
      return "([] " + dump(x->object.get()) + " " + dump(x->index.get()) + ")";
    }
    case ExprKind::Cast: {
      const auto* x = static_cast<const CastExpr*>(e);
      return "(cast " + x->target.name() + " " + dump(x->operand.get()) + ")";
    }
    case ExprKind::InitList: {
      const auto* x = static_cast<const InitListExpr*>(e);
      return "({} " + x->type.name() + dump_list(x->elements) + ")";
    }
    case ExprKind::Conversion: {
      const auto* x = static_cast<const ConversionExpr*>(e);
      return "(to " + x->type.name() + " " + dump(x->operand.get()) + ")";
    }
  }
  return "?";
}

Probe probe(const std::string& globals, const std::string& expr) {
  auto analyzed = analyze_source(globals + "\nvoid t() { " + expr + "; }\n");
  Probe result;
  result.messages = analyzed->messages();
  const auto& body = analyzed->function("t").body->statements;
  if (!body.empty() && body.back() && body.back()->kind == StmtKind::Expr) {
    const Expr* e = static_cast<const ExprStmt&>(*body.back()).expr.get();
    result.type = e ? e->type.name() : "null";
    result.tree = dump(e);
  }
  return result;
}

std::string type_of(const std::string& globals, const std::string& expr) {
  Probe result = probe(globals, expr);
  EXPECT_EQ(result.messages, Strings{}) << expr;
  return result.type;
}

}  // namespace xshade::hlsl::sema_test
