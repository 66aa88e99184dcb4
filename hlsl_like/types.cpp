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

Type Type::texture(TextureShape shape, const Type& texel) {
  Type type = with_kind(TypeKind::Texture);
  type.sub_ = uint8_t(shape);
  type.scalar_ = texel.is_numeric() ? texel.scalar_type() : ScalarType::Float;
  type.cols_ = uint8_t(texel.is_numeric() ? texel.component_count() : 4);
  return type;
}

Type Type::sampler_state(bool comparison) {
  Type type = with_kind(TypeKind::SamplerState);
  type.sub_ = comparison ? 1 : 0;
  return type;
}

Type Type::sampler(TextureShape shape) {
  Type type = with_kind(TypeKind::Sampler);
  type.sub_ = uint8_t(shape);
  return type;
}

Type Type::buffer(BufferKind kind, const Type& element) {
  Type type = with_kind(TypeKind::Buffer);
  type.sub_ = uint8_t(kind);
  type.element_ = std::make_shared<const Type>(element);
  return type;
}

Type Type::constant_buffer(const Type& structure) {
  Type type = with_kind(TypeKind::ConstantBuffer);
  type.element_ = std::make_shared<const Type>(structure);
  return type;
}

Type Type::texel_type() const {
  if (kind_ != TypeKind::Texture) return vector(ScalarType::Float, 4);
  return cols_ == 1 ? scalar(scalar_) : vector(scalar_, cols_);
}

Type Type::with_scalar(const Type& shape, ScalarType scalar) {
  Type type = shape;
  type.scalar_ = scalar;
  return type;
}

uint32_t coordinate_components(TextureShape shape) {
  switch (shape) {
    case TextureShape::Tex1D: return 1;
    case TextureShape::Tex1DArray:
    case TextureShape::Tex2D:
    case TextureShape::Tex2DMS:
    case TextureShape::Subpass:
    case TextureShape::SubpassMS: return 2;
    case TextureShape::Tex2DArray:
    case TextureShape::Tex2DMSArray:
    case TextureShape::Tex3D:
    case TextureShape::Cube: return 3;
    case TextureShape::CubeArray: return 4;
  }
  return 2;
}

uint32_t offset_components(TextureShape shape) {
  switch (shape) {
    case TextureShape::Tex1D:
    case TextureShape::Tex1DArray: return 1;
    case TextureShape::Tex2D:
    case TextureShape::Tex2DArray:
    case TextureShape::Tex2DMS:
    case TextureShape::Tex2DMSArray: return 2;
    case TextureShape::Tex3D: return 3;
    case TextureShape::Cube:
    case TextureShape::CubeArray:
    case TextureShape::Subpass:
    case TextureShape::SubpassMS: return 0;
  }
  return 0;
}

uint32_t gradient_components(TextureShape shape) {
  switch (shape) {
    case TextureShape::Cube:
    case TextureShape::CubeArray: return 3;
    default: return offset_components(shape);
  }
}

bool is_array_shape(TextureShape shape) {
  return shape == TextureShape::Tex1DArray || shape == TextureShape::Tex2DArray ||
         shape == TextureShape::Tex2DMSArray || shape == TextureShape::CubeArray;
}

bool is_multisampled(TextureShape shape) {
  return shape == TextureShape::Tex2DMS || shape == TextureShape::Tex2DMSArray;
}

std::string texture_shape_name(TextureShape shape, bool sampler) {
  if (sampler) {
    switch (shape) {
      case TextureShape::Tex1D: return "sampler1D";
      case TextureShape::Tex3D: return "sampler3D";
      case TextureShape::Cube: return "samplerCUBE";
      default: return "sampler2D";
    }
  }
  switch (shape) {
    case TextureShape::Tex1D: return "Texture1D";
    case TextureShape::Tex1DArray: return "Texture1DArray";
    case TextureShape::Tex2D: return "Texture2D";
    case TextureShape::Tex2DArray: return "Texture2DArray";
    case TextureShape::Tex2DMS: return "Texture2DMS";
    case TextureShape::Tex2DMSArray: return "Texture2DMSArray";
    case TextureShape::Tex3D: return "Texture3D";
    case TextureShape::Cube: return "TextureCube";
    case TextureShape::CubeArray: return "TextureCubeArray";
    case TextureShape::Subpass: return "SubpassInput";
    case TextureShape::SubpassMS: return "SubpassInputMS";
  }
  return "Texture2D";
}

