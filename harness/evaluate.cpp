#include "harness/evaluate.h"

#include <cstring>

#include "harness/shader_program.h"

namespace xshade::harness {
namespace {

// Writes `values` as the member's scalars at its offset: 4 bytes each, vectors packed, matrix
// columns (HLSL column_major) or rows 16 bytes apart.
void write_member(std::vector<std::byte>& bytes, const hlsl::ConstantBufferMember& member,
                  const std::vector<double>& values) {
  const hlsl::Type& type = member.type;
  if (!type.is_numeric()) return;
  for (uint32_t row = 0; row < type.rows(); ++row) {
    for (uint32_t col = 0; col < type.cols(); ++col) {
      const size_t index = size_t(row) * type.cols() + col;
      const double value = index < values.size() ? values[index] : 0.0;
      uint32_t offset = member.offset;
      if (type.is_matrix()) offset += member.row_major ? row * 16 + col * 4 : col * 16 + row * 4;
      else offset += col * 4;
      if (offset + 4 > bytes.size()) continue;
      uint32_t bits = 0;
      switch (type.scalar_type()) {
        case hlsl::ScalarType::Int: {
          const auto i = int32_t(value);
          std::memcpy(&bits, &i, 4);
          break;
        }
        case hlsl::ScalarType::Uint:
        case hlsl::ScalarType::Bool: bits = uint32_t(value); break;
        case hlsl::ScalarType::Half:
        case hlsl::ScalarType::Float: {
          const auto f = float(value);
          std::memcpy(&bits, &f, 4);
          break;
        }
      }
      std::memcpy(bytes.data() + offset, &bits, 4);
    }
  }
}

}  // namespace

std::vector<std::byte> default_constant_buffer(const hlsl::ConstantBuffer& buffer,
                                               const std::vector<hlsl::Property>& properties) {
  std::vector<std::byte> bytes(buffer.size);
  for (const hlsl::ConstantBufferMember& member : buffer.members)
    for (const hlsl::Property& property : properties)
      if (property.name == member.name) write_member(bytes, member, property.default_value);
  return bytes;
}

Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width,
                            uint32_t height, const std::map<std::string, std::vector<std::byte>>& constant_buffers) {
  auto desc = program_for_lane(module, lane);
  if (!desc) return fail(desc.error());
  if (!desc->fullscreen) return fail("the shader must be a fragment shader without a vertex stage");
  auto program = backend.create_program(*desc);
  if (!program) return fail(program.error());
  auto target = backend.create_target({width, height, false});
  if (!target) return fail(target.error());

  DrawItem draw{*program, {}, {}, {}};
  const auto& buffers = module.reflection.constant_buffers;
  for (size_t i = 0; i < buffers.size(); ++i) {
    auto given = constant_buffers.find(buffers[i].name);
    std::vector<std::byte> bytes = given != constant_buffers.end() ? given->second
                                                                   : default_constant_buffer(buffers[i], module.reflection.properties);
    if (bytes.size() != buffers[i].size)
      return fail("constant buffer '" + buffers[i].name + "' needs " + std::to_string(buffers[i].size) + " bytes, not " +
                  std::to_string(bytes.size()));
    draw.uniforms.push_back({desc->layout.uniform_blocks[i].name, std::move(bytes)});
  }
  if (!desc->layout.textures.empty()) {
    TextureData white{TextureFormat::Rgba8Unorm, 1, 1, {std::vector<std::byte>(4, std::byte{255})}};
    auto texture = backend.upload_texture(white);
    if (!texture) return fail(texture.error());
    for (const TextureSlot& slot : desc->layout.textures)
      draw.textures.push_back({slot.name, TextureSource::texture(*texture, {Filter::Nearest, AddressMode::ClampToEdge})});
  }
  if (auto rendered = backend.render({*target, glm::vec4(0.0f), 1.0f, {draw}}); !rendered) return fail(rendered.error());
  return backend.read_color(*target);
}

}  // namespace xshade::harness
