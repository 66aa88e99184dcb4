// The parser's expressions: operators by precedence, postfix chains, calls and constructors,
// literals, initializer lists, and the integer constants that array sizes are.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl::parser_detail {

ExprPtr Parser::parse_expression() {
  ChainDepth chain(*this);
  ExprPtr lhs = parse_assignment();
  while (lhs && is(",")) {
    if (!chain.push()) return nullptr;
    auto comma = make<BinaryExpr>(cur().loc, BinaryOp::Comma);
    advance();
    comma->lhs = std::move(lhs);
    comma->rhs = parse_assignment();
    if (!comma->rhs) return nullptr;
    lhs = std::move(comma);
  }
  return lhs;
}

namespace {

std::optional<AssignOp> assign_op(const Token& token) {
  if (token.kind != TokenKind::Punct) return std::nullopt;
  const std::string_view t = token.text;
  if (t == "=") return AssignOp::Assign;
  if (t == "+=") return AssignOp::Add;
  if (t == "-=") return AssignOp::Sub;
  if (t == "*=") return AssignOp::Mul;
  if (t == "/=") return AssignOp::Div;
  if (t == "%=") return AssignOp::Mod;
  if (t == "<<=") return AssignOp::Shl;
  if (t == ">>=") return AssignOp::Shr;
  if (t == "&=") return AssignOp::BitAnd;
  if (t == "|=") return AssignOp::BitOr;
  if (t == "^=") return AssignOp::BitXor;
  return std::nullopt;
}

}  // namespace

// Right-associative: a = b = c is a = (b = c).
ExprPtr Parser::parse_assignment() {
  ExprPtr target = parse_conditional();
  if (!target) return nullptr;
  const std::optional<AssignOp> op = assign_op(cur());
  if (!op) return target;
  auto assign = make<AssignExpr>(cur().loc, *op);
  advance();
  DepthGuard guard(*this);
  if (!guard.ok()) return nullptr;
  assign->target = std::move(target);
  assign->value = parse_assignment();
  if (!assign->value) return nullptr;
  return assign;
}

// c ? a : b, right-associative through its last operand.
ExprPtr Parser::parse_conditional() {
  ExprPtr condition = parse_binary(1);
  if (!condition || !is("?")) return condition;
  const size_t question = pos_;
  auto conditional = make<ConditionalExpr>(cur().loc);
  advance();
  DepthGuard guard(*this);
  if (!guard.ok()) return nullptr;
  conditional->condition = std::move(condition);
  conditional->then_value = parse_expression();
  if (!conditional->then_value) return nullptr;
  if (!is(":")) {
    if (error_here("expected ':' in conditional expression")) diagnostics_.note(tok(question).loc, "to match this '?'");
    return nullptr;
  }
  advance();
  conditional->else_value = parse_assignment();
  if (!conditional->else_value) return nullptr;
  return conditional;
}

namespace {

// Precedence of a binary operator (higher binds tighter); 0 when the token is none. Asked at
// every level of precedence climbing after every operand, so it switches on the characters
// rather than comparing the token with each operator in turn.
int binary_precedence(const Token& token, BinaryOp& op) {
  if (token.kind != TokenKind::Punct) return 0;
  const std::string_view t = token.text;
  auto found = [&op](BinaryOp binary, int precedence) {
    op = binary;
    return precedence;
  };
  if (t.size() == 1) {
    switch (t[0]) {
      case '|': return found(BinaryOp::BitOr, 3);
      case '^': return found(BinaryOp::BitXor, 4);
      case '&': return found(BinaryOp::BitAnd, 5);
      case '<': return found(BinaryOp::Less, 7);
      case '>': return found(BinaryOp::Greater, 7);
      case '+': return found(BinaryOp::Add, 9);
      case '-': return found(BinaryOp::Sub, 9);
      case '*': return found(BinaryOp::Mul, 10);
      case '/': return found(BinaryOp::Div, 10);
      case '%': return found(BinaryOp::Mod, 10);
      default: return 0;
    }
  }
  if (t.size() != 2) return 0;
  switch (t[0]) {
    case '|': return t[1] == '|' ? found(BinaryOp::LogicalOr, 1) : 0;
    case '&': return t[1] == '&' ? found(BinaryOp::LogicalAnd, 2) : 0;
    case '=': return t[1] == '=' ? found(BinaryOp::Equal, 6) : 0;
    case '!': return t[1] == '=' ? found(BinaryOp::NotEqual, 6) : 0;
    case '<': return t[1] == '=' ? found(BinaryOp::LessEqual, 7) : t[1] == '<' ? found(BinaryOp::Shl, 8) : 0;
    case '>': return t[1] == '=' ? found(BinaryOp::GreaterEqual, 7) : t[1] == '>' ? found(BinaryOp::Shr, 8) : 0;
    default: return 0;
  }
}

}  // namespace

