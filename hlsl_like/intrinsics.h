// HLSL's intrinsic functions and texture methods: one table that semantic analysis resolves
// calls against and that the GLSL emitter maps to GLSL.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "hlsl_like/types.h"

namespace xshade::hlsl {

// The table as it reads, several names a line (clang-format would put one a line).
// clang-format off
#define XSHADE_INTRINSICS(X)                                                                                           \
  X(Abs, "abs") X(Acos, "acos") X(All, "all") X(Any, "any") X(Asfloat, "asfloat")                                      \
  X(Asin, "asin") X(Asint, "asint") X(Asuint, "asuint") X(Atan, "atan") X(Atan2, "atan2")                              \
  X(Ceil, "ceil") X(Clamp, "clamp") X(Clip, "clip") X(Cos, "cos") X(Cosh, "cosh")                                      \
  X(Countbits, "countbits") X(Cross, "cross") X(Ddx, "ddx") X(DdxCoarse, "ddx_coarse")                                 \
  X(DdxFine, "ddx_fine") X(Ddy, "ddy") X(DdyCoarse, "ddy_coarse") X(DdyFine, "ddy_fine")                               \
  X(Degrees, "degrees") X(Determinant, "determinant") X(Distance, "distance") X(Dot, "dot")                            \
  X(Exp, "exp") X(Exp2, "exp2") X(F16tof32, "f16tof32") X(F32tof16, "f32tof16")                                        \
  X(Faceforward, "faceforward") X(Firstbithigh, "firstbithigh") X(Firstbitlow, "firstbitlow")                          \
  X(Floor, "floor") X(Fma, "fma") X(Fmod, "fmod") X(Frac, "frac") X(Frexp, "frexp")                                    \
  X(Fwidth, "fwidth") X(Isfinite, "isfinite") X(Isinf, "isinf") X(Isnan, "isnan")                                      \
  X(Ldexp, "ldexp") X(Length, "length") X(Lerp, "lerp") X(Lit, "lit") X(Log, "log")                                    \
  X(Log10, "log10") X(Log2, "log2") X(Mad, "mad") X(Max, "max") X(Min, "min") X(Modf, "modf")                          \
  X(Mul, "mul") X(Normalize, "normalize") X(Pow, "pow") X(Radians, "radians") X(Rcp, "rcp")                            \
  X(Reflect, "reflect") X(Refract, "refract") X(Reversebits, "reversebits") X(Round, "round")                          \
  X(Rsqrt, "rsqrt") X(Saturate, "saturate") X(Select, "select") X(Sign, "sign") X(Sin, "sin") X(Sincos, "sincos")      \
  X(Sinh, "sinh") X(Smoothstep, "smoothstep") X(Sqrt, "sqrt") X(Step, "step") X(Tan, "tan")                            \
  X(Tanh, "tanh") X(Transpose, "transpose") X(Trunc, "trunc")                                                          \
  /* DX9 sampling: tex<shape>[bias|grad|lod|proj] on sampler1D/2D/3D/CUBE */                                           \
  X(Tex1D, "tex1D") X(Tex1Dbias, "tex1Dbias") X(Tex1Dgrad, "tex1Dgrad") X(Tex1Dlod, "tex1Dlod")                        \
  X(Tex1Dproj, "tex1Dproj") X(Tex2D, "tex2D") X(Tex2Dbias, "tex2Dbias")                                                \
  X(Tex2Dgrad, "tex2Dgrad") X(Tex2Dlod, "tex2Dlod") X(Tex2Dproj, "tex2Dproj") X(Tex3D, "tex3D")                        \
  X(Tex3Dbias, "tex3Dbias") X(Tex3Dgrad, "tex3Dgrad") X(Tex3Dlod, "tex3Dlod")                                          \
  X(Tex3Dproj, "tex3Dproj") X(TexCUBE, "texCUBE") X(TexCUBEbias, "texCUBEbias")                                        \
  X(TexCUBEgrad, "texCUBEgrad") X(TexCUBElod, "texCUBElod") X(TexCUBEproj, "texCUBEproj")                              \
  /* texture methods; their signatures depend on the texture (sema_methods.cpp) */                                     \
  X(Sample, "Sample") X(SampleBias, "SampleBias") X(SampleGrad, "SampleGrad")                                          \
  X(SampleLevel, "SampleLevel") X(SampleCmp, "SampleCmp")                                                              \
  X(SampleCmpLevelZero, "SampleCmpLevelZero") X(Load, "Load") X(SubpassLoad, "SubpassLoad") X(GetDimensions, "GetDimensions") \
  X(Gather, "Gather") X(GatherRed, "GatherRed") X(GatherGreen, "GatherGreen")                                          \
  X(GatherBlue, "GatherBlue") X(GatherAlpha, "GatherAlpha") X(GatherCmp, "GatherCmp")                                  \
  X(GatherCmpRed, "GatherCmpRed") X(GatherCmpGreen, "GatherCmpGreen")                                                  \
  X(GatherCmpBlue, "GatherCmpBlue") X(GatherCmpAlpha, "GatherCmpAlpha")                                                \
  X(CalculateLevelOfDetail, "CalculateLevelOfDetail")                                                                  \
  X(CalculateLevelOfDetailUnclamped, "CalculateLevelOfDetailUnclamped")                                                \
  /* a method of a Buffer-kind resource, which sema types and no target emits */                                       \
  X(BufferMethod, "")
// clang-format on

enum class IntrinsicId : uint16_t {
  None = 0,
#define XSHADE_INTRINSIC_ENUM(id, name) id,
  XSHADE_INTRINSICS(XSHADE_INTRINSIC_ENUM)
#undef XSHADE_INTRINSIC_ENUM
};

std::string_view intrinsic_name(IntrinsicId id);
// A free function's intrinsic by name (not the Texture2D methods).
std::optional<IntrinsicId> find_intrinsic(std::string_view name);
// A texture method by name.
std::optional<IntrinsicId> find_texture_method(std::string_view name);
// tex1D .. texCUBEproj, the DX9 functions on a sampler1D/2D/3D/CUBE.
inline bool is_dx9_sampling(IntrinsicId id) { return id >= IntrinsicId::Tex1D && id <= IntrinsicId::TexCUBEproj; }

// ---------------------------------------------------------------------------------------------
// Signatures: the rules semantic analysis resolves calls with. Each intrinsic has one or more
// signatures; each parameter and the result is a pattern over a template type T, whose element
// type and shape are deduced from the arguments the way HLSL does (the highest element type, the
// smallest vector or matrix; scalars splat), and over dimension variables N, R, C, bound across
// the signature (a matrix fixes a dimension; longer vectors are truncated to it).

// The element type of a pattern: T's (deduced, limited to the signature's `elements`) or fixed.
enum class PatternElement : uint8_t { T, Bool, Int, Uint, Float };

enum class PatternShape : uint8_t {
  T,  // T's shape: scalar, vector or matrix as deduced (limited to the signature's `shapes`)
  Scalar,
  Vector,  // dims[0] components
  Matrix,  // dims[0] rows, dims[1] columns
  Void,
  SamplerState,
  Sampler1D,  // the DX9 samplers
  Sampler2D,
  Sampler3D,
  SamplerCube,
};

// A dimension of a Vector or Matrix pattern: 1..4, or one of these variables.
inline constexpr uint8_t kDimN = 0x10;
inline constexpr uint8_t kDimR = 0x11;
inline constexpr uint8_t kDimC = 0x12;
inline constexpr bool is_dim_variable(uint8_t dim) { return dim >= kDimN; }

struct TypePattern {
  PatternElement element = PatternElement::T;
  PatternShape shape = PatternShape::T;
  uint8_t dims[2] = {0, 0};
};

struct ParamPattern {
  TypePattern type;
  bool out = false;  // an `out` parameter: the argument must be assignable
};

// Bit sets over ScalarType and over the shapes T may take.
inline constexpr uint8_t element_bit(ScalarType scalar) { return uint8_t(1u << unsigned(scalar)); }
inline constexpr uint8_t kShapeScalar = 1, kShapeVector = 2, kShapeMatrix = 4;

struct IntrinsicSignature {
  uint8_t elements = 0;  // element types T may take (element_bit)
  uint8_t shapes = 0;    // shapes T may take (kShape*)
  TypePattern result;
  uint8_t param_count = 0;
  ParamPattern params[4] = {};
};

struct IntrinsicInfo {
  IntrinsicId id = IntrinsicId::None;
  std::string_view name;
  bool is_method = false;                          // a texture method: signatures are not in the table
  bool fragment_only = false;                      // derivatives, implicit-LOD sampling, clip
  std::span<const IntrinsicSignature> signatures;  // in order of preference on a tie
};

// Every intrinsic's entry; IntrinsicId::None gives an empty entry.
const IntrinsicInfo& intrinsic_info(IntrinsicId id);

}  // namespace xshade::hlsl
