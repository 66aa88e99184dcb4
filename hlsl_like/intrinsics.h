// HLSL's intrinsic functions and texture methods: one table that semantic analysis resolves
// calls against and that the GLSL emitter maps to GLSL.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace xshade::hlsl {

#define XSHADE_INTRINSICS(X)                                                                     \
  X(Abs, "abs") X(Acos, "acos") X(All, "all") X(Any, "any") X(Asfloat, "asfloat")               \
  X(Asin, "asin") X(Asint, "asint") X(Asuint, "asuint") X(Atan, "atan") X(Atan2, "atan2")        \
  X(Ceil, "ceil") X(Clamp, "clamp") X(Clip, "clip") X(Cos, "cos") X(Cosh, "cosh")                \
  X(Countbits, "countbits") X(Cross, "cross") X(Ddx, "ddx") X(Ddy, "ddy")                        \
  X(Degrees, "degrees") X(Determinant, "determinant") X(Distance, "distance") X(Dot, "dot")      \
  X(Exp, "exp") X(Exp2, "exp2") X(F16tof32, "f16tof32") X(F32tof16, "f32tof16")                  \
  X(Faceforward, "faceforward") X(Floor, "floor") X(Fma, "fma") X(Fmod, "fmod") X(Frac, "frac")  \
  X(Fwidth, "fwidth") X(Isfinite, "isfinite") X(Isinf, "isinf") X(Isnan, "isnan")               \
  X(Ldexp, "ldexp") X(Length, "length") X(Lerp, "lerp") X(Log, "log") X(Log10, "log10")          \
  X(Log2, "log2") X(Mad, "mad") X(Max, "max") X(Min, "min") X(Modf, "modf") X(Mul, "mul")        \
  X(Normalize, "normalize") X(Pow, "pow") X(Radians, "radians") X(Rcp, "rcp")                    \
  X(Reflect, "reflect") X(Refract, "refract") X(Reversebits, "reversebits") X(Round, "round")    \
  X(Rsqrt, "rsqrt") X(Saturate, "saturate") X(Sign, "sign") X(Sin, "sin") X(Sincos, "sincos")    \
  X(Sinh, "sinh") X(Smoothstep, "smoothstep") X(Sqrt, "sqrt") X(Step, "step") X(Tan, "tan")      \
  X(Tanh, "tanh") X(Tex2D, "tex2D") X(Tex2Dbias, "tex2Dbias") X(Tex2Dgrad, "tex2Dgrad")          \
  X(Tex2Dlod, "tex2Dlod") X(Transpose, "transpose") X(Trunc, "trunc")                            \
  /* methods of Texture2D */                                                                     \
  X(Sample, "Sample") X(SampleBias, "SampleBias") X(SampleGrad, "SampleGrad")                    \
  X(SampleLevel, "SampleLevel") X(Load, "Load") X(GetDimensions, "GetDimensions")

enum class IntrinsicId : uint16_t {
  None = 0,
#define XSHADE_INTRINSIC_ENUM(id, name) id,
  XSHADE_INTRINSICS(XSHADE_INTRINSIC_ENUM)
#undef XSHADE_INTRINSIC_ENUM
};

std::string_view intrinsic_name(IntrinsicId id);
// A free function's intrinsic by name (not the Texture2D methods).
std::optional<IntrinsicId> find_intrinsic(std::string_view name);
// A Texture2D method by name.
std::optional<IntrinsicId> find_texture_method(std::string_view name);

}  // namespace xshade::hlsl
