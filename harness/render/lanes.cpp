#include "harness/render/lanes.h"

#include "harness/gl/gl_backend.h"
#include "harness/vulkan/vulkan_backend.h"

namespace xshade::harness {

Result<std::unique_ptr<Backend>> create_backend(Lane lane, const BackendOptions& options) {
  switch (lane) {
    case Lane::Gl: return create_gl_backend({.platform = options.gl_platform});
    case Lane::Vk:
    case Lane::VkHlsl: return create_vulkan_backend({.validation = options.validation});
  }
  return fail("unknown lane");
}

Result<ShaderStageSource> stage_for_lane(Lane lane, spirv::Stage stage, const GlslStagePair& source) {
  ShaderStageSource result;
  result.name = source.name;
  if (lane == Lane::Gl) {
    result.glsl = source.gl;
    return result;
  }
  if (lane == Lane::VkHlsl) return fail("hand-written GLSL cannot run on the vk-hlsl lane", {source.name});
  auto module = spirv::compile_vulkan_glsl(source.vk, stage, source.name);
  if (!module) return fail(module.error());
  result.spirv = std::move(module->words);
  return result;
}

}  // namespace xshade::harness
