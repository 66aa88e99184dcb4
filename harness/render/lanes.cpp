#include "harness/render/lanes.h"

#include <cstdlib>

#include "harness/gl/gl_backend.h"
#include "harness/vulkan/vulkan_backend.h"

namespace xshade::harness {

namespace {

// Mesa reads these as each driver starts: the folder (always ours when there is one), and the
// switch (a user's, when set; off when there is no folder, so that nothing the drivers compiled
// in another run is loaded without its messages).
void set_driver_cache(const std::filesystem::path& folder) {
  if (folder.empty()) {
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
    return;
  }
  setenv("MESA_SHADER_CACHE_DIR", folder.c_str(), 1);
  setenv("MESA_SHADER_CACHE_DISABLE", "false", 0);
}

}  // namespace

Result<std::unique_ptr<Backend>> create_backend(Lane lane, const BackendOptions& options) {
  set_driver_cache(options.driver_cache);
  switch (lane) {
    case Lane::Gl:
      return create_gl_backend({.platform = options.gl_platform,
                                .compile_messages = options.driver_cache.empty()
                                                        ? std::filesystem::path()
                                                        : options.driver_cache / "compile_messages"});
    case Lane::Vk:
    case Lane::VkHlsl: return create_vulkan_backend({.validation = options.validation});
  }
  return fail(ErrorKind::Internal, "unknown lane");
}

Result<ShaderStageSource> stage_for_lane(Lane lane, spirv::Stage stage, const GlslStagePair& source) {
  ShaderStageSource result;
  result.name = source.name;
  if (lane == Lane::Gl) {
    result.glsl = source.gl;
    return result;
  }
  if (lane == Lane::VkHlsl)
    return fail(ErrorKind::Internal, "hand-written GLSL cannot run on the vk-hlsl lane", {source.name});
  auto module = spirv::compile_vulkan_glsl(source.vk, stage, source.name);
  if (!module) return fail(module.error());
  result.spirv = std::move(module->words);
  return result;
}

}  // namespace xshade::harness
