#include "glsl/lower/half_emulation.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace xshade::glsl::lower {

using hlsl::ExprKind;
using hlsl::ScalarType;

namespace {

bool is_half(const hlsl::Type& type) { return type.is_floating() && type.scalar_type() == ScalarType::Half; }

bool numeric(const hlsl::Type& type) {
  return type.kind() == hlsl::TypeKind::Scalar || type.kind() == hlsl::TypeKind::Vector;
}

}  // namespace

bool same_glsl_scalar_or_vector(const hlsl::Type& a, const hlsl::Type& b) {
  const auto count = [](const hlsl::Type& type) { return type.kind() == hlsl::TypeKind::Vector ? type.cols() : 1u; };
  const auto glsl_scalar = [](ScalarType scalar) { return scalar == ScalarType::Half ? ScalarType::Float : scalar; };
  return glsl_scalar(a.scalar_type()) == glsl_scalar(b.scalar_type()) && count(a) == count(b);
}

double nearest_half(double value) {
  if (!std::isfinite(value) || value == 0.0) return value;
  const double magnitude = std::fabs(value);
  // 65504 is the largest half; halfway to the next step (65536) rounds to even, which is infinity.
  if (magnitude >= 65520.0) return std::copysign(HUGE_VAL, value);
  int exponent = 0;
  std::frexp(magnitude, &exponent);  // magnitude in [2^(exponent-1), 2^exponent)
  // 11 significant bits for normal halves; below 2^-14 the subnormals' fixed step of 2^-24.
  const double step = exponent - 1 < -14 ? std::ldexp(1.0, -24) : std::ldexp(1.0, exponent - 1 - 10);
  return std::copysign(std::nearbyint(magnitude / step) * step, value);
}

bool HalfEmulation::rounds(const hlsl::Type& type) const { return enabled_ && is_half(type) && !type.is_matrix(); }

bool HalfEmulation::rounds_result(const hlsl::Expr& e) const {
  if (!rounds(e.type)) return false;
  switch (e.kind) {
    case ExprKind::FloatLiteral:
    case ExprKind::Cast:
    case ExprKind::Conversion: return true;
    case ExprKind::Unary: {
      const hlsl::UnaryOp op = static_cast<const hlsl::UnaryExpr&>(e).op;
      return op == hlsl::UnaryOp::Plus || op == hlsl::UnaryOp::Minus || op == hlsl::UnaryOp::BitNot ||
             op == hlsl::UnaryOp::Not;
    }
    case ExprKind::Binary: return static_cast<const hlsl::BinaryExpr&>(e).op != hlsl::BinaryOp::Comma;
    case ExprKind::Call: {
      const auto& call = static_cast<const hlsl::CallExpr&>(e);
      if (call.call_kind == hlsl::CallKind::Constructor) {
        // half3(v) of a float3 or half3 v: the argument itself, GLSL's type being the same (half
        // is float there).
        const hlsl::Expr* arg = call.args.size() == 1 ? call.args[0].get() : nullptr;
        return !(arg && (arg->type.is_error() ||
                         (numeric(arg->type) && numeric(e.type) && same_glsl_scalar_or_vector(arg->type, e.type))));
      }
      return call.call_kind == hlsl::CallKind::Function || call.call_kind == hlsl::CallKind::Intrinsic ||
             call.call_kind == hlsl::CallKind::Method;
    }
    default: return false;
  }
}

bool HalfEmulation::rounds_increment(const hlsl::UnaryExpr& e) const {
  const bool increments = e.op == hlsl::UnaryOp::PreIncrement || e.op == hlsl::UnaryOp::PreDecrement ||
                          e.op == hlsl::UnaryOp::PostIncrement || e.op == hlsl::UnaryOp::PostDecrement;
  return increments && e.operand && rounds(e.operand->type);
}

bool HalfEmulation::rounds_conversion(const hlsl::Type& from, const hlsl::Type& to) const {
  return rounds(to) && !is_half(from);
}

std::optional<float> HalfEmulation::rounded_literal(std::string_view text) {
  if (text.empty() || text.find_first_not_of("0123456789.eE+-") != std::string_view::npos) return std::nullopt;
  const std::string spelling(text);
  char* end = nullptr;
  const double value = std::strtod(spelling.c_str(), &end);
  if (end != spelling.c_str() + spelling.size()) return std::nullopt;
  const auto rounded = static_cast<float>(nearest_half(value));
  if (!std::isfinite(rounded)) return std::nullopt;
  return rounded;
}

}  // namespace xshade::glsl::lower
