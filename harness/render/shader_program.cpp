#include "harness/render/shader_program.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <map>

#include "glsl/flavour.h"
#include "glsl/glsl_emitter.h"
#include "glsl/glsl_names.h"
#include "spirv/hlsl_compiler.h"

namespace xshade::harness {
namespace {

// Driver logs name sources by the number `#line` gave them; these become the author's files.
Error with_source_names(Error error, const std::vector<std::string>& source_files) {
  for (Diagnostic& diagnostic : error.diagnostics) {
    uint32_t index = 0;
    const std::string& file = diagnostic.where.file;
    if (!file.empty() && file.find_first_not_of("0123456789") == std::string::npos) index = uint32_t(std::stoul(file));
    if (index > 0 && index < source_files.size()) diagnostic.where.file = source_files[index];
  }
  return error;
}

Result<ShaderStageSource> vk_hlsl_stage(const hlsl::Module& module, spirv::Stage stage, const std::string& entry,
                                        const std::vector<std::filesystem::path>& include_dirs) {
  const std::string& name = module.sources.name(module.main_file);
  spirv::HlslStage request;
  request.source = module.sources.text(module.main_file);
  request.source_name = name;
  request.stage = stage;
  request.entry_point = entry;
  for (const hlsl::MacroDefinition& macro : module.macros) request.defines.emplace_back(macro.name, macro.value);
  request.resolve_include = spirv::include_resolver(include_dirs);
  // A resource read through a local or a struct field (resource_origins.h) needs glslang's
  // legalization; a global or a parameter does not.
  for (const auto& [expr, leaves] : module.resource_origins) {
    if (expr->kind == hlsl::ExprKind::Name) {
      const hlsl::Decl* decl = static_cast<const hlsl::NameExpr*>(expr)->decl;
      if (decl && decl->kind == hlsl::DeclKind::Var && !static_cast<const hlsl::VarDecl*>(decl)->is_global)
        request.legalize = true;
    } else if (expr->kind == hlsl::ExprKind::Member) {
      request.legalize = true;
    }
  }
  request.storage_buffers = !module.reflection.buffers.empty();
  // Resources without a register are numbered once for the whole program, by xshade's reflection
  // (glslang alone would number each stage on its own; see HlslStage::bindings).
  const hlsl::Reflection& declared = module.reflection;
  for (const hlsl::ConstantBuffer& buffer : declared.constant_buffers) {
    const std::string glslang_name = buffer.name == hlsl::kGlobalsBufferName ? "$Global" : buffer.name;
    request.bindings[glslang_name] = buffer.binding;
    // The bytes the harness writes follow HLSL's packing; glslang lays the globals out otherwise.
    for (const hlsl::ConstantBufferMember& member : buffer.members)
      request.member_offsets[glslang_name][member.name] = member.offset;
  }
  for (const hlsl::TextureResource& texture : declared.textures) request.bindings[texture.name] = texture.binding;
  for (const hlsl::SamplerResource& sampler : declared.samplers) request.bindings[sampler.name] = sampler.binding;
  for (const hlsl::StorageBufferResource& buffer : declared.buffers) request.bindings[buffer.name] = buffer.binding;
  for (const hlsl::StageVariable& varying : declared.varyings) request.varying_locations[varying.semantic] = varying.location;
  for (const hlsl::StageVariable& input : declared.vertex_inputs)
    request.vertex_input_locations[input.semantic] = input.location;
  auto compiled = spirv::compile_hlsl(request);
  if (!compiled) return fail(compiled.error());

  // glslang numbers the resources itself; they must be where xshade's reflection says.
  const hlsl::Reflection& reflection = module.reflection;
  for (const spirv::HlslResource& resource : compiled->resources) {
    std::optional<uint32_t> ours;
    std::string resource_name = resource.name == "$Global" ? hlsl::kGlobalsBufferName : resource.name;
    // glslang reflects each element of an array of blocks (ubo[0], ubo[1]) at the array's binding.
    if (const size_t open = resource_name.rfind('['); open != std::string::npos && resource_name.back() == ']')
      resource_name.erase(open);
    if (resource.kind == spirv::HlslResource::Kind::ConstantBuffer) {
      if (const auto* buffer = reflection.find_constant_buffer(resource_name)) {
        // A push-constant block has no binding.
        if (buffer->push_constant && resource.push_constant) continue;
        ours = buffer->binding;
      }
    } else if (resource.kind == spirv::HlslResource::Kind::Sampler) {
      for (const auto& sampler : reflection.samplers)
        if (sampler.name == resource_name) ours = sampler.binding;
    } else {
      for (const auto& texture : reflection.textures)
        if (texture.name == resource_name) ours = texture.binding;
    }
    // glslang reflects a structured buffer as a block, a typed buffer as a texture.
    for (const auto& buffer : reflection.buffers)
      if (buffer.name == resource_name) ours = buffer.binding;
    const bool push_constant_in_globals =
        resource.name == "$Global" && !ours &&
        std::any_of(reflection.constant_buffers.begin(), reflection.constant_buffers.end(),
                    [](const hlsl::ConstantBuffer& buffer) { return buffer.push_constant; });
    if (push_constant_in_globals)
      return fail("vk-hlsl lane: glslang's HLSL front end reads a [[vk::push_constant]] struct global as a member of "
                  "$Global, where DXC and xshade's other targets make it a push-constant block; compile it with --target "
                  "vk or spirv, or declare it as [[vk::push_constant]] ConstantBuffer<T>",
                  {name, 0, 0});
    if (ours != resource.binding)
      return fail("vk-hlsl lane: glslang binds '" + resource.name + "' at " + std::to_string(resource.binding) +
                      ", xshade's reflection " + (ours ? "at " + std::to_string(*ours) : std::string("not at all")),
                  {name, 0, 0});
  }
  ShaderStageSource source;
  source.spirv = std::move(compiled->module.words);
  source.entry_point = entry;
  source.name = name;
  return source;
}

// The lanes whose GLSL filters 2D comparison reads in the shader when a program's comparison
// samplers filter linearly (ProgramOptions::filter_comparisons).
bool filters_comparisons_in_shader(Lane lane, const ProgramOptions& options) {
  return options.filter_comparisons && lane == Lane::Vk;
}

}  // namespace

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


ProgramLayout layout_for_lane(const hlsl::Reflection& reflection, Lane lane, const ProgramOptions& options) {
  ProgramLayout layout;
  for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers)
    layout.uniform_blocks.push_back(
        {glsl::block_name(buffer.name), buffer.binding, buffer.size, buffer.push_constant && lane != Lane::Gl});
  for (const hlsl::TextureResource& texture : reflection.textures) {
    if (!texture.used) continue;
    TextureSlot slot{texture.name, texture.binding, std::nullopt};
    slot.shape = harness_shape(texture.shape);
    slot.comparison = texture.comparison;
    slot.filtered_in_shader = texture.comparison && texture.shape == hlsl::TextureShape::Tex2D &&
                              filters_comparisons_in_shader(lane, options);
    slot.texel = harness_texel(texture.texel);
    if (lane == Lane::Gl && glsl::needs_renaming(texture.name)) slot.glsl_name = glsl::renamed(texture.name);
    if (lane != Lane::Gl && texture.kind == hlsl::TextureKind::Texture) {
      // A Texture object is a sampled image on Vulkan; its sampler, if any, is a binding of its
      // own, or the texture's ([[vk::binding]] of both at one: a combined image sampler).
      slot.sampler_binding = texture.sampler_binding;
      slot.image_only = !texture.sampler_binding;
      if (texture.sampler_binding == texture.binding) slot.sampler_binding = std::nullopt;
    }
    layout.textures.push_back(std::move(slot));
  }
  for (const hlsl::StorageBufferResource& buffer : reflection.buffers)
    if (buffer.used) layout.storage_buffers.push_back({buffer.name, buffer.binding, glsl::buffer_block_name(buffer.name)});
  return layout;
}

