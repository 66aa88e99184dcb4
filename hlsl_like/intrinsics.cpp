#include "hlsl_like/intrinsics.h"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <vector>

namespace xshade::hlsl {
namespace {

// ---------------------------------------------------------------------------------------------
// Patterns, named the way HLSL's documentation writes signatures.

using E = PatternElement;
using Sh = PatternShape;

constexpr TypePattern kT{E::T, Sh::T, {0, 0}};            // T
constexpr TypePattern kS{E::T, Sh::Scalar, {0, 0}};       // scalar of T's element
constexpr TypePattern kVN{E::T, Sh::Vector, {kDimN, 0}};  // vector<T, N>
constexpr TypePattern kVR{E::T, Sh::Vector, {kDimR, 0}};
constexpr TypePattern kVC{E::T, Sh::Vector, {kDimC, 0}};
constexpr TypePattern kV3{E::T, Sh::Vector, {3, 0}};
constexpr TypePattern kMRC{E::T, Sh::Matrix, {kDimR, kDimC}};  // matrix<T, R, C>
constexpr TypePattern kMCR{E::T, Sh::Matrix, {kDimC, kDimR}};
constexpr TypePattern kMRN{E::T, Sh::Matrix, {kDimR, kDimN}};
constexpr TypePattern kMNC{E::T, Sh::Matrix, {kDimN, kDimC}};
constexpr TypePattern kMNN{E::T, Sh::Matrix, {kDimN, kDimN}};
constexpr TypePattern kBoolT{E::Bool, Sh::T, {0, 0}};  // T's shape, other elements
constexpr TypePattern kIntT{E::Int, Sh::T, {0, 0}};
constexpr TypePattern kUintT{E::Uint, Sh::T, {0, 0}};
constexpr TypePattern kFloatT{E::Float, Sh::T, {0, 0}};
constexpr TypePattern kBool{E::Bool, Sh::Scalar, {0, 0}};
constexpr TypePattern kFloat{E::Float, Sh::Scalar, {0, 0}};
constexpr TypePattern kFloat2{E::Float, Sh::Vector, {2, 0}};
constexpr TypePattern kFloat3{E::Float, Sh::Vector, {3, 0}};
constexpr TypePattern kFloat4{E::Float, Sh::Vector, {4, 0}};
constexpr TypePattern kVoid{E::Float, Sh::Void, {0, 0}};

constexpr ParamPattern in(TypePattern type) { return {type, false}; }
constexpr ParamPattern out(TypePattern type) { return {type, true}; }

// Element sets.
constexpr uint8_t kFloatLike = element_bit(ScalarType::Half) | element_bit(ScalarType::Float);
constexpr uint8_t kNumeric = kFloatLike | element_bit(ScalarType::Int) | element_bit(ScalarType::Uint);
constexpr uint8_t kAny = kNumeric | element_bit(ScalarType::Bool);
constexpr uint8_t kBitCastable =
    element_bit(ScalarType::Int) | element_bit(ScalarType::Uint) | element_bit(ScalarType::Float);
constexpr uint8_t kUintOnly = element_bit(ScalarType::Uint);
constexpr uint8_t kIntegers = element_bit(ScalarType::Int) | element_bit(ScalarType::Uint);
constexpr uint8_t kFloatOnly = element_bit(ScalarType::Float);
// Shape sets.
constexpr uint8_t kAllShapes = kShapeScalar | kShapeVector | kShapeMatrix;

IntrinsicSignature sig(uint8_t elements, TypePattern result, std::initializer_list<ParamPattern> params,
                       uint8_t shapes = kAllShapes) {
  IntrinsicSignature signature;
  signature.elements = elements;
  signature.shapes = shapes;
  signature.result = result;
  for (const ParamPattern& param : params) signature.params[signature.param_count++] = param;
  return signature;
}

struct Entry {
  IntrinsicId id;
  bool is_method;
  bool fragment_only;
  std::vector<IntrinsicSignature> signatures;
};

// Component-wise math on float-like T: T f(T).
Entry unary_float(IntrinsicId id, bool fragment_only = false) {
  return {id, false, fragment_only, {sig(kFloatLike, kT, {in(kT)})}};
}

// The DX9 sampling functions of one sampler shape: tex2D(s, uv), tex2D(s, uv, ddx, ddy),
// tex2Dbias(s, float4(uv, 0, bias)), tex2Dgrad(s, uv, ddx, ddy), tex2Dlod(s, float4(uv, 0, lod)),
// tex2Dproj(s, float4(uv, 0, w)); a 1D coordinate is a float, a 3D or cube one a float3.
void add_dx9_sampling(std::vector<Entry>& entries, Sh sampler, IntrinsicId plain, IntrinsicId bias, IntrinsicId grad,
                      IntrinsicId lod, IntrinsicId proj) {
  const TypePattern s{E::Float, sampler, {0, 0}};
  const TypePattern coordinate = sampler == Sh::Sampler1D ? kFloat : sampler == Sh::Sampler2D ? kFloat2 : kFloat3;
  entries.push_back({plain,
                     false,
                     true,
                     {sig(kFloatOnly, kFloat4, {in(s), in(coordinate)}),
                      sig(kFloatOnly, kFloat4, {in(s), in(coordinate), in(coordinate), in(coordinate)})}});
  entries.push_back({bias, false, true, {sig(kFloatOnly, kFloat4, {in(s), in(kFloat4)})}});
  entries.push_back(
      {grad, false, false, {sig(kFloatOnly, kFloat4, {in(s), in(coordinate), in(coordinate), in(coordinate)})}});
  entries.push_back({lod, false, false, {sig(kFloatOnly, kFloat4, {in(s), in(kFloat4)})}});
  entries.push_back({proj, false, true, {sig(kFloatOnly, kFloat4, {in(s), in(kFloat4)})}});
}

// The table. Sema tries every signature of an intrinsic and takes the best match; ties go to
// the earlier one. The GLSL emitter maps IntrinsicId (and the argument types sema chose) to GLSL.
std::vector<Entry> make_entries() {
  using I = IntrinsicId;
  std::vector<Entry> entries = {
      {I::Abs, false, false, {sig(kNumeric, kT, {in(kT)})}},
      unary_float(I::Acos),
      {I::All, false, false, {sig(kAny, kBool, {in(kT)})}},
      {I::Any, false, false, {sig(kAny, kBool, {in(kT)})}},
      {I::Asfloat, false, false, {sig(kBitCastable, kFloatT, {in(kT)})}},
      unary_float(I::Asin),
      {I::Asint, false, false, {sig(kBitCastable, kIntT, {in(kT)})}},
      {I::Asuint, false, false, {sig(kBitCastable, kUintT, {in(kT)})}},
      unary_float(I::Atan),
      {I::Atan2, false, false, {sig(kFloatLike, kT, {in(kT), in(kT)})}},
      unary_float(I::Ceil),
      {I::Clamp, false, false, {sig(kNumeric, kT, {in(kT), in(kT), in(kT)})}},
      {I::Clip, false, true, {sig(kFloatLike, kVoid, {in(kT)})}},
      unary_float(I::Cos),
      unary_float(I::Cosh),
      {I::Countbits, false, false, {sig(kUintOnly, kT, {in(kT)})}},
      {I::Cross, false, false, {sig(kFloatLike, kV3, {in(kV3), in(kV3)})}},
      unary_float(I::Ddx, true),
      unary_float(I::DdxCoarse, true),
      unary_float(I::DdxFine, true),
      unary_float(I::Ddy, true),
      unary_float(I::DdyCoarse, true),
      unary_float(I::DdyFine, true),
      unary_float(I::Degrees),
      {I::Determinant, false, false, {sig(kFloatLike, kS, {in(kMNN)})}},
      {I::Distance, false, false, {sig(kFloatLike, kS, {in(kVN), in(kVN)})}},
      {I::Dot, false, false, {sig(kNumeric, kS, {in(kVN), in(kVN)})}},
      unary_float(I::Exp),
      unary_float(I::Exp2),
      {I::F16tof32, false, false, {sig(kUintOnly, kFloatT, {in(kT)})}},
      {I::F32tof16, false, false, {sig(kFloatOnly, kUintT, {in(kT)})}},
      {I::Faceforward, false, false, {sig(kFloatLike, kVN, {in(kVN), in(kVN), in(kVN)})}},
      {I::Firstbithigh, false, false, {sig(kIntegers, kT, {in(kT)})}},
      {I::Firstbitlow, false, false, {sig(kIntegers, kT, {in(kT)})}},
      unary_float(I::Floor),
      {I::Fma, false, false, {sig(kFloatLike, kT, {in(kT), in(kT), in(kT)})}},
      {I::Fmod, false, false, {sig(kFloatLike, kT, {in(kT), in(kT)})}},
      unary_float(I::Frac),
      {I::Frexp, false, false, {sig(kFloatLike, kT, {in(kT), out(kT)})}},
      unary_float(I::Fwidth, true),
      {I::Isfinite, false, false, {sig(kFloatLike, kBoolT, {in(kT)})}},
      {I::Isinf, false, false, {sig(kFloatLike, kBoolT, {in(kT)})}},
      {I::Isnan, false, false, {sig(kFloatLike, kBoolT, {in(kT)})}},
      {I::Ldexp, false, false, {sig(kFloatLike, kT, {in(kT), in(kT)})}},
      {I::Length, false, false, {sig(kFloatLike, kS, {in(kVN)})}},
      {I::Lerp, false, false, {sig(kFloatLike, kT, {in(kT), in(kT), in(kT)})}},
      {I::Lit, false, false, {sig(kFloatOnly, kFloat4, {in(kFloat), in(kFloat), in(kFloat)})}},
      unary_float(I::Log),
      unary_float(I::Log10),
      unary_float(I::Log2),
      {I::Mad, false, false, {sig(kNumeric, kT, {in(kT), in(kT), in(kT)})}},
      {I::Max, false, false, {sig(kNumeric, kT, {in(kT), in(kT)})}},
      {I::Min, false, false, {sig(kNumeric, kT, {in(kT), in(kT)})}},
      {I::Modf, false, false, {sig(kFloatLike, kT, {in(kT), out(kT)})}},
      // mul: every HLSL overload; vectors are rows on the left of a matrix, columns on its right.
      {I::Mul,
       false,
       false,
       {sig(kNumeric, kS, {in(kS), in(kS)}), sig(kNumeric, kVN, {in(kS), in(kVN)}),
        sig(kNumeric, kMRC, {in(kS), in(kMRC)}), sig(kNumeric, kVN, {in(kVN), in(kS)}),
        sig(kNumeric, kS, {in(kVN), in(kVN)}), sig(kNumeric, kVC, {in(kVN), in(kMNC)}),
        sig(kNumeric, kMRC, {in(kMRC), in(kS)}), sig(kNumeric, kVR, {in(kMRN), in(kVN)}),
        sig(kNumeric, kMRC, {in(kMRN), in(kMNC)})}},
      {I::Normalize, false, false, {sig(kFloatLike, kVN, {in(kVN)})}},
      {I::Pow, false, false, {sig(kFloatLike, kT, {in(kT), in(kT)})}},
      unary_float(I::Radians),
      unary_float(I::Rcp),
      {I::Reflect, false, false, {sig(kFloatLike, kVN, {in(kVN), in(kVN)})}},
      {I::Refract, false, false, {sig(kFloatLike, kVN, {in(kVN), in(kVN), in(kS)})}},
      {I::Reversebits, false, false, {sig(kUintOnly, kT, {in(kT)})}},
      unary_float(I::Round),
      unary_float(I::Rsqrt),
      unary_float(I::Saturate),
      // HLSL 2021 (DXC's default language): ?: component by component, both sides evaluated.
      {I::Select, false, false, {sig(kAny, kT, {in(kBoolT), in(kT), in(kT)})}},
      {I::Sign, false, false, {sig(kNumeric, kIntT, {in(kT)})}},
      unary_float(I::Sin),
      {I::Sincos, false, false, {sig(kFloatLike, kVoid, {in(kT), out(kT), out(kT)})}},
      unary_float(I::Sinh),
      {I::Smoothstep, false, false, {sig(kFloatLike, kT, {in(kT), in(kT), in(kT)})}},
      unary_float(I::Sqrt),
      {I::Step, false, false, {sig(kFloatLike, kT, {in(kT), in(kT)})}},
      unary_float(I::Tan),
      unary_float(I::Tanh),
      {I::Transpose, false, false, {sig(kAny, kMCR, {in(kMRC)})}},
      unary_float(I::Trunc),
  };
  add_dx9_sampling(entries, Sh::Sampler1D, I::Tex1D, I::Tex1Dbias, I::Tex1Dgrad, I::Tex1Dlod, I::Tex1Dproj);
  add_dx9_sampling(entries, Sh::Sampler2D, I::Tex2D, I::Tex2Dbias, I::Tex2Dgrad, I::Tex2Dlod, I::Tex2Dproj);
  add_dx9_sampling(entries, Sh::Sampler3D, I::Tex3D, I::Tex3Dbias, I::Tex3Dgrad, I::Tex3Dlod, I::Tex3Dproj);
  add_dx9_sampling(entries, Sh::SamplerCube, I::TexCUBE, I::TexCUBEbias, I::TexCUBEgrad, I::TexCUBElod, I::TexCUBEproj);
  // Texture methods: names and stages here, signatures in sema_methods.cpp.
  for (I id : {I::Sample, I::SampleBias, I::SampleCmp, I::CalculateLevelOfDetail, I::CalculateLevelOfDetailUnclamped,
               I::SubpassLoad})
    entries.push_back({id, true, true, {}});
  for (I id : {I::SampleGrad, I::SampleLevel, I::SampleCmpLevelZero, I::Load, I::GetDimensions, I::Gather, I::GatherRed,
               I::GatherGreen, I::GatherBlue, I::GatherAlpha, I::GatherCmp, I::GatherCmpRed, I::GatherCmpGreen,
               I::GatherCmpBlue, I::GatherCmpAlpha})
    entries.push_back({id, true, false, {}});
  return entries;
}

#define XSHADE_INTRINSIC_COUNT(id, name) +1
constexpr size_t kIntrinsicCount = 1 XSHADE_INTRINSICS(XSHADE_INTRINSIC_COUNT);  // with None
#undef XSHADE_INTRINSIC_COUNT

constexpr std::array<std::string_view, kIntrinsicCount> kNames = {"",
#define XSHADE_INTRINSIC_NAME(id, name) name,
                                                                  XSHADE_INTRINSICS(XSHADE_INTRINSIC_NAME)
#undef XSHADE_INTRINSIC_NAME
};

struct Table {
  std::vector<Entry> entries;  // indexed by IntrinsicId
  std::array<IntrinsicInfo, kIntrinsicCount> infos{};

