// Lanes: the independent ways xshade runs one shader, each on its own backend.
#pragma once

#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "harness/backend.h"

namespace xshade::harness {

enum class Lane {
  Gl,  // GLSL 4.50 core on OpenGL through OSMesa (llvmpipe)
  Vk,  // Vulkan GLSL -> glslang -> SPIR-V on lavapipe
};

std::string_view lane_name(Lane lane);
std::optional<Lane> parse_lane(std::string_view name);
const std::vector<Lane>& all_lanes();

struct BackendOptions {
  bool validation = false;  // Vulkan validation layer, when installed
};

Result<std::unique_ptr<Backend>> create_backend(Lane lane, const BackendOptions& options = {});

}  // namespace xshade::harness
