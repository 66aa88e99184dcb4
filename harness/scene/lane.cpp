#include "harness/scene/lane.h"

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

}  // namespace xshade::harness
