#include "harness/render/shader_program.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <map>

#include "codegen/generate.h"

namespace xshade::harness {
TextureShape harness_shape(hlsl::TextureShape shape) {
  using S = hlsl::TextureShape;
  using D = TextureDimension;
  switch (shape) {
    case S::Tex1D: return {D::Tex1D, false};
    case S::Tex1DArray: return {D::Tex1DArray, false};
    case S::Tex2D: return {D::Tex2D, false};
    case S::Tex2DArray: return {D::Tex2DArray, false};
    case S::Tex2DMS: return {D::Tex2D, true};
    case S::Tex2DMSArray: return {D::Tex2DArray, true};
    case S::Tex3D: return {D::Tex3D, false};
    case S::Cube: return {D::Cube, false};
    case S::CubeArray: return {D::CubeArray, false};
    case S::Subpass: return {D::Tex2D, false};
    case S::SubpassMS: return {D::Tex2D, true};
  }
  return {};
}

TexelKind harness_texel(hlsl::ScalarType texel) {
  if (texel == hlsl::ScalarType::Int) return TexelKind::Int;
  if (texel == hlsl::ScalarType::Uint || texel == hlsl::ScalarType::Bool) return TexelKind::Uint;
  return TexelKind::Float;
}

Result<std::map<uint32_t, double>> resolve_specialization(const std::vector<std::string>& given,
                                                          const hlsl::Reflection& reflection) {
  std::map<uint32_t, double> values;
  std::string names;
  for (const hlsl::SpecializationConstant& constant : reflection.specialization_constants)
    names += (names.empty() ? "" : ", ") + constant.name;
  for (const std::string& text : given) {
    const size_t equals = text.find('=');
    const std::string name = text.substr(0, equals);
    const auto constant =
        std::find_if(reflection.specialization_constants.begin(), reflection.specialization_constants.end(),
                     [&](const hlsl::SpecializationConstant& c) { return c.name == name; });
    if (equals == std::string::npos || constant == reflection.specialization_constants.end())
      return fail(ErrorKind::Usage, "--specialize " + text +
                                        ": expected NAME=VALUE naming a [[vk::constant_id]] constant of the shader (" +
                                        (names.empty() ? "it has none" : "it has " + names) + ")");
    const std::string number = text.substr(equals + 1);
    char* end = nullptr;
    const double value = std::strtod(number.c_str(), &end);
    const bool whole = constant->scalar != hlsl::ScalarType::Float && constant->scalar != hlsl::ScalarType::Half;
    const bool fits = constant->scalar == hlsl::ScalarType::Bool   ? value == 0.0 || value == 1.0
                      : constant->scalar == hlsl::ScalarType::Uint ? value >= 0.0 && value <= 4294967295.0
                      : constant->scalar == hlsl::ScalarType::Int  ? value >= -2147483648.0 && value <= 2147483647.0
                                                                   : true;
    if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value) ||
        (whole && std::floor(value) != value) || !fits)
      return fail(ErrorKind::Usage, "--specialize " + text + ": '" + name + "' is of type " +
                                        hlsl::scalar_name(constant->scalar) + "; give it " +
                                        (constant->scalar == hlsl::ScalarType::Bool ? std::string("0 or 1")
                                         : whole                                    ? "a whole number in its range"
                                                                                    : "a finite number"));
    values[constant->id] = value;
  }
  return values;
}

uint32_t specialization_word(double value, hlsl::ScalarType scalar) {
  switch (scalar) {
    case hlsl::ScalarType::Bool: return value != 0.0 ? 1u : 0u;  // a VkBool32
    case hlsl::ScalarType::Int: return uint32_t(int32_t(value));
    case hlsl::ScalarType::Uint: return uint32_t(value);
    default: return std::bit_cast<uint32_t>(float(value));
  }
}

std::string array_of_resources(const std::string& name, uint32_t count) {
  return "'" + name + "' is an array of " + std::to_string(count) +
         " resources, which a scene cannot give yet (it binds one texture or buffer per name)";
}

