#include "harness/lanes.h"

#include "harness/gl_backend.h"
#include "harness/lavapipe_backend.h"

namespace xshade::harness {

std::string_view lane_name(Lane lane) {
  switch (lane) {
    case Lane::Gl: return "gl";
    case Lane::Vk: return "vk";
    case Lane::VkHlsl: return "vk-hlsl";
  }
  return "?";
}

std::optional<Lane> parse_lane(std::string_view name) {
  for (Lane lane : all_lanes())
    if (lane_name(lane) == name) return lane;
  return std::nullopt;
}

const std::vector<Lane>& all_lanes() {
  static const std::vector<Lane> lanes{Lane::Gl, Lane::Vk, Lane::VkHlsl};
  return lanes;
}

const std::vector<Lane>& glsl_pair_lanes() {
  static const std::vector<Lane> lanes{Lane::Gl, Lane::Vk};
  return lanes;
}

Result<std::unique_ptr<Backend>> create_backend(Lane lane, const BackendOptions& options) {
  switch (lane) {
    case Lane::Gl: return create_gl_backend({.platform = options.gl_platform});
    case Lane::Vk:
    case Lane::VkHlsl: return create_lavapipe_backend({.validation = options.validation});
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
