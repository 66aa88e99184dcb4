// The types of hlsl_like: HLSL's scalars, vectors, matrices, structs, arrays and resources.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace xshade::hlsl {

struct StructDecl;

// `half`, `min16float` and the prelude's `fixed` are Half: computed in fp32 on these drivers, but
// remembered, so that half-precision emulation can round their results to fp16.
enum class ScalarType : uint8_t { Bool, Int, Uint, Half, Float };

enum class TypeKind : uint8_t {
  Error,  // the type of an expression that already failed; silences follow-on errors
  Void,
  Scalar,
  Vector,  // cols components, 1..4 (a 1-component vector is float1, distinct from float)
  Matrix,  // rows x cols, each 1..4: HLSL floatRxC has R rows
  Struct,
  Array,           // array_length elements of *element
  Texture,         // Texture1D .. TextureCubeArray, Texture2DMS: texture_shape(), read as texel_type()
  SamplerState,    // SamplerState, or SamplerComparisonState when is_comparison()
  Sampler,         // DX9 sampler1D/2D/3D/CUBE: texture and sampler combined, read with tex2D & co.
  Buffer,          // Buffer<T>, StructuredBuffer<T>, ByteAddressBuffer, the RW forms, RWTexture*:
                   // HLSL that no lane here can bind; buffer_kind(), element()
  ConstantBuffer,  // ConstantBuffer<S> (Shader Model 5.1): a constant buffer holding the struct S
};

// The shape of a texture or a DX9 sampler.
// Subpass and SubpassMS are Vulkan's subpass inputs (SubpassInput, SubpassInputMS): the
// previous subpass's attachment read at the fragment's own pixel with SubpassLoad.
enum class TextureShape : uint8_t {
  Tex1D,
  Tex1DArray,
  Tex2D,
  Tex2DArray,
  Tex2DMS,
  Tex2DMSArray,
  Tex3D,
  Cube,
  CubeArray,
  Subpass,
  SubpassMS
};

// Components of the coordinate that addresses a texel (with the array layer), of a texel
// offset (0: the shape has none), of a gradient, and of the size GetDimensions reports
// (with the layer count).
uint32_t coordinate_components(TextureShape shape);
uint32_t offset_components(TextureShape shape);
uint32_t gradient_components(TextureShape shape);
bool is_array_shape(TextureShape shape);
bool is_multisampled(TextureShape shape);
// "Texture2D", "TextureCube", ...; `sampler` gives the DX9 spelling ("sampler2D", "samplerCUBE").
std::string texture_shape_name(TextureShape shape, bool sampler = false);