  Table() {
    entries.resize(kIntrinsicCount);
    for (Entry& entry : make_entries()) entries[size_t(entry.id)] = std::move(entry);
    for (size_t i = 0; i < kIntrinsicCount; ++i) {
      const Entry& entry = entries[i];
      infos[i] = IntrinsicInfo{IntrinsicId(i), kNames[i], entry.is_method, entry.fragment_only,
                               std::span<const IntrinsicSignature>(entry.signatures)};
    }
  }
};

const Table& table() {
  static const Table instance;
  return instance;
}

}  // namespace

std::string_view intrinsic_name(IntrinsicId id) {
  const size_t index = size_t(id);
  return index < kIntrinsicCount ? kNames[index] : std::string_view();
}

const IntrinsicInfo& intrinsic_info(IntrinsicId id) {
  const size_t index = size_t(id) < kIntrinsicCount ? size_t(id) : 0;
  return table().infos[index];
}

namespace {

struct NamedId {
  std::string_view name;
  uint16_t id;
};

// Every name with its id, sorted by name and then id: every call in a shader looks its callee
// up here, and a scan of the whole table per call showed in profiles.
constexpr std::array<NamedId, kIntrinsicCount - 1> kByName = [] {
  std::array<NamedId, kIntrinsicCount - 1> sorted{};
  for (size_t i = 1; i < kIntrinsicCount; ++i) sorted[i - 1] = {kNames[i], uint16_t(i)};
  std::sort(sorted.begin(), sorted.end(),
            [](const NamedId& a, const NamedId& b) { return a.name != b.name ? a.name < b.name : a.id < b.id; });
  return sorted;
}();

// The first id (in IntrinsicId order) named `name` that is (or is not) a method.
std::optional<IntrinsicId> find(std::string_view name, bool method) {
  auto it = std::lower_bound(kByName.begin(), kByName.end(), name,
                             [](const NamedId& entry, std::string_view key) { return entry.name < key; });
  for (; it != kByName.end() && it->name == name; ++it) {
    if (table().infos[it->id].is_method == method) return IntrinsicId(it->id);
  }
  return std::nullopt;
}

}  // namespace

std::optional<IntrinsicId> find_intrinsic(std::string_view name) { return find(name, false); }

std::optional<IntrinsicId> find_texture_method(std::string_view name) { return find(name, true); }

}  // namespace xshade::hlsl
