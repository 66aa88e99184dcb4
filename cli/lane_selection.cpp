#include "cli/lane_selection.h"

namespace xshade::cli {

Result<std::vector<harness::Lane>> resolve_lanes(const LaneSelection& selection) {
  if (!harness::parse_gl_platform(selection.gl_platform))
    return fail(ErrorKind::Usage, "unknown --gl-platform '" + selection.gl_platform + "' (auto, osmesa, egl)");
  if (selection.lanes.empty()) return harness::all_lanes();
  std::vector<harness::Lane> lanes;
  for (const std::string& name : selection.lanes) {
    auto lane = harness::parse_lane(name);
    if (!lane) {
      std::string known;
      for (harness::Lane l : harness::all_lanes())
        known += std::string(known.empty() ? "" : ", ") + std::string(harness::lane_name(l));
      return fail(ErrorKind::Usage, "unknown lane '" + name + "' (lanes: " + known + ")");
    }
    lanes.push_back(*lane);
  }
  return lanes;
}

harness::BackendOptions backend_options(const LaneSelection& selection) {
  return {.validation = selection.validation,
          .gl_platform = harness::parse_gl_platform(selection.gl_platform).value_or(harness::GlPlatform::Auto)};
}

}  // namespace xshade::cli
