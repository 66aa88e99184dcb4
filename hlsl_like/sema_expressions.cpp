// Semantic analysis of expressions: names, operators, members, indexing, casts, initializer
// lists, l-values and implicit conversions. Calls are in sema_calls.cpp.
// Why this file is long: each expression form is one typing rule, and they share the operator
// and conversion helpers above them; calls, the part that grew on its own, are already apart.
#include <algorithm>
#include <limits>

#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl::sema_detail {

namespace {

const char* unary_spelling(UnaryOp op) {
  switch (op) {
    case UnaryOp::Plus: return "+";
    case UnaryOp::Minus: return "-";
    case UnaryOp::Not: return "!";
    case UnaryOp::BitNot: return "~";
    case UnaryOp::PreIncrement:
    case UnaryOp::PostIncrement: return "++";
    case UnaryOp::PreDecrement:
    case UnaryOp::PostDecrement: return "--";
  }
  return "?";
}

const char* binary_spelling(BinaryOp op) {
  switch (op) {
    case BinaryOp::Add: return "+";
    case BinaryOp::Sub: return "-";
    case BinaryOp::Mul: return "*";
    case BinaryOp::Div: return "/";
    case BinaryOp::Mod: return "%";
    case BinaryOp::Shl: return "<<";
    case BinaryOp::Shr: return ">>";
    case BinaryOp::BitAnd: return "&";
    case BinaryOp::BitOr: return "|";
    case BinaryOp::BitXor: return "^";
    case BinaryOp::LogicalAnd: return "&&";
    case BinaryOp::LogicalOr: return "||";
    case BinaryOp::Less: return "<";
    case BinaryOp::Greater: return ">";
    case BinaryOp::LessEqual: return "<=";
    case BinaryOp::GreaterEqual: return ">=";
    case BinaryOp::Equal: return "==";
    case BinaryOp::NotEqual: return "!=";
    case BinaryOp::Comma: return ",";
  }
  return "?";
}

bool is_uniform(const VarDecl& var) {
  return var.is_global && var.storage != StorageClass::Static && var.storage != StorageClass::GroupShared;
}

// Folded values stay within what int and uint can hold, so that no operation on two of them
// overflows 64 bits unnoticed.
std::optional<int64_t> in_fold_range(int64_t value) {
  if (value < int64_t(std::numeric_limits<int32_t>::min()) || value > int64_t(std::numeric_limits<uint32_t>::max())) {
    return std::nullopt;
  }
  return value;
}

}  // namespace

