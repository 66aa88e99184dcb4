// Lowering: half emulation (EmitOptions::half_emulation). half, min16float and fixed compute in
// fp32 on these drivers; with emulation each half value is rounded to fp16 where it is made, so
// that a shader's fp16 hazards show as they would on hardware with a half type. This decides
// which values are rounded; the printer writes the rounding (xs_half, or a rounded literal).
#pragma once

#include <optional>
#include <string_view>

#include "hlsl_like/ast.h"

namespace xshade::glsl::lower {

// The fp16 value nearest `value` (ties to even), infinite past fp16's range: what a cast to
// _Float16 gives, written out because not every compiler has that type (clang 14 on x86 lacks it).
double nearest_half(double value);

// Two scalar or vector types GLSL spells the same: half is float there, and float1 is float. Both
// must be scalars or vectors (StageEmitter::same_glsl asks this of those, half emulation of a
// constructor's argument).
bool same_glsl_scalar_or_vector(const hlsl::Type& a, const hlsl::Type& b);

class HalfEmulation {
 public:
  explicit HalfEmulation(bool enabled) : enabled_(enabled) {}

  // A value of this type is rounded: a half scalar or vector, when emulating. Half matrices are
  // not (GLSL's matrix operations have no per-result hook; their columns are rounded as they are
  // built from rounded vectors).
  bool rounds(const hlsl::Type& type) const;
  // The value `e` computes is a new half value, rounded where it is made: a float literal, an
  // arithmetic operator's result (not `,`, which passes its right side on, nor ++ and --, whose
  // new value is rounded as it is written: rounds_increment), a call's result (not a constructor
  // of one argument of its own type, which passes it on), a cast or an implicit conversion.
  // Names, members, indices and assignments pass on a value rounded already.
  bool rounds_result(const hlsl::Expr& e) const;
  // ++ or -- on a half value: the value written back is t ± 1 rounded to fp16 (2048 + 1 stays
  // 2048), so the printer writes `t = xs_half(t + 1.0)` rather than GLSL's own ++.
  bool rounds_increment(const hlsl::UnaryExpr& e) const;
  // A compound assignment to a half target: the result is stored as half, rounded, whatever the
  // type of the operation (`h += f` with a float f adds in float and rounds as it stores).
  bool rounds_compound_target(const hlsl::Type& target) const { return rounds(target); }
  // A conversion from `from` to `to` makes a half value: float -> half is where a value first
  // becomes half, the rounding the conversion means.
  bool rounds_conversion(const hlsl::Type& from, const hlsl::Type& to) const;

  // A scalar literal's fp16 value, so that it stays a GLSL constant expression (a static const
  // may only be initialised with one): 0.333251953 for "0.33333". None when the text is not a
  // plain number, or when fp16 has no finite value for it (then xs_half gives infinity).
  static std::optional<float> rounded_literal(std::string_view text);

 private:
  bool enabled_;
};

}  // namespace xshade::glsl::lower