// Precedence climbing: left-associative, one loop per level reached.
ExprPtr Parser::parse_binary(int min_precedence) {
  ChainDepth chain(*this);
  ExprPtr lhs = parse_unary();
  while (lhs) {
    BinaryOp op{};
    const int precedence = binary_precedence(cur(), op);
    if (precedence == 0 || precedence < min_precedence) break;
    if (!chain.push()) return nullptr;
    auto binary = make<BinaryExpr>(cur().loc, op);
    advance();
    binary->lhs = std::move(lhs);
    binary->rhs = parse_binary(precedence + 1);
    if (!binary->rhs) return nullptr;
    lhs = std::move(binary);
  }
  return lhs;
}

// ( TYPE ) at `index`: a cast, told from a parenthesised expression by the type table.
bool Parser::is_cast_at(size_t index) const {
  if (!tok(index).is_punct("(") || !is_type_start(index + 1)) return false;
  return tok(type_end(index + 1)).is_punct(")");
}

ExprPtr Parser::parse_unary() {
  const Token& token = cur();
  if (token.kind == TokenKind::Punct) {
    std::optional<UnaryOp> op;
    const std::string_view t = token.text;
    if (t == "+")
      op = UnaryOp::Plus;
    else if (t == "-")
      op = UnaryOp::Minus;
    else if (t == "!")
      op = UnaryOp::Not;
    else if (t == "~")
      op = UnaryOp::BitNot;
    else if (t == "++")
      op = UnaryOp::PreIncrement;
    else if (t == "--")
      op = UnaryOp::PreDecrement;
    if (op) {
      auto unary = make<UnaryExpr>(token.loc, *op);
      advance();
      DepthGuard guard(*this);
      if (!guard.ok()) return nullptr;
      unary->operand = parse_unary();
      if (!unary->operand) return nullptr;
      return unary;
    }
    if (t == "(" && is_cast_at(pos_)) {
      auto cast = make<CastExpr>(token.loc);
      advance();
      const std::optional<Type> target = parse_type(false);
      if (!target) return nullptr;
      cast->target = *target;
      if (!is(")")) {
        error_here("expected ')' after the type of a cast");
        return nullptr;
      }
      advance();
      DepthGuard guard(*this);
      if (!guard.ok()) return nullptr;
      cast->operand = parse_unary();
      if (!cast->operand) return nullptr;
      return cast;
    }
  }
  ExprPtr primary = parse_primary();
  if (!primary) return nullptr;
  return parse_postfix(std::move(primary));
}

ExprPtr Parser::parse_postfix(ExprPtr expr) {
  ChainDepth chain(*this);
  for (;;) {
    const Token& token = cur();
    if (token.kind != TokenKind::Punct) return expr;
    if ((token.text == "[" || token.text == "." || token.text == "++" || token.text == "--") && !chain.push())
      return nullptr;
    if (token.text == "[") {
      const size_t open = pos_;
      auto index = make<IndexExpr>(token.loc);
      advance();
      DepthGuard guard(*this);
      if (!guard.ok()) return nullptr;
      index->object = std::move(expr);
      index->index = parse_expression();
      if (!index->index) return nullptr;
      if (!is("]")) {
        error_unmatched("]", open);
        return nullptr;
      }
      advance();
      expr = std::move(index);
    } else if (token.text == ".") {
      advance();
      if (cur().kind != TokenKind::Identifier) {
        error_here("expected a member name after '.'");
        return nullptr;
      }
      const Token& member = cur();
      advance();
      if (is("(")) {
        auto call = make<CallExpr>(member.loc);
        call->callee = std::string(member.text);
        call->object = std::move(expr);
        if (!parse_call_args(*call)) return nullptr;
        expr = std::move(call);
      } else {
        auto access = make<MemberExpr>(member.loc);
        access->object = std::move(expr);
        access->member = std::string(member.text);
        expr = std::move(access);
      }
    } else if (token.text == "++" || token.text == "--") {
      auto unary = make<UnaryExpr>(token.loc, token.text == "++" ? UnaryOp::PostIncrement : UnaryOp::PostDecrement);
      advance();
      unary->operand = std::move(expr);
      expr = std::move(unary);
    } else if (token.text == "(") {
      error_here("only functions and methods can be called");
      return nullptr;
    } else {
      return expr;
    }
  }
}

