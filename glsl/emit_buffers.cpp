// Read-only buffers in GLSL (hlsl::StorageBufferResource): each one a storage buffer of 32-bit
// words, read through a helper per buffer that assembles an element from the words as Direct3D
// lays it out. GLSL's own block layouts (std430 pads a vec3 to 16 bytes) cannot say Direct3D's
// tight packing, and words can: the same bytes read the same on every target.
#include "glsl/stage_emitter.h"

namespace xshade::glsl::detail {

using namespace hlsl;

namespace {

// The GLSL value of `type` whose first word is read(base + offset) (Direct3D's structured
// layout: four bytes per scalar in order, a matrix column by column, HLSL's default packing).
std::string word_value(StageEmitter& emitter, const Type& type, const std::string& read, uint32_t offset, Loc loc) {
  const auto word = [&](uint32_t k) { return read + "(base + " + std::to_string(offset + k) + "u)"; };
  const auto scalar = [&](ScalarType scalar_type, uint32_t k) -> std::string {
    switch (scalar_type) {
      case ScalarType::Float:
      case ScalarType::Half: return "uintBitsToFloat(" + word(k) + ")";
      case ScalarType::Int: return "int(" + word(k) + ")";
      case ScalarType::Uint: return word(k);
      case ScalarType::Bool: return "(" + word(k) + " != 0u)";
    }
    return word(k);
  };
  switch (type.kind()) {
    case TypeKind::Scalar: return scalar(type.scalar_type(), 0);
    case TypeKind::Vector:
    case TypeKind::Matrix: {
      // GLSL's matRxC holds HLSL's rows as its columns, so its constructor takes HLSL's
      // elements row by row: element (r, c) is word c * rows + r of a matrix stored column-major.
      std::string text = emitter.type_name(type, loc) + "(";
      for (uint32_t r = 0; r < type.rows(); ++r)
        for (uint32_t c = 0; c < type.cols(); ++c) {
          const uint32_t k = type.is_matrix() ? c * type.rows() + r : c;
          text += (r == 0 && c == 0 ? "" : ", ") + scalar(type.scalar_type(), k);
        }
      return text + ")";
    }
    case TypeKind::Array: {
      const uint32_t size = structured_size(type.element()) / 4;
      std::string text = emitter.type_name(type, loc) + "(";
      for (uint32_t i = 0; i < type.array_length(); ++i)
        text += (i ? ", " : "") + word_value(emitter, type.element(), read, offset + i * size, loc);
      return text + ")";
    }
    case TypeKind::Struct: {
      std::string text = emitter.type_name(type, loc) + "(";
      uint32_t at = offset;
      bool first = true;
      for (const FieldDecl& field : type.struct_decl()->fields) {
        text += (first ? "" : ", ") + word_value(emitter, field.type, read, at, loc);
        at += structured_size(field.type) / 4;
        first = false;
      }
      return text + ")";
    }
    default: emitter.fail(loc, in_quotes(type.name()) + " cannot be an element of a buffer on this target"); return "0";
  }
}

}  // namespace

const StorageBufferResource* StageEmitter::buffer_of(const Expr* object, Loc loc) {
  const Decl* decl = lower::named_decl(object);
  for (const StorageBufferResource& buffer : reflection_.buffers)
    if (decl && buffer.decl == decl) return &buffer;
  if (object && !is_read_only_buffer(object->type.buffer_kind()))
    fail(loc, in_quotes(object->type.name()) +
                  " is not supported on this target: xshade reads StructuredBuffer, "
                  "ByteAddressBuffer and Buffer, which a vertex or fragment stage only reads");
  else
    fail(loc, "a buffer is read here through a parameter or local; read the global buffer itself");
  return nullptr;
}

std::string StageEmitter::buffer_declaration(const StorageBufferResource& buffer) const {
  const std::string place = (flavour_ == Flavour::Vk ? "set = " + std::to_string(buffer.set) + ", " : std::string()) +
                            "binding = " + std::to_string(buffer.binding);
  return "layout(std430, " + place + ") readonly buffer " + buffer_block_name(buffer.name) + " { uint xs_words[]; } " +
         names_.of(buffer.name) + ";";
}

std::string StageEmitter::buffer_element_helper(const StorageBufferResource& buffer, uint32_t words, Loc loc) {
  const std::string instance = names_.of(buffer.name);
  const bool bytes = buffer.kind == BufferKind::ByteAddressBuffer;
  const Type element =
      bytes ? (words == 1 ? Type::scalar(ScalarType::Uint) : Type::vector(ScalarType::Uint, words)) : buffer.element;
  const std::string name = "xs_load" + (bytes ? std::to_string(words) : std::string()) + "_" + buffer.name;
  // A ByteAddressBuffer is addressed in bytes (Direct3D ignores the two low bits), the others by element.
  const std::string base = bytes ? "address >> 2u" : "index * " + std::to_string(buffer.stride / 4) + "u";
  const std::string type = type_name(element, loc);
  // A word past the bound buffer's end reads 0, as Direct3D reads past a view's end.
  const std::string read = "xs_word_" + buffer.name;
  helpers_.add(read, "uint " + read + "(uint at) {\n  return at < uint(" + instance + ".xs_words.length()) ? " +
                         instance + ".xs_words[at] : 0u;\n}\n");
  helpers_.add(name, type + " " + name + "(uint " + (bytes ? "address" : "index") + ") {\n  uint base = " + base +
                         ";\n  return " + word_value(*this, element, read, 0, loc) + ";\n}\n");
  return name;
}

Code StageEmitter::buffer_index(const IndexExpr& index) {
  const StorageBufferResource* buffer = buffer_of(index.object.get(), index.loc);
  if (!buffer) return {"0"};
  return {buffer_element_helper(*buffer, 1, index.loc) + "(uint(" + expr(index.index.get()).text + "))", kPostfix};
}

Code StageEmitter::buffer_call(const CallExpr& call) {
  const StorageBufferResource* buffer = buffer_of(call.object.get(), call.loc);
  if (!buffer) return {"0"};
  const std::string& method = call.callee;
  const std::string instance = names_.of(buffer->name);
  if (method == "GetDimensions") {
    // Elements (or bytes) the bound buffer holds, and a structured buffer's stride.
    const std::string bytes = "(uint(" + instance + ".xs_words.length()) * 4u)";
    std::string parts;
    for (size_t i = 0; i < call.args.size(); ++i) {
      const std::string value = i == 1 ? std::to_string(buffer->stride) + "u"
                                : buffer->kind == BufferKind::ByteAddressBuffer
                                    ? bytes
                                    : "(" + bytes + " / " + std::to_string(buffer->stride) + "u)";
      parts +=
          (i ? ", " : "") + operand(expr(call.args[i].get()), kUnary) + " = " +
          operand(convert({value, kPostfix}, Type::scalar(ScalarType::Uint), call.args[i]->type, call.loc), kAssign);
    }
    return {"(" + parts + ")"};
  }
  uint32_t words = 1;
  if (buffer->kind == BufferKind::ByteAddressBuffer && method.size() == 5 && method[4] >= '2' && method[4] <= '4')
    words = uint32_t(method[4] - '0');
  if (method.rfind("Load", 0) != 0 || call.args.empty()) {
    fail(call.loc, in_quotes(method) + " is not supported on this target");
    return {"0"};
  }
  return {buffer_element_helper(*buffer, words, call.loc) + "(uint(" + expr(call.args[0].get()).text + "))", kPostfix};
}

}  // namespace xshade::glsl::detail