bool Sema::report_nesting(Loc loc) {
  if (!reported_depth_) {
    reported_depth_ = true;
    diag_.error(loc, "expression or statement is nested too deeply");
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Conversions

void Sema::wrap_conversion(ExprPtr& slot, const Type& to) {
  if (!slot || slot->type == to) return;
  auto conversion = std::make_unique<ConversionExpr>(slot->loc);
  conversion->type = to;
  conversion->operand = std::move(slot);
  slot = std::move(conversion);
}

bool Sema::coerce(ExprPtr& slot, const Type& to) {
  if (!slot) return true;         // a parse error, already reported
  const Type& from = slot->type;  // read before the slot is wrapped below
  if (from.is_error() || to.is_error()) return true;
  const Conversion conversion = classify_implicit(from, to);
  if (!conversion.valid) {
    diag_.error(slot->loc, "cannot convert from " + in_quotes(from.name()) + " to " + in_quotes(to.name()));
    return false;
  }
  if (conversion.truncation) diag_.warning(slot->loc, truncation_message(from, to));
  wrap_conversion(slot, to);
  return true;
}

ScalarType Sema::common_scalar(std::span<const Expr* const> operands) const {
  // The highest scalar type, except that a float literal takes a half operand's type.
  bool any = false, any_strict = false;
  ScalarType all = ScalarType::Bool, strict = ScalarType::Bool;
  bool weak_float = false;
  for (const Expr* operand : operands) {
    if (!operand || !operand->type.is_numeric()) continue;
    const ScalarType scalar = operand->type.scalar_type();
    all = any ? higher_scalar(all, scalar) : scalar;
    any = true;
    if (is_weak_float_literal(operand)) {
      weak_float = true;
    } else {
      strict = any_strict ? higher_scalar(strict, scalar) : scalar;
      any_strict = true;
    }
  }
  if (weak_float && any_strict && strict == ScalarType::Half) return ScalarType::Half;
  return all;
}

// ---------------------------------------------------------------------------------------------
// The dispatcher

Type Sema::analyze(Expr* expr) {
  if (!expr) return Type::error();
  DepthGuard guard(*this);
  if (nesting_exceeded(expr->loc)) {
    expr->type = Type::error();
    return expr->type;
  }
  Type type;
  switch (expr->kind) {
    case ExprKind::IntLiteral: {
      auto& literal = static_cast<IntLiteralExpr&>(*expr);
      if (literal.value > 0xFFFFFFFFull) {
        diag_.error(literal.loc, "integer literal is too large for 32 bits");
      } else {
        // Too large for int without a u suffix: uint, as C does for hexadecimal literals.
        type = Type::scalar(literal.is_unsigned || literal.value > 0x7FFFFFFFull ? ScalarType::Uint : ScalarType::Int);
      }
      break;
    }
    case ExprKind::FloatLiteral:
      type = Type::scalar(static_cast<FloatLiteralExpr&>(*expr).half_suffix ? ScalarType::Half : ScalarType::Float);
      break;
    case ExprKind::BoolLiteral: type = Type::scalar(ScalarType::Bool); break;
    case ExprKind::Name: type = analyze_name(static_cast<NameExpr&>(*expr)); break;
    case ExprKind::Unary: type = analyze_unary(static_cast<UnaryExpr&>(*expr)); break;
    case ExprKind::Binary: type = analyze_binary(static_cast<BinaryExpr&>(*expr)); break;
    case ExprKind::Assign: type = analyze_assign(static_cast<AssignExpr&>(*expr)); break;
    case ExprKind::Conditional: type = analyze_conditional(static_cast<ConditionalExpr&>(*expr)); break;
    case ExprKind::Call: type = analyze_call(static_cast<CallExpr&>(*expr)); break;
    case ExprKind::Member: type = analyze_member(static_cast<MemberExpr&>(*expr)); break;
    case ExprKind::Index: type = analyze_index(static_cast<IndexExpr&>(*expr)); break;
    case ExprKind::Cast: type = analyze_cast(static_cast<CastExpr&>(*expr)); break;
    case ExprKind::InitList: {
      auto& list = static_cast<InitListExpr&>(*expr);
      for (ExprPtr& element : list.elements) analyze(element.get());
      diag_.error(list.loc, "an initializer list is only allowed in a declaration");
      break;
    }
    case ExprKind::Conversion:  // made by sema around an analyzed operand
      type = expr->type;
      break;
  }
  expr->type = type;
  return type;
}

Type Sema::analyze_name(NameExpr& expr) {
  const Symbol* symbol = lookup(expr.name);
  if (!symbol) {
    std::string message = "unknown name " + in_quotes(expr.name);
    const std::string close = suggestion(expr.name, false);
    if (!close.empty()) message += "; did you mean " + in_quotes(close) + "?";
    diag_.error(expr.loc, message);
    return Type::error();
  }
  switch (symbol->kind) {
    case Symbol::Kind::Variable:
      expr.decl = symbol->decl;
      if (symbol->decl->kind == DeclKind::Var) return static_cast<const VarDecl*>(symbol->decl)->type;
      return static_cast<const ParamDecl*>(symbol->decl)->type;
    case Symbol::Kind::Function:
      diag_.error(expr.loc, in_quotes(expr.name) + " is a function, not a value");
      return Type::error();
    case Symbol::Kind::Struct:
    case Symbol::Kind::Typedef:
      diag_.error(expr.loc, in_quotes(expr.name) + " is a type, not a value");
      return Type::error();
  }
  return Type::error();
}

// ---------------------------------------------------------------------------------------------
// Operators

Type Sema::analyze_unary(UnaryExpr& expr) {
  const Type operand = analyze(expr.operand.get());
  if (operand.is_error()) return Type::error();
  const std::string_view op = unary_spelling(expr.op);
  if (!operand.is_numeric()) {
    diag_.error(expr.loc, "cannot apply " + in_quotes(op) + " to " + in_quotes(operand.name()));
    return Type::error();
  }
  switch (expr.op) {
    case UnaryOp::Plus:
    case UnaryOp::Minus: {
      const Type result = operand.is_bool() ? Type::with_scalar(operand, ScalarType::Int) : operand;
      coerce(expr.operand, result);
      return result;
    }
    case UnaryOp::BitNot: {
      if (operand.is_floating()) {
        diag_.error(expr.loc, "'~' needs integer operands, not " + in_quotes(operand.name()));
        return Type::error();
      }
      const Type result = operand.is_bool() ? Type::with_scalar(operand, ScalarType::Int) : operand;
      coerce(expr.operand, result);
      return result;
    }
    case UnaryOp::Not: {
      const Type result = Type::with_scalar(operand, ScalarType::Bool);
      coerce(expr.operand, result);
      return result;
    }
    case UnaryOp::PreIncrement:
    case UnaryOp::PreDecrement:
    case UnaryOp::PostIncrement:
    case UnaryOp::PostDecrement:
      if (operand.is_bool()) {
        diag_.error(expr.loc, "cannot apply " + in_quotes(op) + " to " + in_quotes(operand.name()));
        return Type::error();
      }
      require_assignable(expr.operand.get());
      return operand;
  }
  return Type::error();
}

std::optional<BinaryTyping> Sema::binary_typing(BinaryOp op, Loc loc, const Expr* lhs, const Expr* rhs) {
  if (!lhs || !rhs) return std::nullopt;
  const Type& a = lhs->type;
  const Type& b = rhs->type;
  if (a.is_error() || b.is_error()) return std::nullopt;
  const std::string_view spelling = binary_spelling(op);
  if (!a.is_numeric() || !b.is_numeric()) {
    diag_.error(loc,
                "cannot apply " + in_quotes(spelling) + " to " + in_quotes(a.name()) + " and " + in_quotes(b.name()));
    return std::nullopt;
  }
  auto shape_error = [&] {
    std::string message =
        "cannot apply " + in_quotes(spelling) + " to " + in_quotes(a.name()) + " and " + in_quotes(b.name());
    if (op == BinaryOp::Mul) message += "; use mul()";
    diag_.error(loc, message);
  };
  switch (op) {
    case BinaryOp::Shl:
    case BinaryOp::Shr:
    case BinaryOp::BitAnd:
    case BinaryOp::BitOr:
    case BinaryOp::BitXor:
      if (a.is_floating() || b.is_floating()) {
        diag_.error(
            loc, in_quotes(spelling) + " needs integer operands, not " + in_quotes((a.is_floating() ? a : b).name()));
        return std::nullopt;
      }
      [[fallthrough]];
    case BinaryOp::Add:
    case BinaryOp::Sub:
    case BinaryOp::Mul:
    case BinaryOp::Div:
    case BinaryOp::Mod: {
      const Expr* const operands[] = {lhs, rhs};
      ScalarType scalar = common_scalar(operands);
      if (scalar == ScalarType::Bool) scalar = ScalarType::Int;
      const std::optional<Type> shape = combine_shapes(a, b, scalar);
      if (!shape) {
        shape_error();
        return std::nullopt;
      }
      return BinaryTyping{*shape, *shape};
    }
    case BinaryOp::LogicalAnd:
    case BinaryOp::LogicalOr: {
      const std::optional<Type> shape = combine_shapes(a, b, ScalarType::Bool);
      if (!shape) {
        shape_error();
        return std::nullopt;
      }
      return BinaryTyping{*shape, *shape};
    }
    case BinaryOp::Less:
    case BinaryOp::Greater:
    case BinaryOp::LessEqual:
    case BinaryOp::GreaterEqual:
    case BinaryOp::Equal:
    case BinaryOp::NotEqual: {
      const Expr* const operands[] = {lhs, rhs};
      const std::optional<Type> shape = combine_shapes(a, b, common_scalar(operands));
      if (!shape) {
        shape_error();
        return std::nullopt;
      }
      return BinaryTyping{*shape, Type::with_scalar(*shape, ScalarType::Bool)};
    }
    case BinaryOp::Comma: return BinaryTyping{b, b};
  }
  return std::nullopt;
}

Type Sema::analyze_binary(BinaryExpr& expr) {
  analyze(expr.lhs.get());
  const Type rhs = analyze(expr.rhs.get());
  if (expr.op == BinaryOp::Comma) return expr.lhs ? rhs : Type::error();
  const std::optional<BinaryTyping> typing = binary_typing(expr.op, expr.loc, expr.lhs.get(), expr.rhs.get());
  if (!typing) return Type::error();
  coerce(expr.lhs, typing->operand);
  coerce(expr.rhs, typing->operand);
  return typing->result;
}

Type Sema::analyze_assign(AssignExpr& expr) {
  const Type target = analyze(expr.target.get());
  if (expr.value && expr.value->kind == ExprKind::InitList) {
    analyze(expr.value.get());  // reports that a list is only allowed in a declaration
    return Type::error();
  }
  const Type value = analyze(expr.value.get());
  if (target.is_error()) return Type::error();
  require_assignable(expr.target.get());
  if (value.is_error()) return target;
  const std::optional<BinaryOp> op = compound_operator(expr.op);
  if (!op) {
    coerce(expr.value, target);
    return target;
  }
  // `t op= v`: the binary operator's rules, then the result converted back to t's type. The
  // value is converted to the operation's operand type, which may differ from t's (i *= 0.5).
  const std::optional<BinaryTyping> typing = binary_typing(*op, expr.loc, expr.target.get(), expr.value.get());
  if (!typing) return target;
  coerce(expr.value, typing->operand);
  const Conversion back = classify_implicit(typing->result, target);
  if (!back.valid) {
    diag_.error(expr.loc,
                "cannot convert from " + in_quotes(typing->result.name()) + " to " + in_quotes(target.name()));
  } else if (back.truncation) {
    diag_.warning(expr.loc, truncation_message(typing->result, target));
  }
  return target;
}

Type Sema::analyze_conditional(ConditionalExpr& expr) {
  const Type condition = analyze(expr.condition.get());
  const Type a = analyze(expr.then_value.get());
  const Type b = analyze(expr.else_value.get());
  if (!expr.then_value || !expr.else_value) return Type::error();
  if (a.is_error() || b.is_error()) return Type::error();
  Type result;
  if (a.is_numeric() && b.is_numeric()) {
    const Expr* const operands[] = {expr.then_value.get(), expr.else_value.get()};
    const ScalarType scalar = common_scalar(operands);
    std::optional<Type> shape = combine_shapes(a, b, scalar);
    if (!shape) {
      diag_.error(expr.loc, "cannot combine " + in_quotes(a.name()) + " and " + in_quotes(b.name()) + " in '?:'");
      return Type::error();
    }
    if (condition.is_numeric() && condition.component_count() > 1) {
      // Component-wise selection: the condition's shape joins the values' shape.
      shape = combine_shapes(condition, *shape, scalar);
      if (!shape) {
        diag_.error(expr.loc, "cannot combine condition " + in_quotes(condition.name()) + " with " +
                                  in_quotes(a.name()) + " in '?:'");
        return Type::error();
      }
      coerce(expr.condition, Type::with_scalar(*shape, ScalarType::Bool));
    } else {
      coerce(expr.condition, Type::scalar(ScalarType::Bool));
    }
    result = *shape;
  } else if (a == b && !a.is_void()) {
    result = a;
    if (condition.is_numeric() && condition.component_count() > 1) {
      diag_.error(expr.condition->loc,
                  "condition must be a scalar, not " + in_quotes(condition.name()) + "; use any() or all()");
    } else {
      coerce(expr.condition, Type::scalar(ScalarType::Bool));
    }
    return result;
  } else {
    diag_.error(expr.loc, "cannot combine " + in_quotes(a.name()) + " and " + in_quotes(b.name()) + " in '?:'");
    return Type::error();
  }
  coerce(expr.then_value, result);
  coerce(expr.else_value, result);
  return result;
}

// ---------------------------------------------------------------------------------------------
// Members and indexing

namespace {

// xyzw / rgba swizzles of a scalar or vector. Returns an error message, or "" on success.
std::string parse_vector_swizzle(const std::string& member, const Type& object, Swizzle& out) {
  static constexpr std::string_view kXyzw = "xyzw";
  static constexpr std::string_view kRgba = "rgba";
  bool xyzw = false, rgba = false;
  for (char c : member) {
    if (kXyzw.find(c) != std::string_view::npos) {
      xyzw = true;
    } else if (kRgba.find(c) != std::string_view::npos) {
      rgba = true;
    } else {
      return in_quotes(object.name()) + " has no member " + in_quotes(member);
    }
  }
  if (member.empty()) return in_quotes(object.name()) + " has no member ''";
  if (member.size() > 4) return "swizzle " + in_quotes(member) + " has more than 4 components";
  if (xyzw && rgba) return "swizzle " + in_quotes(member) + " mixes xyzw and rgba components";
  const uint32_t length = object.is_vector() ? object.cols() : 1;
  for (char c : member) {
    const size_t index = xyzw ? kXyzw.find(c) : kRgba.find(c);
    if (index >= length) return "swizzle " + in_quotes(member) + " is out of range for " + in_quotes(object.name());
    out.push_back(uint8_t(index));
  }
  return "";
}

// _m00 (zero-based) and _11 (one-based) matrix swizzles, possibly concatenated.
std::string parse_matrix_swizzle(const std::string& member, const Type& object, Swizzle& out) {
  const std::string no_member = in_quotes(object.name()) + " has no member " + in_quotes(member);
  size_t pos = 0;
  int based = -1;  // 0 or 1 once known
  bool out_of_range = false;
  while (pos < member.size()) {
    if (member[pos] != '_') return no_member;
    ++pos;
    int form = 1;
    if (pos < member.size() && member[pos] == 'm') {
      form = 0;
      ++pos;
    }
    if (based != -1 && based != form) {
      return "matrix swizzle " + in_quotes(member) + " mixes zero-based and one-based components";
    }
    based = form;
    if (pos + 2 > member.size()) return no_member;
    const int row = member[pos] - '0' - form;
    const int col = member[pos + 1] - '0' - form;
    pos += 2;
    if (row < 0 || row > 3 || col < 0 || col > 3) return no_member;
    if (uint32_t(row) >= object.rows() || uint32_t(col) >= object.cols()) out_of_range = true;
    if (out.size() == 4) return "swizzle " + in_quotes(member) + " has more than 4 components";
    out.push_back(uint8_t(row * 4 + col));
  }
  if (out.empty()) return no_member;
  if (out_of_range) return "swizzle " + in_quotes(member) + " is out of range for " + in_quotes(object.name());
  return "";
}

}  // namespace

Type Sema::analyze_member(MemberExpr& expr) {
  const Type object = analyze(expr.object.get());
  if (object.is_error()) return Type::error();
  expr.swizzle.clear();
  if (object.kind() == TypeKind::Struct || object.kind() == TypeKind::ConstantBuffer) {
    // ConstantBuffer<S> cb: cb.field reads the buffer's member.
    const Type& structure = object.kind() == TypeKind::Struct ? object : object.element();
    const StructDecl* decl = structure.struct_decl();
    if (decl) {
      for (size_t i = 0; i < decl->fields.size(); ++i) {
        if (decl->fields[i].name == expr.member) {
          expr.field_index = int(i);
          return decl->fields[i].type;
        }
      }
    }
    diag_.error(expr.loc, in_quotes(object.name()) + " has no member " + in_quotes(expr.member));
    return Type::error();
  }
  std::string error;
  if (object.is_scalar() || object.is_vector()) {
    error = parse_vector_swizzle(expr.member, object, expr.swizzle);
  } else if (object.is_matrix()) {
    error = parse_matrix_swizzle(expr.member, object, expr.swizzle);
  } else {
    error = in_quotes(object.name()) + " has no member " + in_quotes(expr.member);
  }
  if (!error.empty()) {
    expr.swizzle.clear();
    diag_.error(expr.loc, error);
    return Type::error();
  }
  const uint32_t count = uint32_t(expr.swizzle.size());
  return count == 1 ? Type::scalar(object.scalar_type()) : Type::vector(object.scalar_type(), count);
}

Type Sema::analyze_index(IndexExpr& expr) {
  const Type object = analyze(expr.object.get());
  const Type index = analyze(expr.index.get());
  Type result;
  uint32_t length = 0;
  switch (object.kind()) {
    case TypeKind::Error: return Type::error();  // reported; its index would only add noise
    case TypeKind::Array:
      result = object.element();
      length = object.array_length();
      break;
    case TypeKind::Vector:
      result = Type::scalar(object.scalar_type());
      length = object.cols();
      break;
    case TypeKind::Matrix:  // HLSL: M[i] is row i
      result = Type::vector(object.scalar_type(), object.cols());
      length = object.rows();
      break;
    case TypeKind::Texture:
    case TypeKind::Buffer: return analyze_resource_index(expr, object);
    default: diag_.error(expr.loc, "cannot index a value of type " + in_quotes(object.name())); return Type::error();
  }
  if (expr.index && !index.is_error()) {
    if (!index.is_numeric() || index.component_count() != 1) {
      diag_.error(expr.index->loc, "index must be an integer scalar, not " + in_quotes(index.name()));
      return Type::error();
    }
    if (!index.is_scalar() || !index.is_integer()) {
      // HLSL converts a float index to int without a warning.
      wrap_conversion(expr.index, Type::scalar(index.is_integer() ? index.scalar_type() : ScalarType::Int));
    }
    if (length > 0) {
      const std::optional<int64_t> value = fold_int(expr.index.get());
      if (value && (*value < 0 || *value >= int64_t(length))) {
        diag_.error(expr.index->loc,
                    "index " + std::to_string(*value) + " is out of range for " + in_quotes(object.name()));
        return Type::error();
      }
    }
  }
  return result;
}

Type Sema::analyze_cast(CastExpr& expr) {
  const Type operand = analyze(expr.operand.get());
  const Type& target = expr.target;
  if (target.is_error() || !expr.operand) return Type::error();
  if (operand.is_error()) return target;
  if (!explicit_cast_allowed(operand, target, is_literal(expr.operand.get()), facts_)) {
    diag_.error(expr.loc, "cannot convert from " + in_quotes(operand.name()) + " to " + in_quotes(target.name()));
    return Type::error();
  }
  return target;
}

// ---------------------------------------------------------------------------------------------
// L-values

std::optional<std::pair<Loc, std::string>> Sema::not_assignable(const Expr* expr) const {
  if (!expr || expr->type.is_error()) return std::nullopt;
  if (facts_contain_resource(expr->type) && !rooted_in_local(expr)) {
    return std::make_pair(expr->loc, in_quotes(expr->type.name()) +
                                         " objects are only assignable to local variables, which then name them");
  }
  // Walk down fields, swizzles and indices to the variable at the root.
  for (int step = 0; expr; ++step) {
    if (step > kMaxNesting || expr->type.is_error()) return std::nullopt;
    switch (expr->kind) {
      case ExprKind::Name: {
        const auto& name = static_cast<const NameExpr&>(*expr);
        if (!name.decl) return std::nullopt;
        if (name.decl->kind == DeclKind::Var) {
          const auto& var = static_cast<const VarDecl&>(*name.decl);
          if (var.is_const)
            return std::make_pair(expr->loc, "cannot assign to " + in_quotes(var.name) + ": it is const");
          if (is_uniform(var)) {
            return std::make_pair(expr->loc, "cannot assign to " + in_quotes(var.name) + ": uniforms are read-only");
          }
          return std::nullopt;
        }
        if (name.decl->kind == DeclKind::Param) {
          const auto& param = static_cast<const ParamDecl&>(*name.decl);
          if (param.is_uniform) {
            return std::make_pair(expr->loc, "cannot assign to " + in_quotes(param.name) + ": uniforms are read-only");
          }
          return std::nullopt;
        }
        return std::make_pair(expr->loc, std::string("expression is not assignable"));
      }
      case ExprKind::Member: {
        const auto& member = static_cast<const MemberExpr&>(*expr);
        for (size_t i = 0; i < member.swizzle.size(); ++i) {
          for (size_t j = i + 1; j < member.swizzle.size(); ++j) {
            if (member.swizzle[i] == member.swizzle[j]) {
              return std::make_pair(expr->loc, std::string("cannot assign to a swizzle with repeated components"));
            }
          }
        }
        expr = member.object.get();
        break;
      }
      case ExprKind::Index: {
        const Expr* object = static_cast<const IndexExpr&>(*expr).object.get();
        if (object && is_writable_resource(object->type)) return std::nullopt;  // rw[p] = v
        expr = object;
        break;
      }
      default: return std::make_pair(expr->loc, std::string("expression is not assignable"));
    }
  }
  return std::nullopt;
}

bool Sema::facts_contain_resource(const Type& type) const { return facts_.contains_resource(type); }

bool Sema::rooted_in_local(const Expr* expr) const {
  for (int step = 0; expr && step <= kMaxNesting; ++step) {
    switch (expr->kind) {
      case ExprKind::Name: {
        const Decl* decl = static_cast<const NameExpr*>(expr)->decl;
        return decl && decl->kind == DeclKind::Var && !static_cast<const VarDecl*>(decl)->is_global;
      }
      case ExprKind::Member: expr = static_cast<const MemberExpr*>(expr)->object.get(); break;
      default: return false;
    }
  }
  return false;
}

void Sema::require_assignable(const Expr* expr) {
  if (auto reason = not_assignable(expr)) diag_.error(reason->first, reason->second);
}

// ---------------------------------------------------------------------------------------------
// Constant folding (array sizes, constant indices, infinite loops)

std::optional<int64_t> Sema::fold_int(const Expr* expr, int depth) const {
  if (!expr || depth > kMaxNesting) return std::nullopt;
  switch (expr->kind) {
    case ExprKind::IntLiteral: {
      const uint64_t value = static_cast<const IntLiteralExpr*>(expr)->value;
      if (value > 0xFFFFFFFFull) return std::nullopt;
      return int64_t(value);
    }
    case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr*>(expr)->value ? 1 : 0;
    case ExprKind::Name: {
      const Decl* decl = static_cast<const NameExpr*>(expr)->decl;
      if (!decl || decl->kind != DeclKind::Var) return std::nullopt;
      const auto* var = static_cast<const VarDecl*>(decl);
      if (!var->is_const || is_uniform(*var) || !var->type.is_scalar() || !var->type.is_integer()) return std::nullopt;
      // Memoized: constants defined from constants would otherwise be folded over and over.
      if (auto it = folded_.find(var); it != folded_.end()) return it->second;
      folded_[var] = std::nullopt;
      const std::optional<int64_t> value = fold_int(var->initializer.get(), depth + 1);
      folded_[var] = value;
      return value;
    }
    case ExprKind::Conversion: {
      const auto* conversion = static_cast<const ConversionExpr*>(expr);
      if (!conversion->type.is_scalar() || conversion->type.is_floating()) return std::nullopt;
      return fold_int(conversion->operand.get(), depth + 1);
    }
    case ExprKind::Cast: {
      const auto* cast = static_cast<const CastExpr*>(expr);
      if (!cast->target.is_scalar() || cast->target.is_floating()) return std::nullopt;
      return fold_int(cast->operand.get(), depth + 1);
    }
    case ExprKind::Unary: {
      const auto* unary = static_cast<const UnaryExpr*>(expr);
      const std::optional<int64_t> value = fold_int(unary->operand.get(), depth + 1);
      if (!value) return std::nullopt;
      switch (unary->op) {
        case UnaryOp::Plus: return value;
        case UnaryOp::Minus: return in_fold_range(-*value);
        case UnaryOp::BitNot: return in_fold_range(~*value);
        case UnaryOp::Not: return *value == 0 ? 1 : 0;
        default: return std::nullopt;
      }
    }
    case ExprKind::Binary: {
      const auto* binary = static_cast<const BinaryExpr*>(expr);
      const std::optional<int64_t> a = fold_int(binary->lhs.get(), depth + 1);
      const std::optional<int64_t> b = fold_int(binary->rhs.get(), depth + 1);
      if (!a || !b) return std::nullopt;
      int64_t result = 0;
      bool overflow = false;
      switch (binary->op) {
        case BinaryOp::Add: overflow = __builtin_add_overflow(*a, *b, &result); break;
        case BinaryOp::Sub: overflow = __builtin_sub_overflow(*a, *b, &result); break;
        case BinaryOp::Mul: overflow = __builtin_mul_overflow(*a, *b, &result); break;
        case BinaryOp::Div:
          if (*b == 0) return std::nullopt;
          result = *a / *b;
          break;
        case BinaryOp::Mod:
          if (*b == 0) return std::nullopt;
          result = *a % *b;
          break;
        case BinaryOp::Shl:
          if (*b < 0 || *b > 31 || *a < 0) return std::nullopt;
          result = int64_t(uint64_t(*a) << *b);  // below 2^63: a < 2^32
          break;
        case BinaryOp::Shr:
          if (*b < 0 || *b > 31) return std::nullopt;
          result = *a >> *b;
          break;
        case BinaryOp::BitAnd: result = *a & *b; break;
        case BinaryOp::BitOr: result = *a | *b; break;
        case BinaryOp::BitXor: result = *a ^ *b; break;
        case BinaryOp::Less: result = *a < *b; break;
        case BinaryOp::Greater: result = *a > *b; break;
        case BinaryOp::LessEqual: result = *a <= *b; break;
        case BinaryOp::GreaterEqual: result = *a >= *b; break;
        case BinaryOp::Equal: result = *a == *b; break;
        case BinaryOp::NotEqual: result = *a != *b; break;
        case BinaryOp::LogicalAnd: result = *a && *b; break;
        case BinaryOp::LogicalOr: result = *a || *b; break;
        case BinaryOp::Comma: result = *b; break;
      }
      if (overflow) return std::nullopt;
      return in_fold_range(result);
    }
    default: return std::nullopt;
  }
}

// ---------------------------------------------------------------------------------------------
// Initializers

namespace {

// Lays the flattened leaves of an initializer list out over the declared type, HLSL-style:
// arrays and structs get one element per member, vectors and matrices (and scalars) take leaves
// until their components are filled. A first pass (`dry`) only checks that no leaf straddles two
// members; the second moves the leaves into place.
class InitLayout {
 public:
  InitLayout(Sema& sema, AstVector<ExprPtr>& leaves, const Type& declared, Loc loc)
      : sema_(sema), leaves_(leaves), declared_(declared), loc_(loc) {}

  // Returns false (after reporting) when a leaf straddles members.
  bool check() {
    dry_ = true;
    next_ = 0;
    visits_ = 0;
    ExprPtr unused;
    build(declared_, 0, unused);
    return !failed_;
  }

  ExprPtr layout() {
    dry_ = false;
    next_ = 0;
    visits_ = 0;
    ExprPtr result;
    build(declared_, 0, result);
    return result;
  }

 private:
  const Type& leaf_type() const { return leaves_[next_]->type; }

  void take(ExprPtr& out) {
    if (!dry_) out = std::move(leaves_[next_]);
    ++next_;
  }

  std::unique_ptr<InitListExpr> new_list(const Type& type) {
    if (dry_) return nullptr;
    auto list = std::make_unique<InitListExpr>(loc_);
    list->type = type;
    return list;
  }

  void straddle() {
    if (!failed_) {
      sema_.diag_.error(leaves_[next_]->loc, "initializer element of type " + in_quotes(leaf_type().name()) +
                                                 " spans several elements of " + in_quotes(declared_.name()));
    }
    failed_ = true;
  }

  void build(const Type& type, int depth, ExprPtr& out) {
    if (failed_) return;
    if (++visits_ > kMaxVisits) {
      // Members without components (empty structs) cost visits but no leaves.
      sema_.diag_.error(loc_, "initializer list of " + in_quotes(declared_.name()) + " is too large");
      failed_ = true;
      return;
    }
    if (next_ >= leaves_.size() || depth > kMaxNesting) {
      failed_ = true;
      return;
    }
    if (type.is_numeric()) {
      const Type& leaf = leaf_type();
      if (leaf.is_numeric() && leaf.kind() == type.kind() && leaf.rows() == type.rows() && leaf.cols() == type.cols()) {
        take(out);
        if (!dry_) sema_.wrap_conversion(out, type);
        return;
      }
      std::unique_ptr<InitListExpr> list = new_list(type);
      uint32_t filled = 0;
      while (filled < type.component_count()) {
        if (next_ >= leaves_.size()) {
          failed_ = true;
          return;
        }
        const Type& part = leaf_type();
        if (!part.is_numeric() || filled + part.component_count() > type.component_count()) {
          straddle();
          return;
        }
        filled += part.component_count();
        const Type converted = Type::with_scalar(part, type.scalar_type());
        ExprPtr element;
        take(element);
        if (!dry_) {
          sema_.wrap_conversion(element, converted);
          list->elements.push_back(std::move(element));
        }
      }
      out = std::move(list);
      return;
    }
    if (type.kind() == TypeKind::Struct || type.kind() == TypeKind::Array) {
      if (leaf_type() == type) {
        take(out);
        return;
      }
      std::unique_ptr<InitListExpr> list = new_list(type);
      auto member = [&](const Type& member_type) {
        ExprPtr element;
        build(member_type, depth + 1, element);
        if (!dry_ && !failed_) list->elements.push_back(std::move(element));
      };
      if (type.kind() == TypeKind::Struct) {
        if (type.struct_decl()) {
          for (const FieldDecl& field : type.struct_decl()->fields) {
            member(field.type);
            if (failed_) return;
          }
        }
      } else {
        for (uint32_t i = 0; i < type.array_length() && !failed_; ++i) member(type.element());
      }
      out = std::move(list);
      return;
    }
    straddle();
  }

  Sema& sema_;
  AstVector<ExprPtr>& leaves_;
  const Type& declared_;
  Loc loc_;
  static constexpr size_t kMaxVisits = size_t(1) << 20;
  size_t next_ = 0;
  size_t visits_ = 0;
  bool dry_ = true;
  bool failed_ = false;
};

std::string type_name_for_count(const Type& type) {
  if (type.kind() == TypeKind::Array && type.array_length() == 0) return type.element().name() + "[]";
  return type.name();
}

}  // namespace

void Sema::analyze_initializer(ExprPtr& init, Type& declared, const std::string& var_name) {
  if (!init) return;
  const bool unsized = declared.kind() == TypeKind::Array && declared.array_length() == 0;
  if (init->kind != ExprKind::InitList) {
    const Type type = analyze(init.get());
    if (unsized) {
      if (!type.is_error())
        diag_.error(init->loc, "unsized array " + in_quotes(var_name) + " needs an initializer list");
      return;
    }
    coerce(init, declared);
    return;
  }
  auto& list = static_cast<InitListExpr&>(*init);
  // Flatten nested lists into leaves, analyzing each leaf.
  AstVector<ExprPtr> leaves;
  struct Frame {
    InitListExpr* list;
    size_t next;
  };
  std::vector<Frame> stack{{&list, 0}};
  while (!stack.empty()) {
    Frame& frame = stack.back();
    if (frame.next >= frame.list->elements.size()) {
      stack.pop_back();
      continue;
    }
    ExprPtr& element = frame.list->elements[frame.next++];
    if (!element) continue;
    if (element->kind == ExprKind::InitList) {
      if (stack.size() > size_t(kMaxNesting)) {
        nesting_exceeded(element->loc);
        continue;
      }
      stack.push_back({static_cast<InitListExpr*>(element.get()), 0});
      continue;
    }
    analyze(element.get());
    leaves.push_back(std::move(element));
  }
  // The leaves now belong to `leaves`; nested lists are empty shells.
  list.elements.clear();
  auto keep_leaves = [&] {
    list.elements = std::move(leaves);
    list.type = unsized ? Type::error() : declared;
  };
  uint64_t total = 0;
  bool failed = false;
  for (const ExprPtr& leaf : leaves) {
    if (leaf->type.is_error()) {
      failed = true;
      continue;
    }
    const std::optional<uint64_t> count = facts_.component_count(leaf->type);
    if (!count) {
      diag_.error(leaf->loc, "cannot use a value of type " + in_quotes(leaf->type.name()) + " in an initializer list");
      failed = true;
      continue;
    }
    total += *count;
  }
  if (failed || declared.is_error()) {
    keep_leaves();
    return;
  }
  if (unsized) {
    const std::optional<uint64_t> element = facts_.component_count(declared.element());
    if (!element || *element == 0) {
      diag_.error(list.loc, in_quotes(type_name_for_count(declared)) + " cannot be initialized with a list");
      keep_leaves();
      return;
    }
    if (total == 0 || total % *element != 0) {
      diag_.error(list.loc, "initializer has " + std::to_string(total) + " components, " +
                                in_quotes(type_name_for_count(declared)) + " needs a multiple of " +
                                std::to_string(*element));
      keep_leaves();
      return;
    }
    declared = Type::array(declared.element(), uint32_t(total / *element));
  }
  const std::optional<uint64_t> needed = facts_.component_count(declared);
  if (!needed) {
    diag_.error(list.loc, in_quotes(declared.name()) + " cannot be initialized with a list");
    keep_leaves();
    return;
  }
  if (total != *needed) {
    diag_.error(list.loc, "initializer has " + std::to_string(total) + " components, " + in_quotes(declared.name()) +
                              " needs " + std::to_string(*needed));
    keep_leaves();
    return;
  }
  InitLayout layout(*this, leaves, declared, list.loc);
  if (!layout.check()) {
    keep_leaves();
    return;
  }
  ExprPtr built = layout.layout();
  if (built->kind != ExprKind::InitList && declared.is_numeric()) {
    // `float4 v = {v4}`: a vector's list holds leaves whose components add up, so keep it.
    list.elements.push_back(std::move(built));
    list.type = declared;
    return;
  }
  // An aggregate's list has one element per member; `S s = {other_s}` is just `other_s`.
  init = std::move(built);  // the original (now empty) list goes away
}

}  // namespace xshade::hlsl::sema_detail
