#include "harness/cli/lane_selection.h"

namespace xshade::cli {

Result<std::vector<harness::Lane>> resolve_lanes(const LaneSelection& selection) {
  if (selection.lanes.empty()) return harness::all_lanes();
  std::vector<harness::Lane> lanes;
  for (const std::string& name : selection.lanes) {
    auto lane = harness::parse_lane(name);
    if (!lane) {
      std::string known;
      for (harness::Lane l : harness::all_lanes()) known += std::string(known.empty() ? "" : ", ") + std::string(harness::lane_name(l));
      return fail("unknown lane '" + name + "' (lanes: " + known + ")");
    }
    lanes.push_back(*lane);
  }
  return lanes;
}

}  // namespace xshade::cli
