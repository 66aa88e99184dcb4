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

Result<FullscreenProgram> FullscreenProgram::create(const hlsl::Module& module, Lane lane, Backend& backend,
                                                    const ProgramOptions& options) {
  auto desc = program_for_lane(module, lane, options);
  if (!desc) return fail(desc.error());
  if (!desc->fullscreen) return fail("the shader must be a fragment shader without a vertex stage");
  auto program = backend.create_program(*desc);
  if (!program) return fail(program.error());
  FullscreenProgram made;
  made.program_ = *program;
  const auto& buffers = module.reflection.constant_buffers;
  for (size_t i = 0; i < buffers.size(); ++i)
    made.buffers_.push_back({buffers[i].name, desc->layout.uniform_blocks[i].name,
                             default_constant_buffer(buffers[i], module.reflection.properties)});
  for (const TextureSlot& slot : desc->layout.textures) made.texture_slots_.push_back(slot.name);
  return made;
}

std::optional<uint32_t> FullscreenProgram::constant_buffer_size(const std::string& name) const {
  for (const Buffer& buffer : buffers_)
    if (buffer.name == name) return uint32_t(buffer.defaults.size());
  return std::nullopt;
}

Result<FloatImage> FullscreenProgram::run(Backend& backend, uint32_t width, uint32_t height,
                                          const std::map<std::string, std::vector<std::byte>>& constant_buffers) const {
  auto target = backend.create_target({width, height, false});
  if (!target) return fail(target.error());
  DrawItem draw{program_, {}, {}, {}};
  for (const Buffer& buffer : buffers_) {
    auto given = constant_buffers.find(buffer.name);
    const std::vector<std::byte>& bytes = given != constant_buffers.end() ? given->second : buffer.defaults;
    if (bytes.size() != buffer.defaults.size())
      return fail("constant buffer '" + buffer.name + "' needs " + std::to_string(buffer.defaults.size()) + " bytes, not " +
                  std::to_string(bytes.size()));
    draw.uniforms.push_back({buffer.slot_name, bytes});
  }
  if (!texture_slots_.empty()) {
    TextureData white{TextureFormat::Rgba8Unorm, 1, 1, {std::vector<std::byte>(4, std::byte{255})}};
    auto texture = backend.upload_texture(white);
    if (!texture) return fail(texture.error());
    for (const std::string& slot : texture_slots_)
      draw.textures.push_back({slot, TextureSource::texture(*texture, {Filter::Nearest, AddressMode::ClampToEdge})});
  }
  if (auto rendered = backend.render({*target, glm::vec4(0.0f), 1.0f, {draw}}); !rendered) return fail(rendered.error());
  return backend.read_color(*target);
}

Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width, uint32_t height,
                            const std::map<std::string, std::vector<std::byte>>& constant_buffers,
                            const ProgramOptions& options) {
  auto program = FullscreenProgram::create(module, lane, backend, options);
  if (!program) return fail(program.error());
  return program->run(backend, width, height, constant_buffers);
}

}  // namespace xshade::harness
