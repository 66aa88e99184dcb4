// Semantic analysis of resource methods and indexing: what each texture shape's Sample, Load,
// Gather, GetDimensions... take and give (HLSL's signatures, offsets and clamps included), and
// the methods of the buffer resources, which are typed so that code reaching them can be
// checked even though no target here binds them.
#include <algorithm>
#include <initializer_list>
#include <stdexcept>

#include "hlsl_like/sema_internal.h"

namespace xshade::hlsl::sema_detail {

namespace {

using I = IntrinsicId;

// The fixed arrays below are sized for HLSL's methods; a table outgrowing them is a bug here,
// reported loudly rather than written past.
void check_room(bool room) {
  if (!room) throw std::logic_error("a resource method signature outgrew its fixed capacity");
}

// Built for every method call of a shader, so in fixed arrays rather than vectors.
struct MethodSignature {
  Type params[kMaxSignatureParams];
  bool out[kMaxSignatureParams] = {};
  size_t count = 0;
  Type result;

  void push_back(const Type& type, bool is_out) {
    check_room(count < kMaxSignatureParams);
    params[count] = type;
    out[count++] = is_out;
  }
  // Inserts an in parameter before the others.
  void push_front(const Type& type) {
    check_room(count < kMaxSignatureParams);
    for (size_t i = count; i > 0; --i) {
      params[i] = params[i - 1];
      out[i] = out[i - 1];
    }
    params[0] = type;
    out[0] = false;
    ++count;
  }
};

// The signatures of one method on one resource: at most a base form with an offset and a clamp,
// or GetDimensions' four (uint or float sizes, with or without a mip level).
inline constexpr size_t kMaxMethodSignatures = 4;
struct Signatures {
  MethodSignature items[kMaxMethodSignatures];
  size_t count = 0;

