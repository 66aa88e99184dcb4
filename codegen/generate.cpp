#include "codegen/generate.h"

#include "codegen/codegen_internal.h"
#include "glsl/flavour.h"

namespace xshade::codegen {
namespace {

SourceLocation whole_module(const hlsl::Module& module) { return module.sources.resolve({module.main_file, 0, 0}); }

// The code filters its 2D comparison reads itself: the vk flavour's, when asked. OpenGL's driver
// filters a depth texture; vk-hlsl is glslang's code of the source, which cannot.
bool filters_in_code(Target target, const GenerateOptions& options) {
  return options.filter_comparisons && (target == Target::Vk || target == Target::Spirv);
}

// The names the target's code gives the module's resources (the emitter's, or glslang's for
// vk-hlsl, which keeps the HLSL names but for the loose globals' block), and where they are bound.
BindingInterface binding_interface(const hlsl::Reflection& reflection, Target target,
                                   const glsl::DeclaredNames* glsl_names, const GenerateOptions& options) {
  const auto code_name = [&](const std::map<std::string, std::string> glsl::DeclaredNames::*kind,
                             const std::string& name) {
    if (!glsl_names) return name == hlsl::kGlobalsBufferName ? std::string("$Global") : name;
    const auto& names = glsl_names->*kind;
    const auto found = names.find(name);
    return found == names.end() ? name : found->second;
  };
  BindingInterface interface;
  const bool vulkan = target != Target::Gl;
  for (const hlsl::ConstantBuffer& buffer : reflection.constant_buffers)
    interface.uniform_blocks.push_back({buffer.name, code_name(&glsl::DeclaredNames::blocks, buffer.name),
                                        buffer.binding, buffer.size, buffer.push_constant && vulkan});
  for (const hlsl::TextureResource& texture : reflection.textures) {
    if (!texture.used) continue;
    BindingInterface::Texture slot;
    slot.name = texture.name;
    slot.code_name = code_name(&glsl::DeclaredNames::textures, texture.name);
    slot.binding = texture.binding;
    slot.shape = texture.shape;
    slot.texel = texture.texel;
    slot.comparison = texture.comparison;
    slot.filtered_in_shader =
        texture.comparison && texture.shape == hlsl::TextureShape::Tex2D && filters_in_code(target, options);
    if (vulkan && texture.kind == hlsl::TextureKind::Texture) {
      // A Texture object is a sampled image on Vulkan; its sampler, if any, is a binding of its
      // own, or the texture's ([[vk::binding]] of both at one: a combined image sampler).
      slot.sampler_binding = texture.sampler_binding;
      slot.image_only = !texture.sampler_binding;
      if (texture.sampler_binding == texture.binding) slot.sampler_binding = std::nullopt;
    }
    interface.textures.push_back(std::move(slot));
  }
  for (const hlsl::StorageBufferResource& buffer : reflection.buffers)
    if (buffer.used)
      interface.storage_buffers.push_back(
          {buffer.name, code_name(&glsl::DeclaredNames::storage_blocks, buffer.name), buffer.binding});
  return interface;
}

Result<void> vk_hlsl_can_take(const hlsl::Module& module, const GenerateOptions& options) {
  if (options.half_emulation)
    return fail(ErrorKind::Usage,
                "half emulation rewrites the GLSL xshade emits; the vk-hlsl lane compiles the source with glslang and "
                "cannot emulate half",
                whole_module(module));
  if (options.trace_nonfinite)
    return fail(
        ErrorKind::Usage,
        "tracing non-finite values instruments the GLSL xshade emits; the vk-hlsl lane compiles the source with "
        "glslang's HLSL front end and cannot be traced (trace gl or vk)",
        whole_module(module));
  return {};
}

Result<Generated> generate_vk_hlsl(const hlsl::Module& module, const GenerateOptions& options) {
  if (Result<void> can = vk_hlsl_can_take(module, options); !can) return fail(can.error());
  Generated generated;
  for (const bool vertex : {true, false}) {
    if (!(vertex ? module.entry_points.vertex : module.entry_points.fragment)) continue;
    auto stage = vk_hlsl_stage(module, vertex ? spirv::Stage::Vertex : spirv::Stage::Fragment,
                               vertex ? module.reflection.vertex_entry : module.reflection.fragment_entry);
    if (!stage) {
      if (!spirv::is_spirv_validation_failure(stage.error())) return fail(stage.error());
      // What glslang refuses is the author's HLSL (or a known divergence, docs/divergences.md); a
      // module spirv-val refuses is xshade's (the resolver, the offsets it mends, whether it legalizes).
      Error error = stage.error();
      error.kind = ErrorKind::Internal;
      error.message =
          "internal error: the SPIR-V glslang made of the shader for --target vk-hlsl is not valid (spirv-val "
          "refuses it). This is a bug in xshade, not in the shader: please report it with the shader and "
          "what follows.";
      return fail(std::move(error));
    }
    (vertex ? generated.vertex : generated.fragment) = std::move(*stage);
  }
  generated.interface = binding_interface(module.reflection, Target::VkHlsl, nullptr, options);
  return generated;
}

Result<Generated> generate_glsl(const hlsl::Module& module, Target target, const GenerateOptions& options) {
  auto emitted = glsl::emit(module, {.flavour = target == Target::Gl ? glsl::Flavour::Gl : glsl::Flavour::Vk,
                                     .half_emulation = options.half_emulation,
                                     .trace_nonfinite = options.trace_nonfinite,
                                     .trace_program = options.trace_program,
                                     .filter_comparisons = filters_in_code(target, options),
                                     .specialization = options.specialization});
  if (!emitted) return fail(emitted.error());  // a construct the flavour cannot express: the author's
  Generated generated;
  generated.trace = std::move(emitted->trace);
  generated.interface = binding_interface(module.reflection, target, &emitted->names, options);
  const std::string name = module.sources.name(module.main_file);
  for (const spirv::Stage stage : {spirv::Stage::Vertex, spirv::Stage::Fragment}) {
    const bool vertex = stage == spirv::Stage::Vertex;
    std::optional<glsl::EmittedStage>& emitted_stage = vertex ? emitted->vertex : emitted->fragment;
    if (!emitted_stage) continue;
    GeneratedStage out;
    out.name = name + (vertex ? ".vert" : ".frag");
    out.source_files = emitted->source_files;
    if (target != Target::Gl || options.check_gl) {
      auto words = validate_generated_glsl(target, stage, emitted_stage->text, out.name, out.source_files);
      if (!words) return fail(words.error());
      out.spirv = std::move(*words);
    }
    if (target != Target::Spirv) out.glsl = std::move(emitted_stage->text);
    (vertex ? generated.vertex : generated.fragment) = std::move(out);
  }
  return generated;
}

}  // namespace

std::string_view target_name(Target target) {
  switch (target) {
    case Target::Gl: return "gl";
    case Target::Vk: return "vk";
    case Target::Spirv: return "spirv";
    case Target::VkHlsl: return "vk-hlsl";
  }
  return "vk";
}

std::optional<Target> target_named(std::string_view name) {
  for (const Target target : {Target::Gl, Target::Vk, Target::Spirv, Target::VkHlsl})
    if (target_name(target) == name) return target;
  return std::nullopt;
}

bool makes_spirv(Target target) { return target == Target::Spirv || target == Target::VkHlsl; }

Result<Generated> generate(const hlsl::Module& module, Target target, const GenerateOptions& options) {
  if (!module.ok()) return fail(ErrorKind::UserInput, "the shader did not compile", whole_module(module));
  if (!module.entry_points.vertex && !module.entry_points.fragment) return Generated{};
  // vk-hlsl refuses what it cannot take before it compiles anything, so the message is the same
  // whichever stages the module has.
  auto generated =
      target == Target::VkHlsl ? generate_vk_hlsl(module, options) : generate_glsl(module, target, options);
  if (!generated) return fail(generated.error());
  return generated;
}

Result<GeneratedStage> fullscreen_vertex(Target target, const hlsl::Reflection& reflection) {
  GeneratedStage stage;
  stage.name = "fullscreen.vert";
  const std::string text =
      glsl::fullscreen_vertex_shader(target == Target::Gl ? glsl::Flavour::Gl : glsl::Flavour::Vk, reflection);
  if (!makes_spirv(target)) {
    stage.glsl = text;
    return stage;
  }
  auto words = spirv::compile_vulkan_glsl(text, spirv::Stage::Vertex, stage.name);
  if (!words) return fail(words.error());
  stage.spirv = std::move(words->words);
  return stage;
}

}  // namespace xshade::codegen
