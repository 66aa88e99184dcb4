// The parser's statements: blocks, control flow, switch, and local declarations.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl::parser_detail {
namespace {

StmtPtr make_simple(StmtKind kind, Loc loc) { return make<SimpleStmt>(kind, loc); }

}  // namespace

std::unique_ptr<BlockStmt> Parser::parse_block() {
  const size_t open = pos_;
  auto block = make<BlockStmt>(cur().loc);
  advance();
  NameScope scope(*this);
  Gathered<StmtPtr> statements(gathered_statements_);
  while (!is("}") && !at_end()) {
    const size_t before = pos_;
    StmtPtr statement = parse_statement();
    if (statement) {
      statements.push(std::move(statement));
    } else {
      recover_statement();
    }
    if (pos_ == before && !is("}") && !at_end()) advance();
  }
  statements.move_to(block->statements);
  if (!accept("}")) error_unmatched("}", open);
  return block;
}

// Null when the statement failed and the caller must recover. A statement that failed but
// already recovered (a bad if condition, a switch) comes back as an empty statement.
StmtPtr Parser::parse_statement() {
  DepthGuard guard(*this);
  if (!guard.ok()) {
    skip_to_block_end();
    return make_simple(StmtKind::Empty, cur().loc);
  }
  std::vector<Attribute> attributes;
  if (is("[") && !parse_attributes(attributes)) return nullptr;
  StmtPtr statement = parse_statement_body();
  if (statement) statement->attributes = std::move(attributes);
  return statement;
}

StmtPtr Parser::parse_statement_body() {
  const Token& token = cur();
  const Loc loc = token.loc;
  if (token.is_punct("{")) return parse_block();
  if (token.is_punct(";")) {
    advance();
    return make_simple(StmtKind::Empty, loc);
  }
  if (token.kind == TokenKind::Identifier) {
    const std::string_view word = token.text;
    if (word == "if") return parse_if();
    if (word == "for") return parse_for();
    if (word == "while") return parse_while();
    if (word == "do") return parse_do_while();
    if (word == "return") return parse_return();
    if (word == "break" || word == "continue" || word == "discard") {
      advance();
      if (!expect_semicolon(in_quotes(word))) return nullptr;
      const StmtKind kind = word == "break"      ? StmtKind::Break
                            : word == "continue" ? StmtKind::Continue
                                                 : StmtKind::Discard;
      return make_simple(kind, loc);
    }
    if (word == "switch") return parse_switch();
    if (word == "goto") {
      error_here("goto is not supported");
      return nullptr;
    }
    if (word == "else" || word == "case" || word == "default") {  // a label outside a switch
      error_here("unexpected " + in_quotes(word));
      return nullptr;
    }
    if (word == "struct" || word == "typedef" || word == "cbuffer") {
      error_here("local " + std::string(word) + " declarations are not supported");
      return nullptr;
    }
    if (info(pos_).unsupported) {
      error_here(in_quotes(word) + " is not supported");
      return nullptr;
    }
    if (is_declaration_start()) return parse_declaration_statement();
  }
  auto statement = make<ExprStmt>(loc);
  statement->expr = parse_expression();
  if (!statement->expr || !expect_semicolon("expression")) return nullptr;
  return statement;
}

// switch (c) { case 1: ... default: ... }, at the word. A label outside any case is an error;
// statements after a label belong to it until the next one.
StmtPtr Parser::parse_switch() {
  auto statement = make<SwitchStmt>(cur().loc);
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'switch'");
    return nullptr;
  }
  const size_t open = pos_;
  advance();
  {
    DepthGuard guard(*this);
    if (!guard.ok()) return nullptr;
    statement->condition = parse_expression();
  }
  if (!statement->condition || !is(")")) {
    if (statement->condition) error_unmatched(")", open);
    skip_group(open, false);
    if (is("{")) skip_group(pos_, true);
    return make_simple(StmtKind::Empty, statement->loc);
  }
  advance();
  if (!is("{")) {
    error_here("expected '{' after the condition of 'switch'");
    return nullptr;
  }
  const size_t brace = pos_;
  advance();
  NameScope scope(*this);  // the cases share one scope, as in C
  while (!is("}") && !at_end()) {
    const size_t before = pos_;
    if (is_word("case") || is_word("default")) {
      SwitchCase label;
      label.loc = cur().loc;
      const bool is_default = is_word("default");
      advance();
      if (!is_default) {
        DepthGuard guard(*this);
        if (!guard.ok()) return nullptr;
        label.value = parse_conditional();
        if (!label.value) {
          recover_statement();
          continue;
        }
      }
      if (!accept(":")) {
        error_after_previous(std::string("expected ':' after ") + (is_default ? "'default'" : "the case value"));
        recover_statement();
        continue;
      }
      statement->cases.push_back(std::move(label));
      continue;
    }
    if (statement->cases.empty()) {
      error_here("expected 'case' or 'default' in a switch");
      recover_statement();
      if (pos_ == before) advance();
      continue;
    }
    StmtPtr child = parse_statement();
    if (child)
      statement->cases.back().statements.push_back(std::move(child));
    else
      recover_statement();
    if (pos_ == before && !is("}") && !at_end()) advance();
  }
  if (!accept("}")) error_unmatched("}", brace);
  return statement;
}

