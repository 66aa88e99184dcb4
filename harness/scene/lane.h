// The lanes by name: the independent ways xshade runs one shader (render/lanes.h makes each
// one's backend). Scenes, goldens and reports name lanes with these words and no others.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace xshade::harness {

enum class Lane {
  Gl,      // GLSL 4.50 core on OpenGL (llvmpipe) through OSMesa or EGL surfaceless
  Vk,      // Vulkan GLSL -> glslang -> SPIR-V on lavapipe
  VkHlsl,  // the hlsl_like source through glslang's own HLSL front end -> SPIR-V on lavapipe
};

std::string_view lane_name(Lane lane);
std::optional<Lane> parse_lane(std::string_view name);
const std::vector<Lane>& all_lanes();
// The lanes that run hand-written GLSL pairs: one per backend, gl and vk.
const std::vector<Lane>& glsl_pair_lanes();

}  // namespace xshade::harness
