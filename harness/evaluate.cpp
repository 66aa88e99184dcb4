#include "harness/evaluate.h"

#include <map>

#include "harness/shader_interface.h"
#include "harness/shader_program.h"

namespace xshade::harness {
std::vector<std::byte> default_constant_buffer(const hlsl::ConstantBuffer& buffer,
                                               const std::vector<hlsl::Property>& properties) {
  hlsl::Reflection only_this;
  only_this.constant_buffers = {buffer};
  only_this.properties = properties;
  const ShaderInterface interface = shader_interface(only_this);
  const UniformBlock& block = interface.uniform_blocks.front();
  std::map<std::string, std::vector<float>> values;
  for (const UniformMember& member : block.members) {
    const PropertyDefault* property = interface.find_property(member.name);
    values[member.name] = property && property->value.size() == member.components()
                              ? property->value
                              : std::vector<float>(member.components(), 0.0f);
  }
  auto bytes = build_uniform_block(block, [&values](const std::string& name) { return &values.at(name); });
  return bytes ? std::move(*bytes) : std::vector<std::byte>(buffer.size);
}

Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width,
                            uint32_t height, const std::map<std::string, std::vector<std::byte>>& constant_buffers,
                            const ProgramOptions& options) {
  auto desc = program_for_lane(module, lane, options);
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