  void push_back(const MethodSignature& signature) {
    check_room(count < kMaxMethodSignatures);
    items[count++] = signature;
  }
  MethodSignature& back() { return items[count - 1]; }
  bool empty() const { return count == 0; }
  const MethodSignature* begin() const { return items; }
  const MethodSignature* end() const { return items + count; }
};

Type vec(ScalarType scalar, uint32_t n) { return n == 1 ? Type::scalar(scalar) : Type::vector(scalar, n); }
Type floats(uint32_t n) { return vec(ScalarType::Float, n); }
Type ints(uint32_t n) { return vec(ScalarType::Int, n); }
const Type kFloat = Type::scalar(ScalarType::Float);
const Type kUint = Type::scalar(ScalarType::Uint);

MethodSignature in_only(std::initializer_list<Type> params, const Type& result) {
  MethodSignature signature;
  for (const Type& param : params) signature.push_back(param, false);
  signature.result = result;
  return signature;
}

// `base`, then `base` + a texel offset, then + offset + a clamp for the level of detail.
void with_offset(Signatures& out, const MethodSignature& base, TextureShape shape, bool clamp) {
  out.push_back(base);
  const uint32_t offset = offset_components(shape);
  if (offset == 0) return;
  out.push_back(base);
  out.back().push_back(ints(offset), false);
  if (!clamp) return;
  out.push_back(out.back());
  out.back().push_back(kFloat, false);
}

// GetDimensions: the sizes a shape reports (width, height, depth or layers, samples), each as
// uint or as float, with a mip-level form (mip in, then the sizes and the level count out).
void get_dimensions(Signatures& out, TextureShape shape) {
  uint32_t sizes = 0;
  switch (shape) {
    case TextureShape::Tex1D: sizes = 1; break;
    case TextureShape::Tex1DArray:
    case TextureShape::Tex2D:
    case TextureShape::Cube: sizes = 2; break;
    case TextureShape::Tex2DArray:
    case TextureShape::CubeArray:
    case TextureShape::Tex3D:
    case TextureShape::Tex2DMS: sizes = 3; break;
    case TextureShape::Tex2DMSArray: sizes = 4; break;
    case TextureShape::Subpass:
    case TextureShape::SubpassMS: return;  // a subpass input is read at the pixel, of no size
  }
  for (ScalarType scalar : {ScalarType::Uint, ScalarType::Float}) {
    MethodSignature plain;
    plain.result = Type::void_type();
    for (uint32_t i = 0; i < sizes; ++i) plain.push_back(Type::scalar(scalar), true);
    out.push_back(plain);
    if (is_multisampled(shape)) continue;
    MethodSignature mip = plain;
    mip.push_front(kUint);
    mip.push_back(Type::scalar(scalar), true);
    out.push_back(mip);
  }
}

bool gathers(TextureShape shape) {
  return shape == TextureShape::Tex2D || shape == TextureShape::Tex2DArray || shape == TextureShape::Cube ||
         shape == TextureShape::CubeArray;
}

bool compares(TextureShape shape) { return shape != TextureShape::Tex3D && !is_multisampled(shape); }

// Adds the signatures of `id` on a texture, as HLSL defines them; none when the shape has no such
// method (a cube map has no Load and no offsets, a multisampled texture samples nothing).
void texture_signatures(IntrinsicId id, const Type& texture, Signatures& out) {
  const TextureShape shape = texture.texture_shape();
  const uint32_t n = coordinate_components(shape);
  const uint32_t g = gradient_components(shape);
  const Type texel = texture.texel_type();
  const Type sampler = Type::sampler_state(false);
  const Type comparison = Type::sampler_state(true);
  const Type scalar_texel = Type::scalar(texel.is_numeric() ? texel.scalar_type() : ScalarType::Float);
  const Type gathered = Type::vector(scalar_texel.scalar_type(), 4);
  const bool ms = is_multisampled(shape);
  if (shape == TextureShape::Subpass || shape == TextureShape::SubpassMS) {
    // SubpassLoad() at the fragment's pixel; of a multisampled one, SubpassLoad(sample).
    if (id == I::SubpassLoad)
      out.push_back(shape == TextureShape::Subpass ? in_only({}, texel)
                                                   : in_only({Type::scalar(ScalarType::Int)}, texel));
    return;
  }
  switch (id) {
    case I::Sample:
      if (!ms) with_offset(out, in_only({sampler, floats(n)}, texel), shape, true);
      break;
    case I::SampleBias:
      if (!ms) with_offset(out, in_only({sampler, floats(n), kFloat}, texel), shape, true);
      break;
    case I::SampleLevel:
      if (!ms) with_offset(out, in_only({sampler, floats(n), kFloat}, texel), shape, false);
      break;
    case I::SampleGrad:
      if (!ms) with_offset(out, in_only({sampler, floats(n), floats(g), floats(g)}, texel), shape, true);
      break;
    case I::SampleCmp:
      if (compares(shape)) with_offset(out, in_only({comparison, floats(n), kFloat}, scalar_texel), shape, true);
      break;
    case I::SampleCmpLevelZero:
      if (compares(shape)) with_offset(out, in_only({comparison, floats(n), kFloat}, scalar_texel), shape, false);
      break;
    case I::Load:
      if (ms) {
        with_offset(out, in_only({ints(n), Type::scalar(ScalarType::Int)}, texel), shape, false);
      } else if (shape != TextureShape::Cube && shape != TextureShape::CubeArray) {
        with_offset(out, in_only({ints(n + 1)}, texel), shape, false);  // the mip level last
      }
      break;
    case I::Gather:
    case I::GatherRed:
    case I::GatherGreen:
    case I::GatherBlue:
    case I::GatherAlpha:
      if (gathers(shape)) with_offset(out, in_only({sampler, floats(n)}, gathered), shape, false);
      break;
    case I::GatherCmp:
    case I::GatherCmpRed:
    case I::GatherCmpGreen:
    case I::GatherCmpBlue:
    case I::GatherCmpAlpha:
      if (gathers(shape)) with_offset(out, in_only({comparison, floats(n), kFloat}, gathered), shape, false);
      break;
    case I::GetDimensions: get_dimensions(out, shape); break;
    case I::CalculateLevelOfDetail:
    case I::CalculateLevelOfDetailUnclamped:
      if (!ms) out.push_back(in_only({sampler, floats(g)}, kFloat));
      break;
    default: break;
  }
}

bool is_read_write(BufferKind kind) {
  switch (kind) {
    case BufferKind::RWBuffer:
    case BufferKind::RWStructuredBuffer:
    case BufferKind::RWByteAddressBuffer:
    case BufferKind::RWTexture1D:
    case BufferKind::RWTexture1DArray:
    case BufferKind::RWTexture2D:
    case BufferKind::RWTexture2DArray:
    case BufferKind::RWTexture3D: return true;
    default: return false;
  }
}

// The components of the index of a buffer or RWTexture: RWTexture2D<float4> t; t[uint2(x, y)].
uint32_t buffer_index_components(BufferKind kind) {
  switch (kind) {
    case BufferKind::RWTexture1DArray:
    case BufferKind::RWTexture2D: return 2;
    case BufferKind::RWTexture2DArray:
    case BufferKind::RWTexture3D: return 3;
    default: return 1;
  }
}

// Adds the signatures of the buffer resources' method `method`.
void buffer_signatures(const std::string& method, const Type& buffer, Signatures& out) {
  const BufferKind kind = buffer.buffer_kind();
  const Type& element = buffer.element();
  const Type uint_type = kUint;
  const bool byte_address = kind == BufferKind::ByteAddressBuffer || kind == BufferKind::RWByteAddressBuffer;
  auto outs = [&](uint32_t count) {
    MethodSignature signature;
    signature.result = Type::void_type();
    for (uint32_t i = 0; i < count; ++i) signature.push_back(uint_type, true);
    return signature;
  };
  if (method == "GetDimensions") {
    switch (kind) {
      case BufferKind::StructuredBuffer:
      case BufferKind::RWStructuredBuffer:
      case BufferKind::AppendStructuredBuffer:
      case BufferKind::ConsumeStructuredBuffer: out.push_back(outs(2)); break;
      case BufferKind::RWTexture1D:
      case BufferKind::Buffer:
      case BufferKind::RWBuffer:
      case BufferKind::ByteAddressBuffer:
      case BufferKind::RWByteAddressBuffer: out.push_back(outs(1)); break;
      case BufferKind::RWTexture1DArray:
      case BufferKind::RWTexture2D: out.push_back(outs(2)); break;
      case BufferKind::RWTexture2DArray:
      case BufferKind::RWTexture3D: out.push_back(outs(3)); break;
    }
  } else if (byte_address) {
    for (uint32_t n = 1; n <= 4; ++n) {
      const std::string suffix = n == 1 ? "" : std::to_string(n);
      if (method == "Load" + suffix) out.push_back(in_only({uint_type}, vec(ScalarType::Uint, n)));
      if (kind == BufferKind::RWByteAddressBuffer && method == "Store" + suffix)
        out.push_back(in_only({uint_type, vec(ScalarType::Uint, n)}, Type::void_type()));
    }
  } else if (method == "Load" && kind != BufferKind::AppendStructuredBuffer &&
             kind != BufferKind::ConsumeStructuredBuffer) {
    out.push_back(in_only({ints(buffer_index_components(kind))}, element));
  } else if (method == "Append" && kind == BufferKind::AppendStructuredBuffer) {
    out.push_back(in_only({element}, Type::void_type()));
  } else if (method == "Consume" && kind == BufferKind::ConsumeStructuredBuffer) {
    out.push_back(in_only({}, element));
  } else if ((method == "IncrementCounter" || method == "DecrementCounter") && kind == BufferKind::RWStructuredBuffer) {
    out.push_back(in_only({}, uint_type));
  }
}

}  // namespace

Type Sema::analyze_method_call(CallExpr& expr, const Type& object) {
  Signatures signatures;
  if (object.kind() == TypeKind::Texture) {
    const std::optional<IntrinsicId> method = find_texture_method(expr.callee);
    if (method) {
      expr.intrinsic = uint16_t(*method);
      texture_signatures(*method, object, signatures);
    }
  } else if (object.kind() == TypeKind::Buffer) {
    expr.intrinsic = uint16_t(IntrinsicId::BufferMethod);
    buffer_signatures(expr.callee, object, signatures);
  }
  if (signatures.empty()) {
    diag_.error(expr.loc, in_quotes(object.name()) + " has no method " + in_quotes(expr.callee));
    return Type::error();
  }
  bool arity_matches = false;
  for (const MethodSignature& signature : signatures) arity_matches |= signature.count == expr.args.size();
  if (!arity_matches) {
    std::vector<size_t> arities;
    for (const MethodSignature& signature : signatures) arities.push_back(signature.count);
    diag_.error(expr.loc, in_quotes(expr.callee) + " of " + in_quotes(object.name()) + " takes " + arity_list(arities) +
                              ", " + std::to_string(expr.args.size()) + " given");
    return Type::error();
  }
  const MethodSignature* viable[kMaxMethodSignatures];
  Ranks ranks[kMaxMethodSignatures];
  size_t count = 0;
  for (const MethodSignature& signature : signatures) {
    if (signature.count != expr.args.size()) continue;
    Ranks& rank = ranks[count];
    rank.count = 0;
    bool ok = true;
    for (size_t i = 0; i < expr.args.size() && ok; ++i) {
      const Conversion conversion = signature.out[i] ? classify_implicit(signature.params[i], expr.args[i]->type)
                                                     : classify_implicit(expr.args[i]->type, signature.params[i]);
      ok = conversion.valid;
      rank.push_back(conversion.rank);
    }
    if (!ok) continue;
    viable[count++] = &signature;
  }
  if (count == 0) {
    diag_.error(expr.loc, "no overload of " + in_quotes(expr.callee) + " of " + in_quotes(object.name()) + " takes (" +
                              join_types(expr.args) + ")");
    return Type::error();
  }
  int best = unique_best(std::span<const Ranks>(ranks, count));
  if (best < 0) best = 0;  // the signatures differ only in out types (GetDimensions): uint first
  const MethodSignature& chosen = *viable[size_t(best)];
  for (size_t i = 0; i < expr.args.size(); ++i)
    pass_argument(*this, expr.args[i], chosen.params[i], chosen.out[i] ? ParamDirection::Out : ParamDirection::In, i,
                  expr.callee);
  if (object.kind() == TypeKind::Texture && intrinsic_info(IntrinsicId(expr.intrinsic)).fragment_only)
    note_fragment_only(in_quotes(expr.callee), expr.loc);
  return chosen.result;
}

Type Sema::analyze_resource_index(IndexExpr& expr, const Type& object) {
  uint32_t components = 0;
  Type result;
  if (object.kind() == TypeKind::Texture && !is_multisampled(object.texture_shape()) &&
      object.texture_shape() != TextureShape::Cube && object.texture_shape() != TextureShape::CubeArray) {
    components = coordinate_components(object.texture_shape());  // t[p] reads mip 0: Load(int3(p, 0))
    result = object.texel_type();
  } else if (object.kind() == TypeKind::Buffer && object.buffer_kind() != BufferKind::ByteAddressBuffer &&
             object.buffer_kind() != BufferKind::RWByteAddressBuffer &&
             object.buffer_kind() != BufferKind::AppendStructuredBuffer &&
             object.buffer_kind() != BufferKind::ConsumeStructuredBuffer) {
    components = buffer_index_components(object.buffer_kind());
    result = object.element();
  } else {
    diag_.error(expr.loc, "cannot index a value of type " + in_quotes(object.name()));
    return Type::error();
  }
  if (!expr.index || expr.index->type.is_error()) return result;
  const Type index_type = vec(ScalarType::Uint, components);
  const Conversion conversion = classify_implicit(expr.index->type, index_type);
  if (!conversion.valid) {
    diag_.error(expr.index->loc, "the index of " + in_quotes(object.name()) + " must be " +
                                     in_quotes(index_type.name()) + ", not " + in_quotes(expr.index->type.name()));
    return Type::error();
  }
  coerce(expr.index, index_type);
  return result;
}

bool is_writable_resource(const Type& type) {
  return type.kind() == TypeKind::Buffer && is_read_write(type.buffer_kind());
}

}  // namespace xshade::hlsl::sema_detail