enum class BufferKind : uint8_t {
  Buffer,
  RWBuffer,
  StructuredBuffer,
  RWStructuredBuffer,
  ByteAddressBuffer,
  RWByteAddressBuffer,
  AppendStructuredBuffer,
  ConsumeStructuredBuffer,
  RWTexture1D,
  RWTexture1DArray,
  RWTexture2D,
  RWTexture2DArray,
  RWTexture3D,
};
std::string buffer_kind_name(BufferKind kind);

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
  // A texture read as `texel` (a scalar or vector: Texture2D<float> reads floats; float4 by default).
  static Type texture(TextureShape shape, const Type& texel);
  static Type texture2d() { return texture(TextureShape::Tex2D, vector(ScalarType::Float, 4)); }
  static Type sampler_state(bool comparison = false);
  static Type sampler(TextureShape shape);
  static Type sampler2d() { return sampler(TextureShape::Tex2D); }
  // `element` is ignored (and may be Error) for the byte-address buffers.
  static Type buffer(BufferKind kind, const Type& element);
  static Type constant_buffer(const Type& structure);
  // Scalar, vector or matrix of `scalar` with the shape of `shape` (which must be numeric).
  static Type with_scalar(const Type& shape, ScalarType scalar);

  TypeKind kind() const { return kind_; }
  ScalarType scalar_type() const { return scalar_; }  // of Scalar, Vector, Matrix
  uint32_t rows() const { return rows_; }             // 1 for scalars and vectors
  uint32_t cols() const { return cols_; }             // 1 for scalars
  const StructDecl* struct_decl() const { return struct_; }
  uint32_t array_length() const { return array_length_; }
  const Type& element() const { return *element_; }                  // of Array, Buffer, ConstantBuffer
  TextureShape texture_shape() const { return TextureShape(sub_); }  // of Texture and Sampler
  BufferKind buffer_kind() const { return BufferKind(sub_); }        // of Buffer
  bool is_comparison() const { return kind_ == TypeKind::SamplerState && sub_ != 0; }
  // What a texture's Load and Sample give: Texture2D<float> gives float, Texture2D float4.
  // A DX9 sampler gives float4.
  Type texel_type() const;

  bool is_error() const { return kind_ == TypeKind::Error; }
  bool is_void() const { return kind_ == TypeKind::Void; }
  bool is_scalar() const { return kind_ == TypeKind::Scalar; }
  bool is_vector() const { return kind_ == TypeKind::Vector; }
  bool is_matrix() const { return kind_ == TypeKind::Matrix; }
  bool is_numeric() const { return is_scalar() || is_vector() || is_matrix(); }
  bool is_resource() const { return kind_ >= TypeKind::Texture; }
  bool is_texture() const { return kind_ == TypeKind::Texture; }
  // A sized global array of textures, samplers or constant buffers (Texture2D t[4]), which
  // reflection makes one resource of that many elements.
  bool is_resource_array() const {
    return kind_ == TypeKind::Array && array_length_ > 0 && element_ &&
           (element_->kind_ == TypeKind::Texture || element_->kind_ == TypeKind::SamplerState ||
            element_->kind_ == TypeKind::Sampler || element_->kind_ == TypeKind::ConstantBuffer);
  }
  bool is_floating() const { return is_numeric() && (scalar_ == ScalarType::Float || scalar_ == ScalarType::Half); }
  bool is_integer() const { return is_numeric() && (scalar_ == ScalarType::Int || scalar_ == ScalarType::Uint); }
  bool is_bool() const { return is_numeric() && scalar_ == ScalarType::Bool; }
  // Components of a numeric type (rows * cols); 0 for anything else.
  uint32_t component_count() const { return is_numeric() ? rows_ * cols_ : 0; }

  // HLSL's spelling: float, float3, float4x4, half2, Light, float[4], Texture2D, Texture2D<uint4>.
  std::string name() const;

  // Numeric types, most of what sema and the emitters compare, are compared inline.
  friend bool operator==(const Type& a, const Type& b) {
    if (a.kind_ != b.kind_) return false;
    if (a.kind_ == TypeKind::Scalar || a.kind_ == TypeKind::Vector || a.kind_ == TypeKind::Matrix) {
      return a.scalar_ == b.scalar_ && a.rows_ == b.rows_ && a.cols_ == b.cols_;
    }
    return same_non_numeric(a, b);
  }

 private:
  // operator== for two types of the same kind that is not numeric.
  static bool same_non_numeric(const Type& a, const Type& b);

  static Type with_kind(TypeKind kind) {
    Type type;
    type.kind_ = kind;
    return type;
  }

  TypeKind kind_ = TypeKind::Error;
  ScalarType scalar_ = ScalarType::Float;
  uint8_t rows_ = 1;
  uint8_t cols_ = 1;
  uint8_t sub_ = 0;  // TextureShape, BufferKind or the comparison flag
  uint32_t array_length_ = 0;
  const StructDecl* struct_ = nullptr;
  std::shared_ptr<const Type> element_;
};

std::string scalar_name(ScalarType scalar);

// Bytes a value of `type` takes in a structured buffer, packed as Direct3D packs it.
uint32_t structured_size(const Type& type);
// The scalar type of each 32-bit word of a value of `type` in a structured buffer, in order
// (structured_size / 4 of them).
std::vector<ScalarType> structured_words(const Type& type);

}  // namespace xshade::hlsl
