// The types of hlsl_like: HLSL's scalars, vectors, matrices, structs, arrays and resources.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace xshade::hlsl {

struct StructDecl;

// `half`, `min16float` and the prelude's `fixed` are Half: computed in fp32 on these drivers, but
// remembered, so that half-precision emulation can round their results to fp16.
enum class ScalarType : uint8_t { Bool, Int, Uint, Half, Float };

enum class TypeKind : uint8_t {
  Error,         // the type of an expression that already failed; silences follow-on errors
  Void,
  Scalar,
  Vector,        // cols components, 1..4 (a 1-component vector is float1, distinct from float)
  Matrix,        // rows x cols, each 1..4: HLSL floatRxC has R rows
  Struct,
  Array,         // array_length elements of *element
  Texture2D,     // with SamplerState: separate objects (Shader Model 4+ style)
  SamplerState,
  Sampler2D,     // DX9 `sampler2D`: texture and sampler combined, read with tex2D
};

class Type {
 public:
  Type() = default;  // Error

  static Type error() { return {}; }
  static Type void_type() { return with_kind(TypeKind::Void); }
  static Type scalar(ScalarType scalar);
  static Type vector(ScalarType scalar, uint32_t cols);
  static Type matrix(ScalarType scalar, uint32_t rows, uint32_t cols);
  static Type structure(const StructDecl* decl);
  static Type array(const Type& element, uint32_t length);
  static Type texture2d() { return with_kind(TypeKind::Texture2D); }
  static Type sampler_state() { return with_kind(TypeKind::SamplerState); }
  static Type sampler2d() { return with_kind(TypeKind::Sampler2D); }
  // Scalar, vector or matrix of `scalar` with the shape of `shape` (which must be numeric).
  static Type with_scalar(const Type& shape, ScalarType scalar);

  TypeKind kind() const { return kind_; }
  ScalarType scalar_type() const { return scalar_; }  // of Scalar, Vector, Matrix
  uint32_t rows() const { return rows_; }             // 1 for scalars and vectors
  uint32_t cols() const { return cols_; }             // 1 for scalars
  const StructDecl* struct_decl() const { return struct_; }
  uint32_t array_length() const { return array_length_; }
  const Type& element() const { return *element_; }  // of Array

  bool is_error() const { return kind_ == TypeKind::Error; }
  bool is_void() const { return kind_ == TypeKind::Void; }
  bool is_scalar() const { return kind_ == TypeKind::Scalar; }
  bool is_vector() const { return kind_ == TypeKind::Vector; }
  bool is_matrix() const { return kind_ == TypeKind::Matrix; }
  bool is_numeric() const { return is_scalar() || is_vector() || is_matrix(); }
  bool is_resource() const {
    return kind_ == TypeKind::Texture2D || kind_ == TypeKind::SamplerState || kind_ == TypeKind::Sampler2D;
  }
  bool is_floating() const { return is_numeric() && (scalar_ == ScalarType::Float || scalar_ == ScalarType::Half); }
  bool is_integer() const { return is_numeric() && (scalar_ == ScalarType::Int || scalar_ == ScalarType::Uint); }
  bool is_bool() const { return is_numeric() && scalar_ == ScalarType::Bool; }
  // Components of a numeric type (rows * cols); 0 for anything else.
  uint32_t component_count() const { return is_numeric() ? rows_ * cols_ : 0; }

  // HLSL's spelling: float, float3, float4x4, half2, Light, float[4], Texture2D.
  std::string name() const;

  friend bool operator==(const Type& a, const Type& b);

 private:
  static Type with_kind(TypeKind kind) {
    Type type;
    type.kind_ = kind;
    return type;
  }

  TypeKind kind_ = TypeKind::Error;
  ScalarType scalar_ = ScalarType::Float;
  uint8_t rows_ = 1;
  uint8_t cols_ = 1;
  uint32_t array_length_ = 0;
  const StructDecl* struct_ = nullptr;
  std::shared_ptr<const Type> element_;
};

std::string scalar_name(ScalarType scalar);

}  // namespace xshade::hlsl