std::string buffer_kind_name(BufferKind kind) {
  switch (kind) {
    case BufferKind::Buffer: return "Buffer";
    case BufferKind::RWBuffer: return "RWBuffer";
    case BufferKind::StructuredBuffer: return "StructuredBuffer";
    case BufferKind::RWStructuredBuffer: return "RWStructuredBuffer";
    case BufferKind::ByteAddressBuffer: return "ByteAddressBuffer";
    case BufferKind::RWByteAddressBuffer: return "RWByteAddressBuffer";
    case BufferKind::AppendStructuredBuffer: return "AppendStructuredBuffer";
    case BufferKind::ConsumeStructuredBuffer: return "ConsumeStructuredBuffer";
    case BufferKind::RWTexture1D: return "RWTexture1D";
    case BufferKind::RWTexture1DArray: return "RWTexture1DArray";
    case BufferKind::RWTexture2D: return "RWTexture2D";
    case BufferKind::RWTexture2DArray: return "RWTexture2DArray";
    case BufferKind::RWTexture3D: return "RWTexture3D";
  }
  return "Buffer";
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
    case TypeKind::Texture: {
      const std::string base = texture_shape_name(texture_shape());
      if (scalar_ == ScalarType::Float && cols_ == 4) return base;
      return base + "<" + texel_type().name() + ">";
    }
    case TypeKind::SamplerState: return is_comparison() ? "SamplerComparisonState" : "SamplerState";
    case TypeKind::Sampler: return texture_shape_name(texture_shape(), true);
    case TypeKind::Buffer: {
      const std::string base = buffer_kind_name(buffer_kind());
      if (buffer_kind() == BufferKind::ByteAddressBuffer || buffer_kind() == BufferKind::RWByteAddressBuffer)
        return base;
      return base + "<" + element_->name() + ">";
    }
    case TypeKind::ConstantBuffer: return "ConstantBuffer<" + element_->name() + ">";
  }
  return "?";
}

bool Type::same_non_numeric(const Type& a, const Type& b) {
  switch (a.kind_) {
    case TypeKind::Struct: return a.struct_ == b.struct_;
    case TypeKind::Array: return a.array_length_ == b.array_length_ && *a.element_ == *b.element_;
    case TypeKind::Texture: return a.sub_ == b.sub_ && a.scalar_ == b.scalar_ && a.cols_ == b.cols_;
    case TypeKind::SamplerState:
    case TypeKind::Sampler: return a.sub_ == b.sub_;
    case TypeKind::Buffer: return a.sub_ == b.sub_ && *a.element_ == *b.element_;
    case TypeKind::ConstantBuffer: return *a.element_ == *b.element_;
    default: return true;
  }
}

std::vector<ScalarType> structured_words(const Type& type) {
  std::vector<ScalarType> words;
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector:
    case TypeKind::Matrix: words.assign(type.component_count(), type.scalar_type()); break;
    case TypeKind::Array:
      for (uint32_t i = 0; i < type.array_length(); ++i) {
        const std::vector<ScalarType> element = structured_words(type.element());
        words.insert(words.end(), element.begin(), element.end());
      }
      break;
    case TypeKind::Struct:
      if (type.struct_decl())
        for (const FieldDecl& field : type.struct_decl()->fields) {
          const std::vector<ScalarType> member = structured_words(field.type);
          words.insert(words.end(), member.begin(), member.end());
        }
      break;
    default: break;
  }
  return words;
}

uint32_t structured_size(const Type& type) {
  switch (type.kind()) {
    case TypeKind::Scalar:
    case TypeKind::Vector:
    case TypeKind::Matrix: return 4 * type.component_count();  // half is 32 bits without -enable-16bit-types
    case TypeKind::Array: return type.array_length() * structured_size(type.element());
    case TypeKind::Struct: {
      uint32_t size = 0;
      if (type.struct_decl())
        for (const FieldDecl& field : type.struct_decl()->fields) size += structured_size(field.type);
      return size;
    }
    default: return 0;
  }
}

}  // namespace xshade::hlsl
