// HLSL's conversion rules, the shapes of component-wise operations, and semantics.
#include <algorithm>
#include <cctype>

#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl::sema_detail {

namespace {

Conversion invalid() { return {}; }

// The rank of a change of scalar type alone.
int scalar_change_rank(ScalarType from, ScalarType to) {
  if (from == to) return kRankExact;
  if ((from == ScalarType::Half && to == ScalarType::Float) || (from == ScalarType::Bool && to == ScalarType::Int)) {
    return kRankPromotion;
  }
  return kRankTypeChange;
}

Conversion valid(int shape_rank, int scalar_rank, bool truncation = false) {
  Conversion conversion;
  conversion.valid = true;
  conversion.truncation = truncation;
  conversion.rank = shape_rank + scalar_rank;
  return conversion;
}

// Texel types of one class (float and half; int; uint; bool) read the same kind of GLSL sampler,
// so HLSL's lenient passing of Texture2D<float> as Texture2D is kept within a class.
int texel_class(ScalarType scalar) {
  switch (scalar) {
    case ScalarType::Half:
    case ScalarType::Float: return 0;
    case ScalarType::Int: return 1;
    case ScalarType::Uint: return 2;
    case ScalarType::Bool: return 3;
  }
  return 0;
}

}  // namespace

Conversion classify_implicit(const Type& from, const Type& to) {
  if (from.is_error() || to.is_error()) return valid(kRankExact, kRankExact);
  if (from == to) return valid(kRankExact, kRankExact);
  if (!from.is_numeric() || !to.is_numeric()) {
    if (from.is_texture() && to.is_texture() && from.texture_shape() == to.texture_shape() &&
        texel_class(from.scalar_type()) == texel_class(to.scalar_type()))
      return valid(kRankExact, kRankTypeChange);
    return invalid();
  }
  const int type_change = scalar_change_rank(from.scalar_type(), to.scalar_type());
  const uint32_t from_count = from.component_count();
  switch (from.kind()) {
    case TypeKind::Scalar: return valid(to.is_scalar() ? kRankExact : kRankSplat, type_change);
    case TypeKind::Vector:
      if (to.is_scalar()) {
        if (from.cols() == 1) return valid(kRankSplat, type_change);  // float1 -> float
        return valid(kRankTruncation, type_change, true);
      }
      if (to.is_vector()) {
        if (to.cols() == from.cols()) return valid(kRankExact, type_change);
        if (to.cols() < from.cols()) return valid(kRankTruncation, type_change, true);
        if (from.cols() == 1) return valid(kRankSplat, type_change);
        return invalid();
      }
      // to a matrix: only a one-component vector splats
      if (from_count == 1) return valid(kRankSplat, type_change);
      return invalid();
    case TypeKind::Matrix:
      if (to.is_scalar()) {
        if (from_count == 1) return valid(kRankSplat, type_change);
        return valid(kRankTruncation, type_change, true);
      }
      if (to.is_matrix()) {
        if (to.rows() == from.rows() && to.cols() == from.cols()) return valid(kRankExact, type_change);
        if (to.rows() <= from.rows() && to.cols() <= from.cols()) return valid(kRankTruncation, type_change, true);
        if (from_count == 1) return valid(kRankSplat, type_change);
        return invalid();
      }
      if (from_count == 1) return valid(kRankSplat, type_change);  // float1x1 -> float3
      return invalid();
    default: return invalid();
  }
}

