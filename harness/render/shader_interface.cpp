#include "harness/render/shader_interface.h"

#include <cstring>
#include <map>

#include <nlohmann/json.hpp>

#include "glsl/glsl_emitter.h"

namespace xshade::harness {
namespace {

using nlohmann::json;

UniformMember uniform_member(const hlsl::ConstantBufferMember& member) {
  UniformMember out;
  out.name = member.name;
  out.offset = member.offset;
  out.row_major = member.row_major;
  out.read = member.used;
  const hlsl::Type* type = &member.type;
  if (type->kind() == hlsl::TypeKind::Array) {
    out.array_length = type->array_length();
    type = &type->element();
  }
  out.scalar = type->scalar_type();
  out.rows = type->rows();
  out.cols = type->cols();
  return out;
}

// Bytes between array elements: HLSL starts every element on a 16-byte register, and a
// matrix takes one register per column (column_major) or per row (row_major).
uint32_t element_stride(const UniformMember& member) {
  const uint32_t registers = member.rows > 1 ? (member.row_major ? member.rows : member.cols) : 1;
  return 16 * registers;
}

uint32_t component_bits(hlsl::ScalarType scalar, float value) {
  uint32_t bits = 0;
  switch (scalar) {
    case hlsl::ScalarType::Int: {
      const auto i = int32_t(value);
      std::memcpy(&bits, &i, 4);
      break;
    }
    case hlsl::ScalarType::Uint:
    case hlsl::ScalarType::Bool: bits = uint32_t(value); break;
    // half is stored as a 32-bit float in a constant buffer (Shader Model 5 packing).
    case hlsl::ScalarType::Half:
    case hlsl::ScalarType::Float: std::memcpy(&bits, &value, 4); break;
  }
  return bits;
}

const char* scalar_spelling(hlsl::ScalarType scalar) {
  switch (scalar) {
    case hlsl::ScalarType::Bool: return "bool";
    case hlsl::ScalarType::Int: return "int";
    case hlsl::ScalarType::Uint: return "uint";
    case hlsl::ScalarType::Half: return "half";
    case hlsl::ScalarType::Float: return "float";
  }
  return "float";
}

}  // namespace

const PropertyDefault* ShaderInterface::find_property(const std::string& name) const {
  for (const PropertyDefault& property : properties)
    if (property.name == name) return &property;
  return nullptr;
}

ShaderInterface shader_interface(const hlsl::Reflection& reflection) {
  ShaderInterface interface;
  for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers) {
    UniformBlock block{buffer.name, buffer.size, {}};
    for (const hlsl::ConstantBufferMember& member : buffer.members)
      if (member.type.is_numeric() || member.type.kind() == hlsl::TypeKind::Array)
        block.members.push_back(uniform_member(member));
    interface.uniform_blocks.push_back(std::move(block));
  }
  for (const hlsl::TextureResource& texture : reflection.textures)
    if (texture.used) interface.textures.push_back(texture.name);
  for (const hlsl::StorageBufferResource& buffer : reflection.buffers) {
    if (!buffer.used) continue;
    StorageBufferInput input{buffer.name, buffer.stride, "f"};
    if (buffer.kind != hlsl::BufferKind::ByteAddressBuffer) {
      input.words.clear();
      for (hlsl::ScalarType scalar : hlsl::structured_words(buffer.element))
        input.words += scalar == hlsl::ScalarType::Int    ? 'i'
                       : scalar == hlsl::ScalarType::Uint ? 'u'
                       : scalar == hlsl::ScalarType::Bool ? 'b'
                                                          : 'f';
    }
    interface.storage_buffers.push_back(std::move(input));
  }
  for (const hlsl::Property& property : reflection.properties) {
    if (property.is_texture) continue;
    PropertyDefault out{property.name, {}};
    for (double component : property.default_value) out.value.push_back(float(component));
    interface.properties.push_back(std::move(out));
  }
  return interface;
}

std::string shader_interface_json(const ShaderInterface& interface) {
  json blocks = json::array();
  for (const UniformBlock& block : interface.uniform_blocks) {
    json members = json::array();
    for (const UniformMember& m : block.members)
      members.push_back({{"name", m.name},
                         {"scalar", scalar_spelling(m.scalar)},
                         {"rows", m.rows},
                         {"cols", m.cols},
                         {"array_length", m.array_length},
                         {"offset", m.offset},
                         {"row_major", m.row_major},
                         {"read", m.read}});
    blocks.push_back({{"name", block.name}, {"size", block.size}, {"members", members}});
  }
  json properties = json::array();
  for (const PropertyDefault& property : interface.properties)
    properties.push_back({{"name", property.name}, {"value", property.value}});
  json storage_buffers = json::array();
  for (const StorageBufferInput& buffer : interface.storage_buffers)
    storage_buffers.push_back({{"name", buffer.name}, {"stride", buffer.stride}, {"words", buffer.words}});
  return json{{"uniform_blocks", blocks},
              {"textures", interface.textures},
              {"storage_buffers", storage_buffers},
              {"properties", properties}}
      .dump(1);
}

