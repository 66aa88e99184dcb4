#include "hlsl_like/types.h"

#include "hlsl_like/ast.h"

namespace xshade::hlsl {

Type Type::scalar(ScalarType scalar) {
  Type type = with_kind(TypeKind::Scalar);
  type.scalar_ = scalar;
  return type;
}

Type Type::vector(ScalarType scalar, uint32_t cols) {
  Type type = with_kind(TypeKind::Vector);
  type.scalar_ = scalar;
  type.cols_ = uint8_t(cols);
  return type;
}

Type Type::matrix(ScalarType scalar, uint32_t rows, uint32_t cols) {
  Type type = with_kind(TypeKind::Matrix);
  type.scalar_ = scalar;
  type.rows_ = uint8_t(rows);
  type.cols_ = uint8_t(cols);
  return type;
}

Type Type::structure(const StructDecl* decl) {
  Type type = with_kind(TypeKind::Struct);
  type.struct_ = decl;
  return type;
}

Type Type::array(const Type& element, uint32_t length) {
  Type type = with_kind(TypeKind::Array);
  type.array_length_ = length;
  type.element_ = std::make_shared<const Type>(element);
  return type;
}

Type Type::with_scalar(const Type& shape, ScalarType scalar) {
  Type type = shape;
  type.scalar_ = scalar;
  return type;
}

std::string scalar_name(ScalarType scalar) {
  switch (scalar) {
    case ScalarType::Bool: return "bool";
    case ScalarType::Int: return "int";
    case ScalarType::Uint: return "uint";
    case ScalarType::Half: return "half";
    case ScalarType::Float: return "float";
  }
  return "?";
}

std::string Type::name() const {
  switch (kind_) {
    case TypeKind::Error: return "<error>";
    case TypeKind::Void: return "void";
    case TypeKind::Scalar: return scalar_name(scalar_);
    case TypeKind::Vector: return scalar_name(scalar_) + std::to_string(cols_);
    case TypeKind::Matrix: return scalar_name(scalar_) + std::to_string(rows_) + "x" + std::to_string(cols_);
    case TypeKind::Struct: return struct_ ? struct_->name : "struct";
    case TypeKind::Array: return element_->name() + "[" + std::to_string(array_length_) + "]";
    case TypeKind::Texture2D: return "Texture2D";
    case TypeKind::SamplerState: return "SamplerState";
    case TypeKind::Sampler2D: return "sampler2D";
  }
  return "?";
}

bool operator==(const Type& a, const Type& b) {
  if (a.kind_ != b.kind_) return false;
  switch (a.kind_) {
    case TypeKind::Scalar:
    case TypeKind::Vector:
    case TypeKind::Matrix:
      return a.scalar_ == b.scalar_ && a.rows_ == b.rows_ && a.cols_ == b.cols_;
    case TypeKind::Struct: return a.struct_ == b.struct_;
    case TypeKind::Array: return a.array_length_ == b.array_length_ && *a.element_ == *b.element_;
    default: return true;
  }
}

}  // namespace xshade::hlsl