// ( args ) of a call, at the '('.
bool Parser::parse_call_args(CallExpr& call) {
  const size_t open = pos_;
  advance();
  DepthGuard guard(*this);
  if (!guard.ok()) return false;
  if (accept(")")) return true;
  Gathered<ExprPtr> args(gathered_args_);
  for (;;) {
    ExprPtr arg = parse_assignment();
    if (!arg) return false;
    args.push(std::move(arg));
    if (accept(",")) continue;
    if (accept(")")) {
      args.move_to(call.args);
      return true;
    }
    error_unmatched(")", open);
    return false;
  }
}

IntValue parse_int_spelling(std::string_view text) {
  IntValue result;
  while (!text.empty()) {
    const char c = text.back();
    if (c == 'u' || c == 'U') {
      result.is_unsigned = true;
    } else if (c != 'l' && c != 'L') {
      break;
    }
    text.remove_suffix(1);
  }
  uint64_t base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    base = 16;
    text.remove_prefix(2);
  } else if (text.size() > 1 && text[0] == '0') {
    base = 8;
    text.remove_prefix(1);
  }
  if (text.empty()) result.valid = false;
  for (char c : text) {
    uint64_t digit = 0;
    if (c >= '0' && c <= '9') {
      digit = uint64_t(c - '0');
    } else if (c >= 'a' && c <= 'f') {
      digit = uint64_t(c - 'a' + 10);
    } else if (c >= 'A' && c <= 'F') {
      digit = uint64_t(c - 'A' + 10);
    } else {
      result.valid = false;
      break;
    }
    if (digit >= base) {
      result.valid = false;
      break;
    }
    if (!result.too_large) {
      result.value = result.value * base + digit;
      if (result.value > 0xFFFFFFFFull) result.too_large = true;
    }
  }
  if (!result.valid || result.too_large) result.value = 0;
  return result;
}

ExprPtr Parser::parse_int_literal() {
  const Token& token = cur();
  auto literal = make<IntLiteralExpr>(token.loc);
  const IntValue value = parse_int_spelling(token.text);
  if (!value.valid) {
    literal_error("invalid integer literal " + in_quotes(token.text));
  } else if (value.too_large) {
    error_here("integer literal is too large");
  }
  literal->value = value.value;
  literal->is_unsigned = value.is_unsigned;
  advance();
  return literal;
}

namespace {

// The value of a plain decimal literal (digits, a point, an exponent) whose significant digits
// fit a double exactly and whose power of ten is exact too (10^22 at most): then one multiply
// or divide gives the correctly rounded value, the double strtod would give (Clinger's fast
// path), without strtod's general machinery, which most of a shader's literals do not need.
// Nothing for any other text, which strtod reads (and reports).
std::optional<double> exact_decimal(std::string_view text) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                            1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr int kMaxDigits = 15;  // 10^15 < 2^53: any 15 digits are an exact double
  uint64_t mantissa = 0;
  int significant = 0;
  int scale = 0;
  bool any_digit = false;
  size_t i = 0;
  auto digits = [&](bool fraction) {
    for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
      any_digit = true;
      if (mantissa == 0 && text[i] == '0') {
        if (fraction) --scale;
        continue;
      }
      if (++significant > kMaxDigits) return false;
      mantissa = mantissa * 10 + uint64_t(text[i] - '0');
      if (fraction) --scale;
    }
    return true;
  };
  if (!digits(false)) return std::nullopt;
  if (i < text.size() && text[i] == '.') {
    ++i;
    if (!digits(true)) return std::nullopt;
  }
  if (!any_digit) return std::nullopt;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    const bool negative = i < text.size() && text[i] == '-';
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
    if (i == text.size() || text[i] < '0' || text[i] > '9') return std::nullopt;
    int exponent = 0;
    for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
      exponent = exponent * 10 + (text[i] - '0');
      if (exponent > 1000) return std::nullopt;
    }
    scale += negative ? -exponent : exponent;
  }
  if (i != text.size()) return std::nullopt;
  if (mantissa == 0) return 0.0;
  if (scale < -22 || scale > 22) return std::nullopt;
  const auto value = double(mantissa);
  return scale < 0 ? value / kPowersOfTen[-scale] : value * kPowersOfTen[scale];
}

}  // namespace

