// The vk-hlsl target: glslang's own HLSL front end on the author's source, with xshade's bindings.
#include <algorithm>

#include "codegen/codegen_internal.h"
#include "spirv/hlsl_compiler.h"

namespace xshade::codegen {

Result<GeneratedStage> vk_hlsl_stage(const hlsl::Module& module, spirv::Stage stage, const std::string& entry) {
  const std::string& name = module.sources.name(module.main_file);
  spirv::HlslStage request;
  request.source = module.sources.text(module.main_file);
  request.source_name = name;
  request.stage = stage;
  request.entry_point = entry;
  for (const hlsl::MacroDefinition& macro : module.macros) request.defines.emplace_back(macro.name, macro.value);
  request.resolve_include = spirv::include_resolver(module.include_dirs);
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
  for (const hlsl::StageVariable& varying : declared.varyings)
    request.varying_locations[varying.semantic] = varying.location;
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
      return fail(
          ErrorKind::UserInput,
          "vk-hlsl lane: glslang's HLSL front end reads a [[vk::push_constant]] struct global as a member of "
          "$Global, where DXC and xshade's other targets make it a push-constant block; compile it with --target "
          "vk or spirv, or declare it as [[vk::push_constant]] ConstantBuffer<T>",
          {name, 0, 0});
    if (ours != resource.binding)
      return fail(ErrorKind::Internal,
                  "vk-hlsl lane: glslang binds '" + resource.name + "' at " + std::to_string(resource.binding) +
                      ", xshade's reflection " + (ours ? "at " + std::to_string(*ours) : std::string("not at all")),
                  {name, 0, 0});
  }
  GeneratedStage source;
  source.spirv = std::move(compiled->module.words);
  source.entry_point = entry;
  source.name = name;
  return source;
}

}  // namespace xshade::codegen
