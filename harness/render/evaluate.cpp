#include "harness/render/evaluate.h"

#include <algorithm>
#include <cstring>
#include <map>

#include "harness/backend/resource_set.h"
#include "harness/render/shader_interface.h"
#include "harness/render/shader_program.h"
#include "harness/render/synthetic_inputs.h"

namespace xshade::harness {
std::vector<std::byte> default_constant_buffer(const hlsl::ConstantBuffer& buffer,
                                               const std::vector<hlsl::Property>& properties) {
  return constant_buffer_from(buffer, properties, [](const UniformMember& member, const ShaderInterface& interface) {
    const PropertyDefault* property = interface.find_property(member.name);
    return property && property->value.size() == member.components() ? property->value
                                                                     : std::vector<float>(member.components(), 0.0f);
  });
}

Result<FullscreenProgram> FullscreenProgram::create(const hlsl::Module& module, Lane lane, Backend& backend,
                                                    const ProgramOptions& options) {
  glsl::NonfiniteTrace trace;
  auto desc = program_for_lane(module, lane, options, &trace);
  if (!desc) return fail(desc.error());
  if (!desc->fullscreen)
    return fail(ErrorKind::UserInput, "the shader must be a fragment shader without a vertex stage");
  auto program = backend.create_program(*desc);
  if (!program) return fail(program.error());
  FullscreenProgram made;
  made.program_ = *program;
  made.traced_ = options.trace_nonfinite;
  made.trace_ = std::move(trace);
  const auto& buffers = module.reflection.constant_buffers;
  for (size_t i = 0; i < buffers.size(); ++i) {
    hlsl::ConstantBuffer declared = buffers[i];
    declared.decl = nullptr;
    made.buffers_.push_back(
        {buffers[i].name, default_constant_buffer(buffers[i], module.reflection.properties), std::move(declared)});
  }
  made.texture_slots_ = desc->layout.textures;
  made.storage_buffers_ = shader_interface(module.reflection).storage_buffers;  // plain data: the module may go
  return made;
}

std::optional<uint32_t> FullscreenProgram::constant_buffer_size(const std::string& name) const {
  for (const Buffer& buffer : buffers_)
    if (buffer.name == name) return uint32_t(buffer.defaults.size());
  return std::nullopt;
}

TextureData default_texture(const TextureSlot& slot) {
  TextureData texture;
  texture.width = texture.height = 1;
  texture.dimension = slot.shape.dimension;
  texture.layers =
      slot.shape.dimension == TextureDimension::Cube || slot.shape.dimension == TextureDimension::CubeArray ? 6 : 1;
  // Four samples: the count both backends' drivers offer for every colour format.
  texture.samples = slot.shape.multisampled ? 4 : 1;
  std::vector<std::byte> texel;
  const auto append = [&texel](auto value) {
    const size_t end = texel.size();
    texel.resize(end + sizeof value);
    std::memcpy(texel.data() + end, &value, sizeof value);
  };
  if (slot.comparison) {
    texture.format = TextureFormat::Depth32Float;
    append(1.0f);
  } else if (slot.texel == TexelKind::Int) {
    texture.format = TextureFormat::Rgba32Sint;
    for (int i = 0; i < 4; ++i) append(int32_t{1});
  } else if (slot.texel == TexelKind::Uint) {
    texture.format = TextureFormat::Rgba32Uint;
    for (int i = 0; i < 4; ++i) append(uint32_t{1});
  } else {
    texture.format = TextureFormat::Rgba8Unorm;
    texel.assign(4, std::byte{255});
  }
  std::vector<std::byte> level;
  for (uint32_t layer = 0; layer < texture.layers; ++layer) level.insert(level.end(), texel.begin(), texel.end());
  texture.levels = {std::move(level)};
  return texture;
}

Result<FloatImage> FullscreenProgram::run(Backend& backend, uint32_t width, uint32_t height,
                                          const FullscreenInputs& inputs, FloatImage* record) const {
  const auto& constant_buffers = inputs.constant_buffers;
  const auto& textures = inputs.textures;
  // The target and the default textures are this run's own, freed when it returns; a program is
  // run many times (the stability suite, the lane tests), and would otherwise keep every one.
  ResourceSet resources(backend);
  auto target = resources.create_target({width, height, false, traced_});
  if (!target) return fail(target.error());
  DrawItem draw{program_, {}, {}, {}, {}};
  for (const Buffer& buffer : buffers_) {
    auto given = constant_buffers.find(buffer.name);
    const std::vector<std::byte>& bytes = given != constant_buffers.end() ? given->second : buffer.defaults;
    if (bytes.size() != buffer.defaults.size())
      return fail(ErrorKind::Internal, "constant buffer '" + buffer.name + "' needs " +
                                           std::to_string(buffer.defaults.size()) + " bytes, not " +
                                           std::to_string(bytes.size()));
    draw.uniforms.push_back({buffer.name, bytes});
  }
  for (const auto& given : inputs.storage_buffers)
    if (std::none_of(storage_buffers_.begin(), storage_buffers_.end(),
                     [&](const StorageBufferInput& buffer) { return buffer.name == given.first; }))
      return fail(ErrorKind::Internal, "the program reads no buffer named '" + given.first + "'");
  for (const StorageBufferInput& buffer : storage_buffers_) {
    auto given = inputs.storage_buffers.find(buffer.name);
    if (given == inputs.storage_buffers.end())
      return fail(ErrorKind::UserInput, "the shader reads the buffer '" + buffer.name +
                                            "', which has no default: give its bytes (xshade eval: --seed N)");
    draw.storage_buffers.push_back({buffer.name, given->second});
  }
  // A named entry, not a structured binding: clang before 16 lets no lambda capture one.
  for (const auto& given : textures)
    if (std::none_of(texture_slots_.begin(), texture_slots_.end(),
                     [&](const TextureSlot& slot) { return slot.name == given.first; }))
      return fail(ErrorKind::Internal, "the program reads no texture named '" + given.first + "'");
  // One default per distinct declaration, uploaded once per run.
  std::map<std::string, TextureHandle> defaults;
  for (const TextureSlot& slot : texture_slots_) {
    if (auto given = textures.find(slot.name); given != textures.end()) {
      draw.textures.push_back({slot.name, given->second});
      continue;
    }
    const std::string key = shape_name(slot.shape) + texel_kind_name(slot.texel) + (slot.comparison ? " compare" : "");
    auto known = defaults.find(key);
    if (known == defaults.end()) {
      auto texture = resources.upload_texture(default_texture(slot));
      if (!texture) return fail(texture.error());
      known = defaults.emplace(key, *texture).first;
    }
    draw.textures.push_back(
        {slot.name, TextureSource::texture(known->second, {Filter::Nearest, AddressMode::ClampToEdge})});
  }
  if (auto rendered = backend.render({*target, glm::vec4(0.0f), 1.0f, {draw}}); !rendered)
    return fail(rendered.error());
  if (record && traced_) {
    auto recorded = backend.read_second_color(*target);
    if (!recorded) return fail(recorded.error());
    *record = std::move(*recorded);
  }
  return backend.read_color(*target);
}

Result<FloatImage> FullscreenProgram::run_seeded(Backend& backend, uint32_t width, uint32_t height, uint32_t seed,
                                                 FloatImage* record) const {
  FullscreenInputs inputs;
  for (const Buffer& buffer : buffers_)
    inputs.constant_buffers[buffer.name] = seeded_constant_buffer(buffer.declared, seed);
  ResourceSet resources(backend);  // the textures are this run's own
  for (const TextureSlot& slot : texture_slots_) {
    auto texture = resources.upload_texture(seeded_texture(slot, seed));
    if (!texture) return fail(texture.error());
    inputs.textures[slot.name] = TextureSource::texture(*texture, seeded_sampler(slot));
  }
  for (const StorageBufferInput& buffer : storage_buffers_)
    inputs.storage_buffers[buffer.name] = seeded_storage_buffer(buffer, seed);
  return run(backend, width, height, inputs, record);
}

Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width, uint32_t height,
                            const std::map<std::string, std::vector<std::byte>>& constant_buffers,
                            const ProgramOptions& options, const std::map<std::string, TextureSource>& textures,
                            const std::map<std::string, std::vector<std::byte>>& storage_buffers) {
  auto program = FullscreenProgram::create(module, lane, backend, options);
  if (!program) return fail(program.error());
  Result<FloatImage> image = program->run(backend, width, height, {constant_buffers, textures, storage_buffers});
  (void)backend.destroy(program->handle());  // made here, destroyed once: the backend refuses nothing
  return image;
}

}  // namespace xshade::harness