ExprPtr Parser::parse_float_literal() {
  const Token& token = cur();
  auto literal = make<FloatLiteralExpr>(token.loc);
  std::string_view text = token.text;
  if (!text.empty()) {
    const char suffix = text.back();
    if (suffix == 'h' || suffix == 'H') {
      literal->half_suffix = true;
      text.remove_suffix(1);
    } else if (suffix == 'f' || suffix == 'F' || suffix == 'l' || suffix == 'L') {
      text.remove_suffix(1);
    }
  }
  literal->spelling = std::string(text);
  if (const std::optional<double> value = exact_decimal(text)) {
    literal->value = *value;
    advance();
    return literal;
  }
  const bool starts_well = !text.empty() && ((text[0] >= '0' && text[0] <= '9') || text[0] == '.');
  char* end = nullptr;
  const char* begin = literal->spelling.c_str();
  literal->value = starts_well ? std::strtod(begin, &end) : 0.0;
  if (!starts_well || end != begin + literal->spelling.size()) {
    literal_error("invalid floating-point literal " + in_quotes(token.text));
    literal->value = 0.0;
  } else if (std::isinf(literal->value)) {
    error_here("floating-point literal is out of range");
  }
  advance();
  return literal;
}

ExprPtr Parser::parse_primary() {
  const Token& token = cur();
  switch (token.kind) {
    case TokenKind::IntLiteral: return parse_int_literal();
    case TokenKind::FloatLiteral: return parse_float_literal();
    case TokenKind::StringLiteral:  // an unterminated one was reported by the lexer already
      literal_error("string literals are only allowed in annotations");
      return nullptr;
    case TokenKind::Identifier: return parse_name_or_call();
    case TokenKind::Punct:
      if (token.text == "(") {
        const size_t open = pos_;
        advance();
        DepthGuard guard(*this);
        if (!guard.ok()) return nullptr;
        ExprPtr inner = parse_expression();
        if (!inner) return nullptr;
        if (!is(")")) {
          error_unmatched(")", open);
          return nullptr;
        }
        advance();
        return inner;
      }
      if (token.text == "{") {
        error_here("initializer lists are only allowed in initializers");
        return nullptr;
      }
      break;
    default: break;
  }
  error_here("expected an expression");
  return nullptr;
}

ExprPtr Parser::parse_name_or_call() {
  const Token& token = cur();
  if (token.text == "true" || token.text == "false") {
    auto literal = make<BoolLiteralExpr>(token.loc);
    literal->value = token.text == "true";
    advance();
    return literal;
  }
  if (is_type_start(pos_)) {
    // A constructor: float3(a, b), float2x2(...), vector<float, 2>(...).
    auto call = make<CallExpr>(token.loc);
    call->callee = std::string(token.text);
    const std::optional<Type> type = parse_type(false);
    if (!type) return nullptr;
    if (!is("(")) {
      error_here("expected '(' after type " + in_quotes(call->callee));
      return nullptr;
    }
    call->constructed = *type;
    call->call_kind = CallKind::Constructor;
    if (!parse_call_args(*call)) return nullptr;
    return call;
  }
  if (is_reserved(pos_)) {
    error_here("expected an expression");
    return nullptr;
  }
  advance();
  if (is("(") && token.text == "printf" && tok(pos_ + 1).kind == TokenKind::StringLiteral) {
    // printf("format", values...): the one place a string literal is an operand.
    auto call = make<CallExpr>(token.loc);
    call->callee = "printf";
    call->call_kind = CallKind::Printf;
    const size_t open = pos_;
    advance();
    call->format = std::string(cur().text);
    advance();
    while (accept(",")) {
      ExprPtr arg = parse_assignment();
      if (!arg) return nullptr;
      call->args.push_back(std::move(arg));
    }
    if (!is(")")) {
      error_unmatched(")", open);
      return nullptr;
    }
    advance();
    return call;
  }
  if (is("(")) {
    auto call = make<CallExpr>(token.loc);
    call->callee = std::string(token.text);
    if (!parse_call_args(*call)) return nullptr;
    return call;
  }
  auto name = make<NameExpr>(token.loc);
  name->name = std::string(token.text);
  return name;
}

// -------------------------------------------------------------------------------------------
// Initializer lists