namespace {

// The element kinds DXC scores with: literals are kinds of their own; `half` (and min16float) is
// DXC's 32-bit float of partial precision.
enum class Element : uint8_t { Bool, LiteralInt, Int, Uint, LiteralFloat, Half, Float };

Element element_of(ScalarType scalar, bool literal) {
  switch (scalar) {
    case ScalarType::Bool: return Element::Bool;
    case ScalarType::Int: return literal ? Element::LiteralInt : Element::Int;
    case ScalarType::Uint: return literal ? Element::LiteralInt : Element::Uint;
    case ScalarType::Half: return Element::Half;
    case ScalarType::Float: return literal ? Element::LiteralFloat : Element::Float;
  }
  return Element::Float;
}

bool is_float_element(Element e) { return e == Element::LiteralFloat || e == Element::Half || e == Element::Float; }

// The kind both sides meet in (DXC's CombineBasicTypes): a float if either is one, unsigned
// over signed; partial precision stays only beside a literal or a bool; a literal or bool
// result becomes a 32-bit type.
Element combine(Element a, Element b) {
  if (a == b) return a == Element::LiteralInt ? Element::Int : a == Element::LiteralFloat ? Element::Float : a;
  const bool a_float = is_float_element(a), b_float = is_float_element(b);
  if (a_float || b_float) {
    if (a_float && b_float) {
      if (a == Element::Float || b == Element::Float) return Element::Float;
      return Element::Half;  // half with a literal float
    }
    const Element f = a_float ? a : b;
    const Element other = a_float ? b : a;
    if (f == Element::Half)
      return other == Element::Bool || other == Element::LiteralInt ? Element::Half : Element::Float;
    return Element::Float;
  }
  if (a == Element::Uint || b == Element::Uint) return Element::Uint;
  return Element::Int;  // int, literal int and bool
}

// `narrow` widens to `wide` without loss (DXC's IsPromotion): half to float.
bool is_promotion(Element wide, Element narrow) { return wide == Element::Float && narrow == Element::Half; }

// A change of kind that is no promotion (DXC's IsCast): everything but a literal into its
// family and int <-> uint of one width, which is an int cast of its own.
bool is_cast(Element a, Element b) {
  if (a == b) return false;
  auto int_like = [](Element e) { return e == Element::Int || e == Element::Uint || e == Element::LiteralInt; };
  if (int_like(a) && int_like(b)) return false;
  if ((a == Element::LiteralFloat && is_float_element(b)) || (b == Element::LiteralFloat && is_float_element(a)))
    return false;
  return true;
}

bool is_int_cast(Element a, Element b) {
  return a != b && (a == Element::Int || a == Element::Uint) && (b == Element::Int || b == Element::Uint);
}

}  // namespace

// DXC scores a conversion (ScoreCast in its SemaHLSL.cpp) as a sum of flags, each in a field of
// 7 bits so that the sums of a call compare field by field, the highest first: truncation, then
// a cast on the argument's side (int -> float), a cast on the parameter's side (float -> int,
// float -> half, anything -> bool), an int cast on either side (int <-> uint), a promotion
// (half -> float), and last a splat. Literals fit their family exactly.
std::optional<uint64_t> overload_cost(const Type& from, bool literal, const Type& to) {
  const Conversion conversion = classify_implicit(from, to);
  if (!conversion.valid) return std::nullopt;
  if (from == to || !from.is_numeric() || !to.is_numeric()) return conversion.rank == 0 ? 0 : uint64_t(1) << 37;
  enum Flag { kSplat, kParamPromotion, kArgPromotion, kParamIntCast, kArgIntCast, kParamCast, kArgCast, kTruncation };
  auto flag = [](Flag f) { return uint64_t(1) << (2 + 7 * int(f)); };
  uint64_t cost = 0;
  const uint32_t from_count = from.component_count(), to_count = to.component_count();
  if (from_count < to_count) cost += flag(kSplat);
  if (to_count < from_count) cost += flag(kTruncation);
  const Element param = element_of(to.scalar_type(), false);
  const Element arg = element_of(from.scalar_type(), literal && from.is_scalar());
  const Element met = combine(param, arg);
  if (is_promotion(param, met))
    cost += flag(kParamPromotion);
  else if (is_cast(param, met))
    cost += flag(kParamCast);
  else if (is_int_cast(param, met))
    cost += flag(kParamIntCast);
  if (is_promotion(met, arg))
    cost += flag(kArgPromotion);
  else if (is_cast(met, arg))
    cost += flag(kArgCast);
  else if (is_int_cast(met, arg))
    cost += flag(kArgIntCast);
  return cost;
}

bool explicit_cast_allowed(const Type& from, const Type& to, bool literal_scalar, TypeFacts& facts) {
  if (from.is_error() || to.is_error()) return true;
  if (to.is_void()) return true;
  if (from == to) return true;
  if (from.is_numeric() && to.is_numeric()) {
    const uint32_t from_count = from.component_count();
    const uint32_t to_count = to.component_count();
    if (from_count == 1) return true;  // splat
    if (from.is_vector() && to.is_vector()) return to.cols() <= from.cols();
    if (from.is_matrix() && to.is_matrix()) return to.rows() <= from.rows() && to.cols() <= from.cols();
    // vector <-> matrix and to scalar: reshape within the components available
    return to_count <= from_count;
  }
  if (to.kind() == TypeKind::Struct && from.is_scalar() && literal_scalar) {
    // (S)0: every field of S must be numeric (possibly in nested structs and arrays)
    return facts.component_count(to).has_value();
  }
  return false;
}

