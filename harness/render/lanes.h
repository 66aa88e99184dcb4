// Lanes: the independent ways xshade runs one shader, each on its own backend.
#pragma once

#include <filesystem>

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "harness/backend/backend.h"
#include "harness/gl/gl_context.h"  // GlPlatform, gl_platform_name, parse_gl_platform
#include "harness/scene/lane.h"
#include "spirv/spirv_compiler.h"

namespace xshade::harness {

struct BackendOptions {
  bool validation = false;                    // Vulkan validation layer, when installed
  GlPlatform gl_platform = GlPlatform::Auto;  // how the gl lane gets its context (gl_context.h)
  // Mesa's on-disk shader cache, in this folder (xshade's own, never the user's): the drivers
  // load what they compiled before instead of compiling it again, and the gl lane keeps its
  // compile messages beside it (gl/compile_messages.h). Empty: the drivers cache nothing on disk.
  // Mesa's own keys hold its build and LLVM's, so a folder outlives neither. It is the process's
  // setting (an environment variable Mesa reads as a driver starts): the first backend decides,
  // and a user's MESA_SHADER_CACHE_DISABLE is kept.
  std::filesystem::path driver_cache{};
};

Result<std::unique_ptr<Backend>> create_backend(Lane lane, const BackendOptions& options = {});

// One shader stage written twice by hand, once per GLSL flavour (until the compiler writes both).
struct GlslStagePair {
  std::string gl;  // #version 450 core
  std::string vk;  // Vulkan GLSL
  std::string name;
};

// The stage in the form the lane's backend reads: GLSL text for gl, validated SPIR-V for vk.
// Hand-written GLSL has no vk-hlsl form: that lane fails.
Result<ShaderStageSource> stage_for_lane(Lane lane, spirv::Stage stage, const GlslStagePair& source);

}  // namespace xshade::harness