// { a, b, { c, d } }. Only the outermost list skips on an error: to just past its '}'.
ExprPtr Parser::parse_init_list() {
  DepthGuard guard(*this);
  if (!guard.ok()) return nullptr;
  const size_t open = pos_;
  auto list = make<InitListExpr>(cur().loc);
  advance();
  ++init_list_nesting_;
  bool ok = true;
  while (!is("}")) {
    ExprPtr element = is("{") ? parse_init_list() : parse_assignment();
    if (!element) {
      ok = false;
      break;
    }
    list->elements.push_back(std::move(element));
    if (accept(",")) continue;
    if (!is("}")) {
      error_unmatched("}", open);
      ok = false;
      break;
    }
  }
  --init_list_nesting_;
  if (ok) {
    advance();
    return list;
  }
  if (init_list_nesting_ == 0) skip_group(open, false);
  return nullptr;
}

// -------------------------------------------------------------------------------------------
// Integer constants (array sizes)

// The first name in `expr` that is a uniform const, which its author may have meant as a constant.
const NameExpr* Parser::find_uniform_constant(const Expr& expr) const {
  switch (expr.kind) {
    case ExprKind::Name: {
      const auto& name = static_cast<const NameExpr&>(expr);
      return uniform_constants_.count(name.name) ? &name : nullptr;
    }
    case ExprKind::Unary: return find_uniform_constant(*static_cast<const UnaryExpr&>(expr).operand);
    case ExprKind::Binary: {
      const auto& binary = static_cast<const BinaryExpr&>(expr);
      if (const NameExpr* found = find_uniform_constant(*binary.lhs)) return found;
      return find_uniform_constant(*binary.rhs);
    }
    default: return nullptr;
  }
}

// Integer constant expressions for array sizes: literals, arithmetic, and names of constant
// integers declared with a constant initializer.
std::optional<int64_t> Parser::evaluate_int(const Expr& expr) const {
  switch (expr.kind) {
    case ExprKind::IntLiteral: return int64_t(static_cast<const IntLiteralExpr&>(expr).value);
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr&>(expr).value ? 1 : 0;
    case ExprKind::Name: {
      const auto it = int_constants_.find(static_cast<const NameExpr&>(expr).name);
      if (it == int_constants_.end()) return std::nullopt;
      return it->second;
    }
    case ExprKind::Unary: {
      const auto& unary = static_cast<const UnaryExpr&>(expr);
      const std::optional<int64_t> value = evaluate_int(*unary.operand);
      if (!value) return std::nullopt;
      switch (unary.op) {
        case UnaryOp::Plus: return *value;
        case UnaryOp::Minus: return -*value;
        case UnaryOp::BitNot: return ~*value;
        case UnaryOp::Not: return *value == 0 ? 1 : 0;
        default: return std::nullopt;
      }
    }
    case ExprKind::Binary: {
      const auto& binary = static_cast<const BinaryExpr&>(expr);
      const std::optional<int64_t> a = evaluate_int(*binary.lhs);
      const std::optional<int64_t> b = evaluate_int(*binary.rhs);
      if (!a || !b) return std::nullopt;
      int64_t result = 0;
      switch (binary.op) {
        case BinaryOp::Add:
          if (__builtin_add_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case BinaryOp::Sub:
          if (__builtin_sub_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case BinaryOp::Mul:
          if (__builtin_mul_overflow(*a, *b, &result)) return std::nullopt;
          return result;
        case BinaryOp::Div:
          if (*b == 0 || (*b == -1 && *a == INT64_MIN)) return std::nullopt;
          return *a / *b;
        case BinaryOp::Mod:
          if (*b == 0 || (*b == -1 && *a == INT64_MIN)) return std::nullopt;
          return *a % *b;
        case BinaryOp::Shl:
          if (*b < 0 || *b > 32 || *a < 0 || *a > 0xFFFFFFFFll) return std::nullopt;
          return int64_t(uint64_t(*a) << *b);
        case BinaryOp::Shr:
          if (*b < 0 || *b > 63) return std::nullopt;
          return *a >> *b;
        case BinaryOp::BitAnd: return *a & *b;
        case BinaryOp::BitOr: return *a | *b;
        case BinaryOp::BitXor: return *a ^ *b;
        default: return std::nullopt;
      }
    }
    default: return std::nullopt;
  }
}

}  // namespace xshade::hlsl::parser_detail