// A declaration begins with a qualifier, or with a type not followed by '(' (which would be a
// constructor call), or with two names in a row (an unknown type, reported by parse_type).
bool Parser::is_declaration_start() const {
  const Token& token = cur();
  if (token.kind != TokenKind::Identifier) return false;
  if (is_specifier_at(pos_)) return true;
  if (is_type_start(pos_)) return !tok(type_end(pos_)).is_punct("(");
  return !is_reserved(pos_) && is_name(pos_ + 1);
}

// float a = 1, b[2]; — in a block or a for header. Consumes the ';'.
StmtPtr Parser::parse_declaration_statement() {
  auto statement = make<DeclStmt>(cur().loc);
  Specifiers spec;
  parse_specifiers(DeclContext::Local, spec);
  const size_t type_index = pos_;
  const std::optional<Type> type = parse_type(false);
  if (!type) return nullptr;
  const std::optional<size_t> name = expect_name();
  if (!name) return nullptr;
  if (!parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::Local, statement->vars))
    return nullptr;
  return statement;
}

// ( expression ) after if and while. On an error the group is skipped, so that the body can
// still be read; null then.
ExprPtr Parser::parse_paren_condition(std::string_view keyword) {
  if (!is("(")) {
    error_here("expected '(' after " + in_quotes(keyword));
    return nullptr;
  }
  const size_t open = pos_;
  advance();
  ExprPtr condition = parse_expression();
  if (condition && is(")")) {
    advance();
    return condition;
  }
  if (condition) error_unmatched(")", open);
  skip_group(open, false);
  return nullptr;
}

StmtPtr Parser::parse_if() {
  auto statement = make<IfStmt>(cur().loc);
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'if'");
    return nullptr;
  }
  statement->condition = parse_paren_condition("if");
  if (!statement->condition && (is("}") || at_end())) return make_simple(StmtKind::Empty, statement->loc);
  statement->then_branch = parse_substatement();
  if (!statement->then_branch) return nullptr;
  if (is_word("else")) {
    advance();
    statement->else_branch = parse_substatement();
    if (!statement->else_branch) return nullptr;
  }
  if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
  return statement;
}

StmtPtr Parser::parse_while() {
  auto statement = make<WhileStmt>(cur().loc);
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'while'");
    return nullptr;
  }
  statement->condition = parse_paren_condition("while");
  if (!statement->condition && (is("}") || at_end())) return make_simple(StmtKind::Empty, statement->loc);
  statement->body = parse_substatement();
  if (!statement->body) return nullptr;
  if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
  return statement;
}

StmtPtr Parser::parse_do_while() {
  auto statement = make<DoWhileStmt>(cur().loc);
  advance();
  statement->body = parse_substatement();
  if (!statement->body) return nullptr;
  if (!is_word("while")) {
    error_here("expected 'while' after the body of 'do'");
    return nullptr;
  }
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'while'");
    return nullptr;
  }
  statement->condition = parse_paren_condition("while");
  if (!expect_semicolon("do-while statement")) return nullptr;
  if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
  return statement;
}

StmtPtr Parser::parse_for() {
  auto statement = make<ForStmt>(cur().loc);
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'for'");
    return nullptr;
  }
  const size_t open = pos_;
  advance();
  NameScope scope(*this);  // the header's declaration, through the body
  const bool header_ok = parse_for_header(*statement, open);
  if (!header_ok) {
    skip_group(open, true);
    if (is("}") || at_end()) return make_simple(StmtKind::Empty, statement->loc);
  }
  statement->body = parse_substatement();
  if (!statement->body) return nullptr;
  if (!header_ok) return make_simple(StmtKind::Empty, statement->loc);
  return statement;
}

bool Parser::parse_for_header(ForStmt& statement, size_t open) {
  if (!is(";")) {
    if (is_declaration_start()) {
      statement.init = parse_declaration_statement();
      if (!statement.init) return false;
    } else {
      auto init = make<ExprStmt>(cur().loc);
      init->expr = parse_expression();
      if (!init->expr) return false;
      if (!is(";")) {
        error_here("expected ';' in 'for' statement");
        return false;
      }
      advance();
      statement.init = std::move(init);
    }
  } else {
    advance();
  }
  if (!is(";")) {
    statement.condition = parse_expression();
    if (!statement.condition) return false;
    if (!is(";")) {
      error_here("expected ';' in 'for' statement");
      return false;
    }
  }
  advance();
  if (!is(")")) {
    statement.step = parse_expression();
    if (!statement.step) return false;
    if (!is(")")) {
      error_unmatched(")", open);
      return false;
    }
  }
  advance();
  return true;
}

StmtPtr Parser::parse_return() {
  auto statement = make<ReturnStmt>(cur().loc);
  advance();
  if (!is(";")) {
    statement->value = parse_expression();
    if (!statement->value) return nullptr;
  }
  if (!expect_semicolon("return statement")) return nullptr;
  return statement;
}

}  // namespace xshade::hlsl::parser_detail