Result<LaneStages> stages_for_lane(const hlsl::Module& module, Lane lane, const ProgramOptions& options) {
  if (!module.ok()) return fail("the shader did not compile", module.sources.resolve({module.main_file, 0, 0}));
  if (!module.entry_points.vertex && !module.entry_points.fragment)
    return fail("the shader has no entry point (#pragma vertex or #pragma fragment)",
                module.sources.resolve({module.main_file, 0, 0}));
  LaneStages stages;
  if (lane == Lane::VkHlsl) {
    if (options.half_emulation)
      return fail("half emulation rewrites the GLSL xshade emits; the vk-hlsl lane compiles the source with glslang and "
                  "cannot emulate half",
                  module.sources.resolve({module.main_file, 0, 0}));
    if (options.trace_nonfinite)
      return fail("tracing non-finite values instruments the GLSL xshade emits; the vk-hlsl lane compiles the source with "
                  "glslang's HLSL front end and cannot be traced (trace gl or vk)",
                  module.sources.resolve({module.main_file, 0, 0}));
    for (const bool vertex : {true, false}) {
      if (!(vertex ? module.entry_points.vertex : module.entry_points.fragment)) continue;
      auto stage = vk_hlsl_stage(module, vertex ? spirv::Stage::Vertex : spirv::Stage::Fragment,
                                 vertex ? module.reflection.vertex_entry : module.reflection.fragment_entry,
                                 module.include_dirs);
      if (!stage) return fail(stage.error());
      (vertex ? stages.vertex : stages.fragment) = std::move(*stage);
    }
    return stages;
  }
  const glsl::Flavour flavour = lane == Lane::Gl ? glsl::Flavour::Gl : glsl::Flavour::Vk;
  auto emitted = glsl::emit(module, {.flavour = flavour,
                                     .half_emulation = options.half_emulation,
                                     .trace_nonfinite = options.trace_nonfinite,
                                     .trace_program = options.trace_program,
                                     .filter_comparisons = filters_comparisons_in_shader(lane, options),
                                     .specialization = options.specialization});
  if (!emitted) return fail(emitted.error());
  stages.trace = std::move(emitted->trace);
  const std::string name = module.sources.name(module.main_file);
  for (const bool vertex : {true, false}) {
    const std::optional<glsl::EmittedStage>& emitted_stage = vertex ? emitted->vertex : emitted->fragment;
    if (!emitted_stage) continue;
    ShaderStageSource source;
    source.name = name + (vertex ? ".vert" : ".frag");
    source.source_files = emitted->source_files;
    if (lane == Lane::Gl) {
      source.glsl = emitted_stage->text;
    } else {
      auto words = spirv::compile_vulkan_glsl(emitted_stage->text, vertex ? spirv::Stage::Vertex : spirv::Stage::Fragment,
                                              source.name);
      if (!words) {
        // glslang refusing the GLSL xshade wrote is xshade's fault, whatever the shader says.
        Error refused = with_source_names(words.error(), emitted->source_files);
        refused.kind = ErrorKind::Internal;
        return fail(std::move(refused));
      }
      source.spirv = std::move(words->words);
    }
    (vertex ? stages.vertex : stages.fragment) = std::move(source);
  }
  return stages;
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
    const auto constant = std::find_if(reflection.specialization_constants.begin(), reflection.specialization_constants.end(),
                                       [&](const hlsl::SpecializationConstant& c) { return c.name == name; });
    if (equals == std::string::npos || constant == reflection.specialization_constants.end())
      return fail("--specialize " + text + ": expected NAME=VALUE naming a [[vk::constant_id]] constant of the shader (" +
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
      return fail("--specialize " + text + ": '" + name + "' is of type " + hlsl::scalar_name(constant->scalar) +
                  "; give it " +
                  (constant->scalar == hlsl::ScalarType::Bool ? std::string("0 or 1")
                   : whole                                     ? "a whole number in its range"
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
    return fail(what + "; `xshade compile` writes it as the source asks, but the harness cannot draw it", where);
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
      return refuse("'" + texture.name + "' is a subpass input, which a scene cannot give yet (on Vulkan an input "
                    "attachment; the gl target reads the texture bound at its binding at the fragment's pixel)");
  }
  for (const hlsl::StorageBufferResource& buffer : reflection.buffers) {
    if (!buffer.used) continue;
    if (buffer.set != 0) return refuse("'" + buffer.name + "' is in descriptor set " + std::to_string(buffer.set));
    if (buffer.kind == hlsl::BufferKind::Buffer && lane == Lane::VkHlsl)
      return refuse("'" + buffer.name + "' is a Buffer<T>, which glslang's HLSL front end reads as a uniform texel "
                    "buffer, and the harness binds read-only buffers as storage buffers (the gl and vk lanes read it so)");
  }
  for (const hlsl::SamplerResource& sampler : reflection.samplers) {
    if (!sampler.used) continue;
    if (sampler.set != 0) return refuse("'" + sampler.name + "' is in descriptor set " + std::to_string(sampler.set));
    if (sampler.count > 1) return refuse(array_of_resources(sampler.name, sampler.count));
  }
  if (reflection.reads_shading_rate && lane != Lane::Gl)
    return refuse("it reads SV_ShadingRate, and lavapipe has no variable-rate shading (VK_KHR_fragment_shading_rate); "
                  "the gl lane reads 0, OpenGL's one rate (1x1)");
  for (const hlsl::StageVariable& input : reflection.vertex_inputs) {
    const std::optional<uint32_t> fed = hlsl::vertex_input_location(input.semantic);
    if (input.given_location && fed != input.given_location)
      return refuse("vertex input " + input.semantic + " is at [[vk::location(" + std::to_string(*input.given_location) +
                    ")]], where the meshes feed " + (fed ? "location " + std::to_string(*fed) : "nothing") +
                    " (docs/hlsl_like.md, section 8)");
  }
  return {};
}

Result<ProgramDesc> program_for_lane(const hlsl::Module& module, Lane lane, const ProgramOptions& options,
                                     glsl::NonfiniteTrace* trace) {
  if (!module.ok()) return fail("the shader did not compile", module.sources.resolve({module.main_file, 0, 0}));
  if (Result<void> can = drawable(module, lane); !can) return fail(can.error());
  if (!module.entry_points.fragment)
    return fail("the shader has no fragment entry point (#pragma fragment): a program needs one to draw",
                module.sources.resolve({module.main_file, 0, 0}));
  auto stages = stages_for_lane(module, lane, options);
  if (!stages) return fail(stages.error());
  if (trace) *trace = std::move(stages->trace);
  ProgramDesc desc;
  desc.name = module.sources.name(module.main_file);
  desc.layout = layout_for_lane(module.reflection, lane, options);
  desc.fullscreen = module.entry_points.vertex == nullptr;
  desc.clip_distances = module.reflection.clip_distances;
  if (lane != Lane::Gl)
    for (const hlsl::SpecializationConstant& constant : module.reflection.specialization_constants)
      if (auto given = options.specialization.find(constant.id); given != options.specialization.end())
        desc.specialization[constant.id] = specialization_word(given->second, constant.scalar);
  desc.fragment = std::move(*stages->fragment);
  if (stages->vertex) {
    desc.vertex = std::move(*stages->vertex);
    return desc;
  }
  // A full-screen pass: the shared vertex shader feeds its TEXCOORD0.
  const glsl::Flavour flavour = lane == Lane::Gl ? glsl::Flavour::Gl : glsl::Flavour::Vk;
  const std::string text = glsl::fullscreen_vertex_shader(flavour, module.reflection);
  desc.vertex.name = "fullscreen.vert";
  if (lane == Lane::Gl) {
    desc.vertex.glsl = text;
  } else {
    auto words = spirv::compile_vulkan_glsl(text, spirv::Stage::Vertex, desc.vertex.name);
    if (!words) return fail(words.error());
    desc.vertex.spirv = std::move(words->words);
  }
  return desc;
}

}  // namespace xshade::harness