std::string truncation_message(const Type& from, const Type& to) {
  return std::string("implicit truncation of ") + (from.is_matrix() ? "matrix" : "vector") + " type from " +
         in_quotes(from.name()) + " to " + in_quotes(to.name());
}

std::optional<Type> combine_shapes(const Type& a, const Type& b, ScalarType scalar) {
  if (!a.is_numeric() || !b.is_numeric()) return std::nullopt;
  // A scalar, or a one-component vector, takes the other operand's shape.
  auto scalar_like = [](const Type& t) { return t.is_scalar() || (t.is_vector() && t.cols() == 1); };
  if (a.is_scalar() || (scalar_like(a) && !b.is_scalar())) return Type::with_scalar(b, scalar);
  if (scalar_like(b)) return Type::with_scalar(a, scalar);
  if (a.is_vector() && b.is_vector()) return Type::vector(scalar, std::min(a.cols(), b.cols()));
  if (a.is_matrix() && b.is_matrix()) {
    return Type::matrix(scalar, std::min(a.rows(), b.rows()), std::min(a.cols(), b.cols()));
  }
  // A 1x1 matrix behaves like a scalar too.
  if (a.is_matrix() && a.component_count() == 1) return Type::with_scalar(b, scalar);
  if (b.is_matrix() && b.component_count() == 1) return Type::with_scalar(a, scalar);
  return std::nullopt;
}

bool is_literal(const Expr* expr) {
  for (int i = 0; expr && i < 64; ++i) {
    switch (expr->kind) {
      case ExprKind::IntLiteral:
      case ExprKind::FloatLiteral:
      case ExprKind::BoolLiteral: return true;
      case ExprKind::Unary: {
        const auto* unary = static_cast<const UnaryExpr*>(expr);
        if (unary->op != UnaryOp::Minus && unary->op != UnaryOp::Plus) return false;
        expr = unary->operand.get();
        break;
      }
      default: return false;
    }
  }
  return false;
}

bool is_weak_float_literal(const Expr* expr) {
  for (int i = 0; expr && i < 64; ++i) {
    if (expr->kind == ExprKind::FloatLiteral) return !static_cast<const FloatLiteralExpr*>(expr)->half_suffix;
    if (expr->kind != ExprKind::Unary) return false;
    const auto* unary = static_cast<const UnaryExpr*>(expr);
    if (unary->op != UnaryOp::Minus && unary->op != UnaryOp::Plus) return false;
    expr = unary->operand.get();
  }
  return false;
}

std::optional<uint64_t> TypeFacts::component_count(const Type& type, int depth) {
  if (depth > kMaxNesting) return std::nullopt;
  constexpr uint64_t kLimit = uint64_t(1) << 32;  // beyond any real shader; keeps sums exact
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector:
    case TypeKind::Matrix: return type.component_count();
    case TypeKind::Array: {
      const std::optional<uint64_t> element = component_count(type.element(), depth + 1);
      if (!element || *element * type.array_length() > kLimit) return std::nullopt;
      return *element * type.array_length();
    }
    case TypeKind::Struct: {
      const StructDecl* decl = type.struct_decl();
      if (!decl) return std::nullopt;
      if (auto it = counts_.find(decl); it != counts_.end()) return it->second;
      std::optional<uint64_t> total = 0;
      for (const FieldDecl& field : decl->fields) {
        const std::optional<uint64_t> count = component_count(field.type, depth + 1);
        if (!count || *total + *count > kLimit) {
          total = std::nullopt;
          break;
        }
        *total += *count;
      }
      counts_[decl] = total;
      return total;
    }
    default: return std::nullopt;
  }
}

bool TypeFacts::contains_resource(const Type& type, int depth) {
  if (depth > kMaxNesting) return false;
  if (type.is_resource()) return true;
  if (type.kind() == TypeKind::Array) return contains_resource(type.element(), depth + 1);
  if (type.kind() != TypeKind::Struct || !type.struct_decl()) return false;
  const StructDecl* decl = type.struct_decl();
  if (auto it = resources_.find(decl); it != resources_.end()) return it->second;
  bool found = false;
  for (const FieldDecl& field : decl->fields) {
    if (contains_resource(field.type, depth + 1)) {
      found = true;
      break;
    }
  }
  resources_[decl] = found;
  return found;
}

}  // namespace xshade::hlsl::sema_detail
