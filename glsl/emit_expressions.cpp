// Types, expressions and conversions. Sema made every implicit HLSL conversion an explicit
// ConversionExpr; here each becomes the GLSL constructor or swizzle that computes the same value.
// Why this file is long: an expression's GLSL depends on its operands' types and on the
// conversions sema made explicit; keeping every expression form beside the one set of type and
// conversion helpers it uses is easier to follow than splitting one table-like switch.
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "glsl/stage_emitter.h"
#include "hlsl_like/ast_walk.h"

namespace xshade::glsl::detail {

using namespace hlsl;

namespace {

// `text` is one call of `function`, whose closing parenthesis ends the text.
bool is_whole_call(const std::string& text, std::string_view function) {
  if (text.size() < function.size() + 2 || text.compare(0, function.size(), function) != 0 ||
      text[function.size()] != '(' || text.back() != ')')
    return false;
  int depth = 0;
  for (size_t i = function.size(); i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    if (text[i] == ')' && --depth == 0) return i == text.size() - 1;
  }
  return false;
}

const char* scalar_glsl(ScalarType scalar) {
  switch (scalar) {
    case ScalarType::Bool: return "bool";
    case ScalarType::Int: return "int";
    case ScalarType::Uint: return "uint";
    case ScalarType::Half:  // computed in fp32; see StageEmitter::half_value
    case ScalarType::Float: return "float";
  }
  return "float";
}

const char* vector_prefix(ScalarType scalar) {
  switch (scalar) {
    case ScalarType::Bool: return "bvec";
    case ScalarType::Int: return "ivec";
    case ScalarType::Uint: return "uvec";
    case ScalarType::Half:
    case ScalarType::Float: return "vec";
  }
  return "vec";
}

// GLSL's name for `type`, or why it has none.
std::string glsl_type(const Type& type, Flavour flavour, std::string* why) {
  switch (type.kind()) {
    case TypeKind::Void: return "void";
    case TypeKind::Scalar: return scalar_glsl(type.scalar_type());
    case TypeKind::Vector:
      if (type.cols() == 1) return scalar_glsl(type.scalar_type());
      return vector_prefix(type.scalar_type()) + std::to_string(type.cols());
    case TypeKind::Matrix: {
      // HLSL floatRxC (R rows) is held transposed: GLSL matRxC has R columns of C components.
      if (!type.is_floating()) {
        if (why)
          *why = "matrices of " + scalar_name(type.scalar_type()) + " (" + in_quotes(type.name()) +
                 ") are not supported on this target";
        return type.name();
      }
      if (type.rows() == 1 || type.cols() == 1) {
        if (why)
          *why = "matrices with one row or column (" + in_quotes(type.name()) + ") are not supported on this target";
        return type.name();
      }
      if (type.rows() == type.cols()) return "mat" + std::to_string(type.rows());
      return "mat" + std::to_string(type.rows()) + "x" + std::to_string(type.cols());
    }
    case TypeKind::Struct: return type.struct_decl() ? type.struct_decl()->name : "?";
    case TypeKind::Array:
      return glsl_type(type.element(), flavour, why) + "[" + std::to_string(type.array_length()) + "]";
    case TypeKind::Texture:
    case TypeKind::Sampler:
    case TypeKind::SamplerState:
      // Their spelling depends on the declaration as well (StageEmitter::resource_type); this
      // one serves to tell overloads apart.
      if (flavour == Flavour::Gl && type.kind() == TypeKind::SamplerState && why)
        *why = "a SamplerState has no GLSL type on OpenGL";
      return type.name();
    case TypeKind::Buffer:
      if (why)
        *why = in_quotes(type.name()) +
               " is not supported on this target: shaders here read textures, constant buffers and "
               "read-only buffers (StructuredBuffer, ByteAddressBuffer, Buffer)";
      return type.name();
    case TypeKind::ConstantBuffer:
      if (why) *why = in_quotes(type.name()) + " can only be a global variable";
      return type.name();
    case TypeKind::Error:
      if (why) *why = "an expression without a type";
      return "?";
  }
  return "?";
}

// A float literal's spelling as GLSL reads it: always with a `.` or an exponent.
std::string float_text(const std::string& spelling) {
  if (spelling.find_first_of(".eE") == std::string::npos) return spelling + ".0";
  return spelling;
}

// A scalar literal rounded to fp16 and spelt as a literal (lower::HalfEmulation::rounded_literal).
std::optional<std::string> half_literal(const std::string& text) {
  const std::optional<float> rounded = lower::HalfEmulation::rounded_literal(text);
  if (!rounded) return std::nullopt;
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof buffer, *rounded);  // the shortest exact spelling
  return float_text(std::string(buffer, written.ptr));
}

bool is_split_name(const Expr* e, const std::unordered_map<const Decl*, lower::SplitMember>& split) {
  return e && e->kind == ExprKind::Name && split.count(static_cast<const NameExpr*>(e)->decl) > 0;
}

// Text made of identifier characters and dots only: a name, a literal, a field or swizzle.
bool is_simple_text(const std::string& text) {
  for (char c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.')) return false;
  return !text.empty();
}

// `type(value)`: a constructor or conversion of one argument.
Code constructed(const std::string& type, const Code& value) {
  std::string text;
  text.reserve(type.size() + value.text.size() + 4);
  text += type;
  text += '(';
  append_operand(text, value, kAssign);
  text += ')';
  return {std::move(text)};
}

}  // namespace

std::string StageEmitter::type_name(const Type& type, Loc loc) {
  // Scalars and vectors, most of what is asked, from a table: glsl_type spells them without a
  // complaint, and building their names was much of its cost.
  if ((type.kind() == TypeKind::Scalar || type.kind() == TypeKind::Vector) && type.cols() >= 1 && type.cols() <= 4) {
    static constexpr const char* kNames[5][4] = {
        {"bool", "bvec2", "bvec3", "bvec4"},  // Bool
        {"int", "ivec2", "ivec3", "ivec4"},   // Int
        {"uint", "uvec2", "uvec3", "uvec4"},  // Uint
        {"float", "vec2", "vec3", "vec4"},    // Half, computed in fp32
        {"float", "vec2", "vec3", "vec4"},    // Float
    };
    const uint32_t count = type.kind() == TypeKind::Vector ? type.cols() : 1;
    return kNames[size_t(type.scalar_type())][count - 1];
  }
  std::string why;
  std::string name = glsl_type(type, flavour_, &why);
  if (!why.empty()) fail(loc, why);
  if (type.kind() == TypeKind::Struct && type.struct_decl()) return names_.type(type.struct_decl());
  if (type.kind() == TypeKind::Array) {
    // The element's name (a struct's may be renamed) and the lengths.
    const Type* element = &type;
    std::string lengths;
    while (element->kind() == TypeKind::Array) {
      lengths += "[" + std::to_string(element->array_length()) + "]";
      element = &element->element();
    }
    return type_name(*element, loc) + lengths;
  }
  return name;
}

std::string StageEmitter::declarator(const Type& type, const std::string& name, Loc loc) {
  const Type* element = &type;
  while (element->kind() == TypeKind::Array) element = &element->element();
  std::string text = type_name(*element, loc);
  text += ' ';
  text += name;
  for (const Type* array = &type; array->kind() == TypeKind::Array; array = &array->element()) {
    text += '[';
    text += std::to_string(array->array_length());
    text += ']';
  }
  return text;
}

bool StageEmitter::same_glsl(const Type& a, const Type& b) {
  if (a.is_error() || b.is_error()) return true;
  if (a.kind() == TypeKind::Struct || b.kind() == TypeKind::Struct) return a == b;
  // Scalars and vectors, most of what is asked, without spelling them.
  const auto numeric = [](TypeKind kind) { return kind == TypeKind::Scalar || kind == TypeKind::Vector; };
  if (numeric(a.kind()) && numeric(b.kind())) return lower::same_glsl_scalar_or_vector(a, b);
  return glsl_type(a, flavour_, nullptr) == glsl_type(b, flavour_, nullptr);
}

std::string StageEmitter::bool_type(uint32_t count) { return count <= 1 ? "bool" : "bvec" + std::to_string(count); }

Code StageEmitter::half_value(Code value, const Type& type) {
  if (!half_.rounds(type)) return value;
  if (is_whole_call(value.text, "xs_half")) return value;  // rounded already
  if (type.component_count() == 1)
    if (std::optional<std::string> literal = half_literal(value.text)) return {*literal, value.prec};
  // Rounded by arithmetic, not by unpackHalf2x16(packHalf2x16(x)): the same value (fp16's
  // round-to-nearest-even, infinity past 65504, the sign of zero kept; tests/lanes/
  // half_emulation_test.cpp compares the two on every exponent), but LLVM compiles a shader
  // full of packs about four times slower, which is most of what an fp16 stability case costs.
  // x + c - c rounds x to a multiple of c's float ulp: c = 1.5 x 2^(e + 13) for x's binade
  // [2^e, 2^(e+1)) has ulp 2^(e - 10), fp16's step there (2^-24 below 2^-14, its subnormals),
  // and an even multiple of that step, so float's ties-to-even is fp16's. `precise` keeps the
  // compilers from folding the sum away.
  const uint32_t count = type.component_count();
  const std::string n = count == 1 ? "" : std::to_string(count);
  const std::string f = count == 1 ? "float" : "vec" + n;
  const std::string u = count == 1 ? "uint" : "uvec" + n;
  const std::string overflows = count == 1 ? "abs(x) >= 65520.0" : "greaterThanEqual(abs(x), " + f + "(65520.0))";
  helpers_.add(
      "xs_half(" + f + ")",
      f + " xs_half(" + f + " x) {\n" + "  " + u + " sign = floatBitsToUint(x) & 0x80000000u;\n" + "  " + f +
          " c = max(uintBitsToFloat(floatBitsToUint(x) & 0x7f800000u), 6.103515625e-05) * 12288.0;\n" + "  precise " +
          f + " rounded = (x + c) - c;\n" +
          // 65520, halfway from 65504 to 65536, rounds to even: infinity.
          "  return mix(uintBitsToFloat(floatBitsToUint(rounded) | sign), uintBitsToFloat(sign | 0x7f800000u), " +
          overflows + ");\n}\n");
  return {"xs_half(" + value.text + ")", kPostfix};
}

Code StageEmitter::increment(const UnaryExpr& e, const Code& target) {
  const bool up = e.op == UnaryOp::PreIncrement || e.op == UnaryOp::PostIncrement;
  const bool after = (e.op == UnaryOp::PostIncrement || e.op == UnaryOp::PostDecrement) && &e != value_discarded_;
  if (!half_.rounds_increment(e)) {
    if (e.op == UnaryOp::PostIncrement || e.op == UnaryOp::PostDecrement)
      return {operand(target, kPostfix) + (up ? "++" : "--"), kPostfix};
    return {(up ? "++" : "--") + operand(target, kUnary), kUnary};
  }
  // t = xs_half(t + 1.0): the target is read and written, so it is written out twice.
  if (has_side_effects(e.operand.get())) {
    fail(e.loc, std::string("'") + (up ? "++" : "--") +
                    "' on a half value inside an expression with side effects is not supported with half "
                    "emulation; compute the target once into a variable");
    return target;
  }
  const std::string step = up ? " + 1.0" : " - 1.0";
  const Code rounded = half_value({operand(target, kAdditive) + step, kAdditive}, e.operand->type);
  if (!after) return {operand(target, kUnary) + " = " + rounded.text, kAssign};
  // The old value is the expression's: a helper that writes the rounded new value and returns the
  // old one (GLSL has no statement expressions); half_value above has declared its xs_half.
  const std::string type =
      e.operand->type.component_count() == 1 ? "float" : "vec" + std::to_string(e.operand->type.component_count());
  const std::string name = std::string("xs_half_") + (up ? "increment" : "decrement") + "_after";
  helpers_.add(name + "(" + type + ")", type + " " + name + "(inout " + type + " v) {\n  " + type +
                                            " old = v;\n  v = xs_half(v" + step + ");\n  return old;\n}\n");
  return {name + "(" + target.text + ")", kPostfix};
}

// ---------------------------------------------------------------------------------------------
// Conversions

Code StageEmitter::convert(Code value, const Type& from, const Type& to, Loc loc) {
  Code converted = convert_components(std::move(value), from, to, loc);
  if (half_.rounds_conversion(from, to)) return half_value(std::move(converted), to);
  return converted;
}

Code StageEmitter::convert_components(Code value, const Type& from, const Type& to, Loc loc) {
  if (from.is_error() || to.is_error() || to.is_void() || same_glsl(from, to)) return value;
  if (!from.is_numeric() || !to.is_numeric()) {
    fail(loc, "cannot convert " + in_quotes(from.name()) + " to " + in_quotes(to.name()) + " on this target");
    return value;
  }
  const uint32_t from_count = from.component_count();
  const uint32_t to_count = to.component_count();
  const std::string target = type_name(to, loc);
  const bool same_scalar = same_glsl(Type::scalar(from.scalar_type()), Type::scalar(to.scalar_type()));
  if (from_count == 1) {
    if (to.is_matrix()) {
      // GLSL's mat3(x) is a diagonal matrix; HLSL's splat fills every component.
      const Code scalar = from.is_floating() ? value : Code{"float(" + value.text + ")"};
      if (is_simple_text(scalar.text)) {
        const std::string column = type_name(Type::vector(ScalarType::Float, to.cols()), loc) + "(" + scalar.text + ")";
        std::string text = target + "(";
        for (uint32_t i = 0; i < to.rows(); ++i) text += (i ? ", " : "") + column;
        return {text + ")"};
      }
      return {"(" + target + "(0.0) + " + operand(scalar, kMultiplicative) + ")"};
    }
    return constructed(target, value);  // float(i), vec3(x), bvec2(x)
  }
  if (from.is_vector()) {
    if (to_count == 1) {
      std::string first = operand(std::move(value), kPostfix);
      first += ".x";
      if (same_scalar) return {std::move(first), kPostfix};
      return {target + "(" + first + ")"};
    }
    if (to.is_vector()) {
      if (to_count < from_count && same_scalar) {
        std::string text = operand(std::move(value), kPostfix);
        text += '.';
        text.append(kComponents, to_count);
        return {std::move(text), kPostfix};
      }
      return constructed(target, value);  // vec3(ivec3), vec3(ivec4)
    }
    // (float2x2)v: components in HLSL's row order fill GLSL's columns of the transpose.
    std::string source = operand(value, kAssign);
    if (to_count < from_count) source = operand(value, kPostfix) + "." + std::string(kComponents, to_count);
    return {target + "(" + source + ")"};
  }
  // From a matrix.
  if (to_count == 1) {
    const std::string first = operand(value, kPostfix) + "[0][0]";
    if (same_scalar) return {first, kPostfix};
    return {target + "(" + first + ")"};
  }
  return constructed(target, value);  // mat3(G): the upper-left corner
}

namespace {

// A literal, possibly negated: its node and the sign.
const Expr* literal_of(const Expr* e, bool& negative) {
  negative = false;
  if (e && e->kind == ExprKind::Unary) {
    const auto* unary = static_cast<const UnaryExpr*>(e);
    if (unary->op != UnaryOp::Minus) return nullptr;
    negative = true;
    e = unary->operand.get();
  }
  if (e && (e->kind == ExprKind::IntLiteral || e->kind == ExprKind::FloatLiteral || e->kind == ExprKind::BoolLiteral))
    return e;
  return nullptr;
}

// The literal `e` (negated if `negative`) as a literal of `scalar`, when GLSL spells that exactly.
std::optional<std::string> fold_literal(const Expr* e, bool negative, ScalarType scalar) {
  std::string text;
  bool is_bool_result = scalar == ScalarType::Bool;
  switch (e->kind) {
    case ExprKind::IntLiteral: {
      const uint64_t value = static_cast<const IntLiteralExpr*>(e)->value;
      if (value == 0) negative = false;  // -0 is an int zero, then +0.0
      switch (scalar) {
        case ScalarType::Half:
        case ScalarType::Float: text = std::to_string(value) + ".0"; break;
        case ScalarType::Int:
          if (value > 0x7FFFFFFFull) return std::nullopt;
          text = std::to_string(value);
          break;
        case ScalarType::Uint:
          if (negative) return std::nullopt;
          text = std::to_string(value) + "u";
          break;
        case ScalarType::Bool: text = value != 0 ? "true" : "false"; break;
      }
      break;
    }
    case ExprKind::FloatLiteral: {
      const auto* literal = static_cast<const FloatLiteralExpr*>(e);
      switch (scalar) {
        case ScalarType::Half:
        case ScalarType::Float: text = float_text(literal->spelling); break;
        case ScalarType::Bool: text = literal->value != 0.0 ? "true" : "false"; break;
        default: return std::nullopt;
      }
      break;
    }
    case ExprKind::BoolLiteral: {
      if (negative) return std::nullopt;
      const bool value = static_cast<const BoolLiteralExpr*>(e)->value;
      switch (scalar) {
        case ScalarType::Half:
        case ScalarType::Float: text = value ? "1.0" : "0.0"; break;
        case ScalarType::Int: text = value ? "1" : "0"; break;
        case ScalarType::Uint: text = value ? "1u" : "0u"; break;
        case ScalarType::Bool: text = value ? "true" : "false"; break;
      }
      break;
    }
    default: return std::nullopt;
  }
  if (negative && !is_bool_result) text = "-" + text;
  return text;
}

}  // namespace

Code StageEmitter::convert_expr(const Expr* e, const Type& to) {
  if (!e) return expr(e);
  bool negative = false;
  if (const Expr* literal = literal_of(e, negative); literal && to.is_numeric()) {
    if (auto folded = fold_literal(literal, negative, to.scalar_type())) {
      const Code scalar =
          half_value({*folded, (*folded)[0] == '-' ? kUnary : kPrimary}, Type::scalar(to.scalar_type()));
      if (to.component_count() == 1) return scalar;
      return convert(scalar, Type::scalar(to.scalar_type()), to, e->loc);
    }
  }
  return convert(expr(e), e->type, to, e->loc);
}

Code StageEmitter::splat_aggregate(const Expr* scalar, const Type& to, Loc loc) {
  if (to.is_numeric()) return convert_expr(scalar, to);
  std::string text = type_name(to, loc) + "(";
  if (to.kind() == TypeKind::Struct && to.struct_decl()) {
    bool first = true;
    for (const FieldDecl& field : to.struct_decl()->fields) {
      text += (first ? "" : ", ") + splat_aggregate(scalar, field.type, loc).text;
      first = false;
    }
  } else if (to.kind() == TypeKind::Array) {
    const std::string element = splat_aggregate(scalar, to.element(), loc).text;
    for (uint32_t i = 0; i < to.array_length(); ++i) text += (i ? ", " : "") + element;
  } else {
    fail(loc, "cannot convert to " + in_quotes(to.name()) + " on this target");
  }
  return {text + ")"};
}

// ---------------------------------------------------------------------------------------------
// Expression properties

bool StageEmitter::is_simple(const Expr* e) {
  if (!e) return false;
  switch (e->kind) {
    case ExprKind::Name:
    case ExprKind::IntLiteral:
    case ExprKind::FloatLiteral:
    case ExprKind::BoolLiteral: return true;
    case ExprKind::Member: return is_simple(static_cast<const MemberExpr*>(e)->object.get());
    case ExprKind::Index: {
      const auto* index = static_cast<const IndexExpr*>(e);
      return is_simple(index->object.get()) && is_simple(index->index.get());
    }
    case ExprKind::Conversion: return is_simple(static_cast<const ConversionExpr*>(e)->operand.get());
    case ExprKind::Unary: {
      const auto* unary = static_cast<const UnaryExpr*>(e);
      return (unary->op == UnaryOp::Minus || unary->op == UnaryOp::Plus) && is_simple(unary->operand.get());
    }
    default: return false;
  }
}

bool StageEmitter::has_side_effects(const Expr* e) {
  bool effects = false;
  hlsl::walk_expressions(e, [&](const Expr& x) {
    switch (x.kind) {
      case ExprKind::Assign: effects = true; break;
      case ExprKind::Unary: {
        const UnaryOp op = static_cast<const UnaryExpr&>(x).op;
        if (op == UnaryOp::PreIncrement || op == UnaryOp::PreDecrement || op == UnaryOp::PostIncrement ||
            op == UnaryOp::PostDecrement)
          effects = true;
        break;
      }
      case ExprKind::Call: {
        const auto& call = static_cast<const CallExpr&>(x);
        if (call.call_kind == CallKind::Function) effects = true;
        const auto id = IntrinsicId(call.intrinsic);
        if ((call.call_kind == CallKind::Intrinsic || call.call_kind == CallKind::Method) &&
            (id == IntrinsicId::Sincos || id == IntrinsicId::Modf || id == IntrinsicId::GetDimensions ||
             id == IntrinsicId::Clip))
          effects = true;
        break;
      }
      default: break;
    }
  });
  return effects;
}

bool StageEmitter::branches(const Expr* e) {
  bool found = false;
  hlsl::walk_expressions(e, [&](const Expr& x) {
    if (x.kind == ExprKind::Conditional)
      found = found || static_cast<const ConditionalExpr&>(x).condition->type.component_count() == 1;
    if (x.kind == ExprKind::Binary) {
      const BinaryOp op = static_cast<const BinaryExpr&>(x).op;
      found = found || op == BinaryOp::LogicalAnd || op == BinaryOp::LogicalOr;
    }
  });
  return found;
}

bool StageEmitter::is_constant(const Expr* e) {
  if (!e) return false;
  switch (e->kind) {
    case ExprKind::IntLiteral:
    case ExprKind::FloatLiteral:
    case ExprKind::BoolLiteral: return true;
    case ExprKind::Name: return const_decls_.count(static_cast<const NameExpr*>(e)->decl) > 0;
    case ExprKind::Unary: {
      const auto* unary = static_cast<const UnaryExpr*>(e);
      if (unary->op == UnaryOp::PreIncrement || unary->op == UnaryOp::PreDecrement ||
          unary->op == UnaryOp::PostIncrement || unary->op == UnaryOp::PostDecrement)
        return false;
      return is_constant(unary->operand.get());
    }
    case ExprKind::Binary: {
      const auto* binary = static_cast<const BinaryExpr*>(e);
      if (binary->op == BinaryOp::Comma || !binary->lhs) return false;
      const Type& type = binary->lhs->type;
      // These become helper calls, which are not constant expressions.
      if (binary->op == BinaryOp::Mod && type.is_floating()) return false;
      if ((binary->op == BinaryOp::Div || binary->op == BinaryOp::Mod) && type.is_integer() &&
          type.scalar_type() == ScalarType::Int)
        return false;
      return is_constant(binary->lhs.get()) && is_constant(binary->rhs.get());
    }
    case ExprKind::Conditional: {
      const auto* c = static_cast<const ConditionalExpr*>(e);
      return is_constant(c->condition.get()) && is_constant(c->then_value.get()) && is_constant(c->else_value.get());
    }
    case ExprKind::Call: {
      const auto* call = static_cast<const CallExpr*>(e);
      if (call->call_kind != CallKind::Constructor) return false;
      for (const ExprPtr& arg : call->args)
        if (!is_constant(arg.get())) return false;
      return true;
    }
    case ExprKind::Member:
      if (is_split_name(static_cast<const MemberExpr*>(e)->object.get(), constant_buffer_members_.split)) return false;
      return is_constant(static_cast<const MemberExpr*>(e)->object.get());
    case ExprKind::Index: {
      const auto* index = static_cast<const IndexExpr*>(e);
      return is_constant(index->object.get()) && is_constant(index->index.get());
    }
    case ExprKind::Cast: return is_constant(static_cast<const CastExpr*>(e)->operand.get());
    case ExprKind::Conversion: return is_constant(static_cast<const ConversionExpr*>(e)->operand.get());
    case ExprKind::InitList:
      for (const ExprPtr& element : static_cast<const InitListExpr*>(e)->elements)
        if (!is_constant(element.get())) return false;
      return true;
    case ExprKind::Assign: return false;
  }
  return false;
}

Code StageEmitter::out_argument(const Expr* arg) {
  if (arg && arg->kind == ExprKind::Conversion) {
    const auto* conversion = static_cast<const ConversionExpr*>(arg);
    const Expr* inner = conversion->operand.get();
    if (inner && !same_glsl(inner->type, conversion->type)) {
      fail(arg->loc, "passing a " + in_quotes(inner->type.name()) + " to an out parameter of type " +
                         in_quotes(conversion->type.name()) +
                         " needs a conversion, which this target does not support; pass a variable of type " +
                         in_quotes(conversion->type.name()));
    }
    return expr(inner);
  }
  return expr(arg);
}

// ---------------------------------------------------------------------------------------------
// Expressions

namespace {

struct BinaryInfo {
  const char* text;
  int prec;
};

BinaryInfo binary_info(BinaryOp op) {
  switch (op) {
    case BinaryOp::Add: return {"+", kAdditive};
    case BinaryOp::Sub: return {"-", kAdditive};
    case BinaryOp::Mul: return {"*", kMultiplicative};
    case BinaryOp::Div: return {"/", kMultiplicative};
    case BinaryOp::Mod: return {"%", kMultiplicative};
    case BinaryOp::Shl: return {"<<", kShift};
    case BinaryOp::Shr: return {">>", kShift};
    case BinaryOp::BitAnd: return {"&", kBitAnd};
    case BinaryOp::BitOr: return {"|", kBitOr};
    case BinaryOp::BitXor: return {"^", kBitXor};
    case BinaryOp::LogicalAnd: return {"&&", kLogicalAnd};
    case BinaryOp::LogicalOr: return {"||", kLogicalOr};
    case BinaryOp::Less: return {"<", kRelational};
    case BinaryOp::Greater: return {">", kRelational};
    case BinaryOp::LessEqual: return {"<=", kRelational};
    case BinaryOp::GreaterEqual: return {">=", kRelational};
    case BinaryOp::Equal: return {"==", kEquality};
    case BinaryOp::NotEqual: return {"!=", kEquality};
    case BinaryOp::Comma: return {",", kComma};
  }
  return {"?", kComma};
}

const char* comparison_function(BinaryOp op) {
  switch (op) {
    case BinaryOp::Less: return "lessThan";
    case BinaryOp::Greater: return "greaterThan";
    case BinaryOp::LessEqual: return "lessThanEqual";
    case BinaryOp::GreaterEqual: return "greaterThanEqual";
    case BinaryOp::Equal: return "equal";
    case BinaryOp::NotEqual: return "notEqual";
    default: return nullptr;
  }
}

// HLSL operators that GLSL's operator of the same spelling computes differently on `type`.
bool needs_lowering(BinaryOp op, const Type& type) {
  if (type.is_matrix() && op == BinaryOp::Mul) return true;    // component-wise in HLSL
  if (op == BinaryOp::Mod && type.is_floating()) return true;  // HLSL truncates, GLSL's mod floors
  if ((op == BinaryOp::Div || op == BinaryOp::Mod) && type.scalar_type() == ScalarType::Int && type.is_integer())
    return true;  // GLSL leaves negative operands undefined
  return false;
}

// An operator GLSL applies component by component to a scalar and a vector or matrix, as HLSL
// applies it to the splatted scalar (v * s, M * s, M + s, i % n).
bool scalar_operand_allowed(BinaryOp op, const Type& type) {
  return !needs_lowering(op, type) || (type.is_matrix() && op == BinaryOp::Mul);
}

// A scalar that sema splatted to a vector or matrix for an operator GLSL applies to a scalar and
// a vector or matrix alike (v * s, M + s).
const Expr* splatted_scalar(const Expr* e) {
  if (!e || e->kind != ExprKind::Conversion) return nullptr;
  const Expr* operand = static_cast<const ConversionExpr*>(e)->operand.get();
  if (!operand || operand->type.component_count() != 1 || e->type.component_count() <= 1) return nullptr;
  if (!operand->type.is_numeric()) return nullptr;
  return operand;
}

// `l op r`, each side parenthesized as the operator's precedence needs. The left operand's
// text becomes the result's, so that a chain of operators does not copy what it has built.
Code infix(Code&& l, const BinaryInfo& info, const Code& r) {
  std::string text = operand(std::move(l), info.prec);
  text += ' ';
  text += info.text;
  text += ' ';
  append_operand(text, r, info.prec + 1);
  return {std::move(text), info.prec};
}

// `function(a, b)`.
Code call2(std::string_view function, const Code& a, const Code& b) {
  std::string text;
  text.reserve(function.size() + a.text.size() + b.text.size() + 8);
  text += function;
  text += '(';
  append_operand(text, a, kAssign);
  text += ", ";
  append_operand(text, b, kAssign);
  text += ')';
  return {std::move(text), kPostfix};
}

}  // namespace

// `l op r` on operands of `type` (both already of that type), with HLSL's meaning.
static Code arithmetic(StageEmitter& emitter, BinaryOp op, const Type& type, Code l, const Code& r, Loc loc) {
  if (type.is_matrix() && op == BinaryOp::Mul) return call2("matrixCompMult", l, r);
  if (type.is_matrix() && op == BinaryOp::Mod) {
    emitter.fail(loc, "'%' on matrices is not supported on this target");
    return l;
  }
  if (needs_lowering(op, type)) {
    const char* helper = op == BinaryOp::Mod ? (type.is_floating() ? "xs_fmod" : "xs_imod") : "xs_idiv";
    const std::string name = emitter.require_helper(helper, {type, type}, loc);
    return call2(name, l, r);
  }
  return infix(std::move(l), binary_info(op), r);
}

Code StageEmitter::expr_untraced(const Expr* e) {
  if (e && half_.rounds_result(*e)) return half_value(expr_unrounded(e), e->type);
  return expr_unrounded(e);
}

Code StageEmitter::expr_unrounded(const Expr* e) {
  if (!e) {
    fail_internal({}, "an expression is missing");
    return {"0"};
  }
  switch (e->kind) {
    case ExprKind::IntLiteral: {
      const auto* literal = static_cast<const IntLiteralExpr*>(e);
      const bool is_unsigned = e->type.scalar_type() == ScalarType::Uint;
      return {std::to_string(literal->value) + (is_unsigned ? "u" : "")};
    }
    case ExprKind::FloatLiteral: return {float_text(static_cast<const FloatLiteralExpr*>(e)->spelling)};
    case ExprKind::BoolLiteral: return {static_cast<const BoolLiteralExpr*>(e)->value ? "true" : "false"};

    case ExprKind::Name: {
      const auto* name = static_cast<const NameExpr*>(e);
      if (e->type.kind() == TypeKind::Buffer) {
        type_name(e->type, e->loc);  // reports that this target has none
        return {"0"};
      }
      if (name->decl && e->type.is_resource() && e->type.kind() != TypeKind::ConstantBuffer) {
        if (flavour_ == Flavour::Gl && e->type.kind() == TypeKind::SamplerState)
          fail(e->loc, "SamplerState " + in_quotes(name->name) +
                           " can only be passed to Sample methods and functions on OpenGL");
        return resource_text(e, {});
      }
      if (auto it = constant_buffer_members_.split.find(name->decl); it != constant_buffer_members_.split.end()) {
        std::string text = type_name(Type::vector(it->second.scalar, it->second.count), e->loc) + "(";
        for (uint32_t i = 0; i < it->second.count; ++i) text += (i ? ", " : "") + names_.split_member(name->name, i);
        return {text + ")"};
      }
      if (flavour_ == Flavour::Gl && e->type.kind() == TypeKind::SamplerState)
        fail(e->loc,
             "SamplerState " + in_quotes(name->name) + " can only be passed to Sample methods and functions on OpenGL");
      const Type& element = e->type.is_resource_array() ? e->type.element() : e->type;
      if (element.kind() == TypeKind::ConstantBuffer) return {constant_buffer_instance(name->name)};
      if (e->type.kind() == TypeKind::Buffer) {
        type_name(e->type, e->loc);  // reports that this target has none
        return {"0"};
      }
      return {name->decl ? names_.variable(name->decl) : names_.of(name->name)};
    }

    case ExprKind::Unary: {
      const auto* unary = static_cast<const UnaryExpr*>(e);
      const Code value = expr(unary->operand.get());
      auto prefix = [&](const char* op) {
        std::string text = operand(value, kUnary);
        if (!text.empty() && text[0] == op[0]) text = "(" + text + ")";  // - -x, not --x
        return Code{op + text, kUnary};
      };
      switch (unary->op) {
        case UnaryOp::Plus: return prefix("+");
        case UnaryOp::Minus: return prefix("-");
        case UnaryOp::BitNot: return prefix("~");
        case UnaryOp::Not:
          if (e->type.component_count() > 1) {
            if (e->type.is_matrix()) fail(e->loc, "'!' on a matrix is not supported on this target");
            return {"not(" + value.text + ")", kPostfix};
          }
          return prefix("!");
        case UnaryOp::PreIncrement:
        case UnaryOp::PreDecrement:
        case UnaryOp::PostIncrement:
        case UnaryOp::PostDecrement: return increment(*unary, value);
      }
      return value;
    }

    case ExprKind::Binary: {
      const auto* binary = static_cast<const BinaryExpr*>(e);
      const BinaryOp op = binary->op;
      if (op == BinaryOp::Comma) {
        Code l = expr(binary->lhs.get());
        const Code r = expr(binary->rhs.get());
        std::string text = operand(std::move(l), kComma);
        text += ", ";
        append_operand(text, r, kAssign);
        return {std::move(text), kComma};
      }
      const Type& type = binary->lhs->type;  // both operands have it after sema
      if (op == BinaryOp::LogicalAnd || op == BinaryOp::LogicalOr) {
        Code l = expr(binary->lhs.get());
        const Code r = expr(binary->rhs.get());
        if (type.component_count() > 1) {
          if (type.is_matrix()) fail(e->loc, "logical operators on matrices are not supported on this target");
          // Component-wise, both sides evaluated, as HLSL does for vectors.
          const std::string n = std::to_string(type.cols());
          return {"bvec" + n + "(uvec" + n + "(" + l.text + ") " + (op == BinaryOp::LogicalAnd ? "&" : "|") + " uvec" +
                      n + "(" + r.text + "))",
                  kPostfix};
        }
        return infix(std::move(l), binary_info(op), r);
      }
      if (const char* function = comparison_function(op)) {
        Code l = expr(binary->lhs.get());
        const Code r = expr(binary->rhs.get());
        if (type.is_matrix()) {
          fail(e->loc, "comparing matrices is not supported on this target");
          return l;
        }
        if (type.component_count() > 1) return call2(function, l, r);
        return infix(std::move(l), binary_info(op), r);
      }
      // Arithmetic and bitwise: GLSL takes a scalar on either side of a vector or matrix.
      const Expr* lhs = binary->lhs.get();
      const Expr* rhs = binary->rhs.get();
      Code l, r;
      if (scalar_operand_allowed(op, type) && splatted_scalar(lhs) && !splatted_scalar(rhs)) {
        l = convert_expr(splatted_scalar(lhs), Type::scalar(type.scalar_type()));
        r = expr(rhs);
        return infix(std::move(l), binary_info(op), r);
      }
      if (scalar_operand_allowed(op, type) && splatted_scalar(rhs) && !splatted_scalar(lhs)) {
        l = expr(lhs);
        r = convert_expr(splatted_scalar(rhs), Type::scalar(type.scalar_type()));
        return infix(std::move(l), binary_info(op), r);
      }
      l = expr(lhs);
      r = expr(rhs);
      return arithmetic(*this, op, type, std::move(l), r, e->loc);
    }

    case ExprKind::Assign: {
      const auto* assign = static_cast<const AssignExpr*>(e);
      const Expr* target = assign->target.get();
      if (target && target->kind == ExprKind::Member) {
        const auto* member = static_cast<const MemberExpr*>(target);
        if (member->object && member->object->type.is_matrix() && member->swizzle.size() > 1) {
          fail(target->loc, "assigning to several matrix components at once is not supported on this target");
        }
      }
      Code t = expr(target);
      const std::optional<BinaryOp> op = compound_operator(assign->op);
      if (!op) {
        std::string text = operand(std::move(t), kUnary);
        text += " = ";
        append_operand(text, expr(assign->value.get()), kAssign);
        return {std::move(text), kAssign};
      }
      const Type& operation = assign->value->type;  // the operator's operand type (sema)
      const Type& target_type = target->type;
      const Expr* scalar = splatted_scalar(assign->value.get());
      // With half emulation a half result is rounded, so `h += x` is written out as h = xs_half(h + x).
      if (same_glsl(operation, target_type) && !half_.rounds(operation) && !half_.rounds_compound_target(target_type) &&
          (!needs_lowering(*op, operation) || (scalar && scalar_operand_allowed(*op, operation)))) {
        const BinaryInfo info = binary_info(*op);
        const Code v = scalar ? convert_expr(scalar, Type::scalar(operation.scalar_type())) : expr(assign->value.get());
        std::string text = operand(std::move(t), kUnary);
        text += ' ';
        text += info.text;
        text += "= ";
        append_operand(text, v, kAssign);
        return {std::move(text), kAssign};
      }
      // t = T(t' op v): the target is read and written, so it is written out twice.
      if (has_side_effects(target)) {
        fail(e->loc, std::string("compound assignment '") + binary_info(*op).text +
                         "=' to an expression with side effects is not supported on this target; "
                         "compute the target once into a variable");
        return t;
      }
      Code current = convert(t, target_type, operation, e->loc);
      const Code value = expr(assign->value.get());
      Code result = half_value(arithmetic(*this, *op, operation, std::move(current), value, e->loc), operation);
      std::string text = operand(std::move(t), kUnary);
      text += " = ";
      append_operand(text, convert(std::move(result), operation, target_type, e->loc), kAssign);
      return {std::move(text), kAssign};
    }

    case ExprKind::Conditional: {
      const auto* c = static_cast<const ConditionalExpr*>(e);
      const Code condition = expr(c->condition.get());
      const Code then_value = expr(c->then_value.get());
      const Code else_value = expr(c->else_value.get());
      const Type& condition_type = c->condition->type;
      if (condition_type.component_count() > 1) {
        if (condition_type.is_matrix() || e->type.is_matrix()) {
          fail(e->loc, "'?:' on matrices is not supported on this target");
          return then_value;
        }
        // Component-wise selection; HLSL evaluates both sides too.
        std::string text = "mix(";
        append_operand(text, else_value, kAssign);
        text += ", ";
        append_operand(text, then_value, kAssign);
        text += ", ";
        append_operand(text, condition, kAssign);
        text += ')';
        return {std::move(text), kPostfix};
      }
      std::string text;
      text.reserve(condition.text.size() + then_value.text.size() + else_value.text.size() + 10);
      append_operand(text, condition, kLogicalOr);
      text += " ? ";
      append_operand(text, then_value, kAssign);
      text += " : ";
      append_operand(text, else_value, kAssign);
      return {std::move(text), kConditional};
    }

    case ExprKind::Call: {
      const auto* call = static_cast<const CallExpr*>(e);
      switch (call->call_kind) {
        case CallKind::Constructor: {
          const Type& type = e->type;
          if (call->args.size() == 1 && call->args[0] && same_glsl(call->args[0]->type, type))
            return expr(call->args[0].get());
          std::string text = type_name(type, e->loc) + "(";
          for (size_t i = 0; i < call->args.size(); ++i) {
            const Expr* arg = call->args[i].get();
            if (type.is_matrix() && arg && arg->type.is_matrix())
              fail(arg->loc, "a matrix constructor with matrix arguments is not supported on this target");
            if (i) text += ", ";
            append_operand(text, expr(arg), kAssign);
          }
          text += ')';
          return {std::move(text), kPostfix};
        }
        case CallKind::Function: {
          const FunctionDecl* function = call->function;
          if (!function) {
            fail_internal(e->loc, "unresolved call to " + in_quotes(call->callee));
            return {"0"};
          }
          std::string text = function_name(function) + "(";
          bool first = true;
          for (size_t i = 0; i < function->params.size(); ++i) {
            const ParamDecl* param = function->params[i].get();
            if (!param) continue;
            if (!resource_paths(param->type).empty() && i < call->args.size()) {
              // One argument per resource, as the callee's parameters are flattened.
              for (const lower::FlattenedParameter& flat : lower::flattened_parameters(*param, names_, flavour_)) {
                text += (first ? "" : ", ") + resource_text(call->args[i].get(), flat.path).text;
                first = false;
              }
              continue;
            }
            if (flavour_ == Flavour::Gl && param->type.kind() == TypeKind::SamplerState) continue;
            Code arg;
            if (i < call->args.size()) {
              arg = param->direction == ParamDirection::In ? expr(call->args[i].get())
                                                           : out_argument(call->args[i].get());
            } else if (param->default_value) {
              arg = expr(param->default_value.get());
            } else {
              fail_internal(e->loc,
                            "argument " + std::to_string(i + 1) + " of " + in_quotes(call->callee) + " is missing");
            }
            if (!first) text += ", ";
            append_operand(text, arg, kAssign);
            first = false;
          }
          if (in_traced_copy_) {  // the call path (emit_trace.cpp)
            if (!first) text += ", ";
            text += trace_call_path(function->name, e->loc);
          }
          text += ')';
          return {std::move(text), kPostfix};
        }
        case CallKind::Intrinsic:
        case CallKind::Method: return intrinsic_call(*call);
        case CallKind::Printf: {
          // Vulkan's debug printf, which the validation layer prints; OpenGL has none, and the
          // statement is left out there (emit_statements.cpp).
          if (flavour_ == Flavour::Gl) {
            fail(e->loc, "printf has no OpenGL form inside an expression; call it as a statement of its own");
            return {"0"};
          }
          require_extension("GL_EXT_debug_printf");
          std::string text = "debugPrintfEXT(" + call->format;
          for (const ExprPtr& arg : call->args) append_operand(text += ", ", expr(arg.get()), kAssign);
          return {text + ")", kPostfix};
        }
        case CallKind::Unresolved: fail_internal(e->loc, "unresolved call to " + in_quotes(call->callee)); return {"0"};
      }
      return {"0"};
    }

    case ExprKind::Member: {
      const auto* member = static_cast<const MemberExpr*>(e);
      if (e->type.is_resource()) return resource_text(e, {});  // tex.smpl of a struct of resources
      const Expr* object = member->object.get();
      const Type& type = object->type;
      if (type.kind() == TypeKind::Struct || type.kind() == TypeKind::ConstantBuffer) {
        // ConstantBuffer<S> cb: cb.field is a member of the block whose instance is cb.
        const StructDecl* decl = type.kind() == TypeKind::Struct ? type.struct_decl() : type.element().struct_decl();
        const std::string& field = decl && member->field_index >= 0 && size_t(member->field_index) < decl->fields.size()
                                       ? decl->fields[size_t(member->field_index)].name
                                       : member->member;
        std::string text = operand(expr(object), kPostfix);
        text += '.';
        text += names_.of(field);
        return {std::move(text), kPostfix};
      }
      const hlsl::Swizzle& swizzle = member->swizzle;
      const uint32_t count = uint32_t(swizzle.size());
      if (type.is_matrix()) {
        if (count > 1 && has_side_effects(object))
          fail(e->loc, "a matrix swizzle of an expression with side effects is not supported on this target");
        const std::string base = operand(expr(object), kPostfix);
        std::string parts;
        for (uint32_t i = 0; i < count; ++i)
          parts += (i ? ", " : "") + base + "[" + std::to_string(swizzle[i] / 4) + "][" +
                   std::to_string(swizzle[i] % 4) + "]";
        if (count == 1) return {parts, kPostfix};
        return {type_name(e->type, e->loc) + "(" + parts + ")", kPostfix};
      }
      if (type.component_count() == 1) {  // f.xxx on a scalar (or float1)
        const Code value = expr(object);
        if (count == 1) return value;
        return convert(value, Type::scalar(type.scalar_type()), e->type, e->loc);
      }
      if (is_split_name(object, constant_buffer_members_.split)) {
        const std::string& base = static_cast<const NameExpr*>(object)->name;
        std::string parts;
        for (uint32_t i = 0; i < count; ++i) parts += (i ? ", " : "") + names_.split_member(base, swizzle[i]);
        if (count == 1) return {parts};
        return {type_name(e->type, e->loc) + "(" + parts + ")", kPostfix};
      }
      std::string text = operand(expr(object), kPostfix);
      text += '.';
      for (uint8_t component : swizzle) text += kComponents[component & 3];
      return {std::move(text), kPostfix};
    }

    case ExprKind::Index: {
      const auto* index = static_cast<const IndexExpr*>(e);
      if (index->object->type.is_texture()) return texture_index(*index);
      if (index->object->type.kind() == TypeKind::Buffer && is_read_only_buffer(index->object->type.buffer_kind()))
        return buffer_index(*index);
      Code object = expr(index->object.get());
      if (index->object->type.is_vector() && index->object->type.cols() == 1) return object;  // float1[0]
      std::string text = operand(std::move(object), kPostfix);
      text += '[';
      text += expr(index->index.get()).text;
      text += ']';
      return {std::move(text), kPostfix};
    }

    case ExprKind::Cast: {
      const auto* cast = static_cast<const CastExpr*>(e);
      const Expr* operand_expr = cast->operand.get();
      if (cast->target.is_void()) return expr(operand_expr);
      if ((cast->target.kind() == TypeKind::Struct || cast->target.kind() == TypeKind::Array) && operand_expr &&
          operand_expr->type.component_count() == 1 && !(operand_expr->type == cast->target))
        return splat_aggregate(operand_expr, cast->target, e->loc);  // (S)0
      return convert_expr(operand_expr, cast->target);
    }

    case ExprKind::InitList: {
      const auto* list = static_cast<const InitListExpr*>(e);
      const Type& type = e->type;
      if (type.is_numeric() && list->elements.size() == 1 && list->elements[0] &&
          same_glsl(list->elements[0]->type, type))
        return expr(list->elements[0].get());
      std::string text = type_name(type, e->loc) + "(";
      for (size_t i = 0; i < list->elements.size(); ++i) {
        const Expr* element = list->elements[i].get();
        if (type.is_matrix() && element && element->type.is_matrix())
          fail(element->loc, "a matrix initializer with matrix elements is not supported on this target");
        text += (i ? ", " : "") + operand(expr(element), kAssign);
      }
      return {text + ")", kPostfix};
    }

    case ExprKind::Conversion: {
      const auto* conversion = static_cast<const ConversionExpr*>(e);
      return convert_expr(conversion->operand.get(), e->type);
    }
  }
  return {"0"};
}

}  // namespace xshade::glsl::detail

namespace xshade::glsl::lower {

// Renaming's overload key is the printer's type spelling, without its diagnostics.
std::string type_key(const hlsl::Type& type, Flavour flavour) { return detail::glsl_type(type, flavour, nullptr); }

}  // namespace xshade::glsl::lower