Result<ShaderInterface> parse_shader_interface_json(const std::string& text) {
  try {
    const json document = json::parse(text);
    ShaderInterface interface;
    for (const json& b : document.at("uniform_blocks")) {
      UniformBlock block{b.at("name"), b.at("size"), {}};
      for (const json& m : b.at("members")) {
        UniformMember member;
        member.name = m.at("name");
        const std::string scalar = m.at("scalar");
        for (auto candidate : {hlsl::ScalarType::Bool, hlsl::ScalarType::Int, hlsl::ScalarType::Uint,
                               hlsl::ScalarType::Half, hlsl::ScalarType::Float})
          if (scalar == scalar_spelling(candidate)) member.scalar = candidate;
        member.rows = m.at("rows");
        member.cols = m.at("cols");
        member.array_length = m.at("array_length");
        member.offset = m.at("offset");
        member.row_major = m.at("row_major");
        member.read = m.at("read");
        block.members.push_back(std::move(member));
      }
      interface.uniform_blocks.push_back(std::move(block));
    }
    interface.textures = document.at("textures").get<std::vector<std::string>>();
    for (const json& b : document.at("storage_buffers"))
      interface.storage_buffers.push_back({b.at("name"), b.at("stride"), b.at("words")});
    for (const json& p : document.at("properties"))
      interface.properties.push_back({p.at("name"), p.at("value").get<std::vector<float>>()});
    return interface;
  } catch (const json::exception& error) {
    return fail(ErrorKind::Internal, std::string("a cached shader interface is malformed: ") + error.what());
  }
}

Result<std::vector<std::byte>> build_uniform_block(const UniformBlock& block, const UniformLookup& lookup) {
  std::vector<std::byte> bytes(block.size);
  for (const UniformMember& member : block.members) {
    const std::vector<float>* value = lookup(member.name);
    if (!value && !member.read) continue;  // zeros, which nothing reads
    if (!value)
      return fail(
          ErrorKind::UserInput,
          "uniform '" + member.name + "' in '" + block.name +
              "' has no value: the renderer does not supply it, the scene does not set it and it has no default");
    if (value->size() != member.components())
      return fail(ErrorKind::UserInput, "uniform '" + member.name + "' in '" + block.name + "' has " +
                                            std::to_string(member.components()) + " components; the value given has " +
                                            std::to_string(value->size()));
    const uint32_t stride = element_stride(member);
    const uint32_t per_element = member.rows * member.cols;
    for (uint32_t element = 0; element < std::max(member.array_length, 1u); ++element) {
      for (uint32_t row = 0; row < member.rows; ++row) {
        for (uint32_t col = 0; col < member.cols; ++col) {
          uint32_t offset = member.offset + element * stride;
          if (member.rows > 1)
            offset += member.row_major ? row * 16 + col * 4 : col * 16 + row * 4;
          else
            offset += col * 4;
          if (offset + 4 > bytes.size())
            return fail(ErrorKind::Internal, "uniform '" + member.name + "' in '" + block.name +
                                                 "' lies outside the block's " + std::to_string(block.size) + " bytes");
          const uint32_t bits =
              component_bits(member.scalar, (*value)[element * per_element + row * member.cols + col]);
          std::memcpy(bytes.data() + offset, &bits, 4);
        }
      }
    }
  }
  return bytes;
}

std::vector<std::byte> constant_buffer_from(const hlsl::ConstantBuffer& buffer,
                                            const std::vector<hlsl::Property>& properties,
                                            const MemberValue& value_of) {
  hlsl::Reflection only_this;
  only_this.constant_buffers = {buffer};
  only_this.properties = properties;
  const ShaderInterface interface = shader_interface(only_this);
  const UniformBlock& block = interface.uniform_blocks.front();
  std::map<std::string, std::vector<float>> values;
  for (const UniformMember& member : block.members) values[member.name] = value_of(member, interface);
  auto bytes = build_uniform_block(block, [&values](const std::string& name) { return &values.at(name); });
  return bytes ? std::move(*bytes) : std::vector<std::byte>(buffer.size);
}

}  // namespace xshade::harness