// What the harness cannot draw, said before the program is compiled for a lane: its backends bind
// descriptor set 0, a scene gives no subpass inputs or arrays of resources, lavapipe has
// no variable-rate shading, and its meshes feed the vertex format's locations.
Result<void> drawable(const hlsl::Module& module, Lane lane) {
  const hlsl::Reflection& reflection = module.reflection;
  const SourceLocation where = module.sources.resolve({module.main_file, 0, 0});
  const auto refuse = [&](const std::string& what) {
    return fail(ErrorKind::UserInput,
                what + "; `xshade compile` writes it as the source asks, but the harness cannot draw it", where);
  };
  for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers) {
    if (buffer.set != 0) return refuse("'" + buffer.name + "' is in descriptor set " + std::to_string(buffer.set));
    if (buffer.count > 1) return refuse(array_of_resources(buffer.name, buffer.count));
  }
  for (const hlsl::TextureResource& texture : reflection.textures) {
    if (!texture.used) continue;
    if (texture.set != 0) return refuse("'" + texture.name + "' is in descriptor set " + std::to_string(texture.set));
    if (texture.count > 1) return refuse(array_of_resources(texture.name, texture.count));
    if (texture.shape == hlsl::TextureShape::Subpass || texture.shape == hlsl::TextureShape::SubpassMS)
      return refuse("'" + texture.name +
                    "' is a subpass input, which a scene cannot give yet (on Vulkan an input "
                    "attachment; the gl target reads the texture bound at its binding at the fragment's pixel)");
  }
  for (const hlsl::StorageBufferResource& buffer : reflection.buffers) {
    if (!buffer.used) continue;
    if (buffer.set != 0) return refuse("'" + buffer.name + "' is in descriptor set " + std::to_string(buffer.set));
    if (buffer.kind == hlsl::BufferKind::Buffer && lane == Lane::VkHlsl)
      return refuse(
          "'" + buffer.name +
          "' is a Buffer<T>, which glslang's HLSL front end reads as a uniform texel "
          "buffer, and the harness binds read-only buffers as storage buffers (the gl and vk lanes read it so)");
  }
  for (const hlsl::SamplerResource& sampler : reflection.samplers) {
    if (!sampler.used) continue;
    if (sampler.set != 0) return refuse("'" + sampler.name + "' is in descriptor set " + std::to_string(sampler.set));
    if (sampler.count > 1) return refuse(array_of_resources(sampler.name, sampler.count));
  }
  if (reflection.reads_shading_rate && lane != Lane::Gl)
    return refuse(
        "it reads SV_ShadingRate, and lavapipe has no variable-rate shading (VK_KHR_fragment_shading_rate); "
        "the gl lane reads 0, OpenGL's one rate (1x1)");
  for (const hlsl::StageVariable& input : reflection.vertex_inputs) {
    const std::optional<uint32_t> fed = hlsl::vertex_input_location(input.semantic);
    if (input.given_location && fed != input.given_location)
      return refuse("vertex input " + input.semantic + " is at [[vk::location(" +
                    std::to_string(*input.given_location) + ")]], where the meshes feed " +
                    (fed ? "location " + std::to_string(*fed) : "nothing") + " (docs/hlsl_like.md, section 8)");
  }
  return {};
}

namespace {

// The layout the harness binds by, from the names and bindings the generated code declares: each
// resource by its HLSL name, and on OpenGL, which binds by name, by the code's name where it differs.
ProgramLayout program_layout(const codegen::BindingInterface& interface, Lane lane) {
  const bool gl = lane == Lane::Gl;
  ProgramLayout layout;
  for (const codegen::BindingInterface::UniformBlock& block : interface.uniform_blocks)
    layout.uniform_blocks.push_back({block.name, block.binding, block.size, block.push_constant,
                                     gl && block.code_name != block.name ? block.code_name : ""});
  for (const codegen::BindingInterface::Texture& texture : interface.textures) {
    TextureSlot slot{texture.name, texture.binding, texture.sampler_binding};
    slot.shape = harness_shape(texture.shape);
    slot.comparison = texture.comparison;
    slot.texel = harness_texel(texture.texel);
    slot.image_only = texture.image_only;
    slot.filtered_in_shader = texture.filtered_in_shader;
    if (gl && texture.code_name != texture.name) slot.glsl_name = texture.code_name;
    layout.textures.push_back(std::move(slot));
  }
  for (const codegen::BindingInterface::StorageBuffer& buffer : interface.storage_buffers)
    layout.storage_buffers.push_back({buffer.name, buffer.binding, gl ? buffer.code_name : ""});
  return layout;
}

ShaderStageSource stage_source(codegen::GeneratedStage&& stage) {
  ShaderStageSource source;
  source.glsl = std::move(stage.glsl);
  source.spirv = std::move(stage.spirv);
  source.entry_point = std::move(stage.entry_point);
  source.name = std::move(stage.name);
  source.source_files = std::move(stage.source_files);
  return source;
}

}  // namespace

codegen::Target lane_target(Lane lane) {
  switch (lane) {
    case Lane::Gl: return codegen::Target::Gl;
    case Lane::Vk: return codegen::Target::Spirv;
    case Lane::VkHlsl: return codegen::Target::VkHlsl;
  }
  return codegen::Target::Spirv;
}

Result<ProgramDesc> program_for_lane(const hlsl::Module& module, Lane lane, const ProgramOptions& options,
                                     glsl::NonfiniteTrace* trace) {
  if (!module.ok())
    return fail(ErrorKind::UserInput, "the shader did not compile", module.sources.resolve({module.main_file, 0, 0}));
  if (Result<void> can = drawable(module, lane); !can) return fail(can.error());
  if (!module.entry_points.fragment)
    return fail(ErrorKind::UserInput,
                "the shader has no fragment entry point (#pragma fragment): a program needs one to draw",
                module.sources.resolve({module.main_file, 0, 0}));
  const codegen::Target target = lane_target(lane);
  auto generated = codegen::generate(module, target, options);
  if (!generated) return fail(generated.error());
  if (trace) *trace = std::move(generated->trace);
  ProgramDesc desc;
  desc.name = module.sources.name(module.main_file);
  desc.layout = program_layout(generated->interface, lane);
  desc.fullscreen = module.entry_points.vertex == nullptr;
  desc.clip_distances = module.reflection.clip_distances;
  if (lane != Lane::Gl)
    for (const hlsl::SpecializationConstant& constant : module.reflection.specialization_constants)
      if (auto given = options.specialization.find(constant.id); given != options.specialization.end())
        desc.specialization[constant.id] = specialization_word(given->second, constant.scalar);
  desc.fragment = stage_source(std::move(*generated->fragment));
  if (generated->vertex) {
    desc.vertex = stage_source(std::move(*generated->vertex));
    return desc;
  }
  // A full-screen pass: the shared vertex shader feeds its TEXCOORD0.
  auto vertex = codegen::fullscreen_vertex(target, module.reflection);
  if (!vertex) return fail(vertex.error());
  desc.vertex = stage_source(std::move(*vertex));
  return desc;
}

}  // namespace xshade::harness
