#include "hlsl_like/parser_test_support.h"

#include <gtest/gtest.h>

#include "hlsl_like/lexer.h"

namespace xshade::hlsl::parser_test {

std::unique_ptr<Parsed> lex_text(const std::string& text) {
  auto parsed = std::make_unique<Parsed>();
  const uint32_t file = parsed->sources.add("test.hlsl", text);
  Lexer lexer(parsed->sources.text(file), file, parsed->diagnostics, &parsed->text_store);
  for (;;) {
    parsed->tokens.push_back(lexer.next());
    if (parsed->tokens.back().kind == TokenKind::EndOfFile) break;
  }
  return parsed;
}

std::unique_ptr<Parsed> parse_text(const std::string& text) {
  auto parsed = lex_text(text);
  parsed->unit = parse(parsed->tokens, parsed->diagnostics);
  return parsed;
}

std::string sexpr(const Expr& e) {
  switch (e.kind) {
    case ExprKind::IntLiteral: {
      const auto& x = static_cast<const IntLiteralExpr&>(e);
      return std::to_string(x.value) + (x.is_unsigned ? "u" : "");
    }
    case ExprKind::FloatLiteral: {
      const auto& x = static_cast<const FloatLiteralExpr&>(e);
      return x.spelling + (x.half_suffix ? "h" : "");
    }
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr&>(e).value ? "true" : "false";
    case ExprKind::Name: return static_cast<const NameExpr&>(e).name;
    case ExprKind::Unary: {
      const auto& x = static_cast<const UnaryExpr&>(e);
      static const char* const kOps[] = {"+", "-", "!", "~", "pre++", "pre--", "post++", "post--"};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.operand) + ")";
    }
    case ExprKind::Binary: {
      const auto& x = static_cast<const BinaryExpr&>(e);
      static const char* const kOps[] = {"+",  "-",  "*", "/", "%",  "<<", ">>", "&",  "|", "^",
                                         "&&", "||", "<", ">", "<=", ">=", "==", "!=", ","};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.lhs) + " " + sexpr(*x.rhs) + ")";
    }
    case ExprKind::Assign: {
      const auto& x = static_cast<const AssignExpr&>(e);
      static const char* const kOps[] = {"=", "+=", "-=", "*=", "/=", "%=", "<<=", ">>=", "&=", "|=", "^="};
      return std::string("(") + kOps[int(x.op)] + " " + sexpr(*x.target) + " " + sexpr(*x.value) + ")";
    }
    case ExprKind::Conditional: {
      const auto& x = static_cast<const ConditionalExpr&>(e);
      return "(? " + sexpr(*x.condition) + " " + sexpr(*x.then_value) + " " + sexpr(*x.else_value) + ")";
    }
    case ExprKind::Call: {
      const auto& x = static_cast<const CallExpr&>(e);
      if (x.call_kind == CallKind::Constructor) return "(ctor " + x.constructed.name() + sexpr_list(x.args) + ")";
      if (x.object) return "(method " + sexpr(*x.object) + " " + x.callee + sexpr_list(x.args) + ")";
      return "(call " + x.callee + sexpr_list(x.args) + ")";
    }
    case ExprKind::Member: {
      const auto& x = static_cast<const MemberExpr&>(e);
      return "(. " + sexpr(*x.object) + " " + x.member + ")";
    }
    case ExprKind::Index: {
      const auto& x = static_cast<const IndexExpr&>(e);
      return "([] " + sexpr(*x.object) + " " + sexpr(*x.index) + ")";
    }
    case ExprKind::Cast: {
      const auto& x = static_cast<const CastExpr&>(e);
      return "(cast " + x.target.name() + " " + sexpr(*x.operand) + ")";
    }
    case ExprKind::InitList: return "{" + sexpr_list(static_cast<const InitListExpr&>(e).elements) + " }";
    case ExprKind::Conversion: return "(conversion)";
  }
  return "?";
}

std::string expr_tree(const std::string& expression) {
  auto parsed = parse_text(
      "struct Light { float3 color; };\n"
      "void f(float a, float b, float c, float d, float x, float y, float z, float w, float v,"
      " float3 n, int i, int j, Texture2D tex, SamplerState s, float2 uv, Light l,"
      " float arr[4]) {\n  " +
      expression + ";\n}\n");
  EXPECT_EQ(parsed->errors(), std::vector<std::string>{}) << expression;
  if (parsed->diagnostics.has_errors()) return "<error>";
  const FunctionDecl& f = parsed->function("f");
  const Stmt& statement = *f.body->statements.at(0);
  EXPECT_EQ(statement.kind, StmtKind::Expr);
  return sexpr(*static_cast<const ExprStmt&>(statement).expr);
}

}  // namespace xshade::hlsl::parser_test
