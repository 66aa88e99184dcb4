// xshade info: what each lane runs on. Every report carries the same strings.
#include <fmt/core.h>

#include "harness/cli/commands.h"
#include "harness/cli/lane_selection.h"

namespace xshade::cli {

int run_info(const LaneSelection& selection) {
  auto lanes = resolve_lanes(selection);
  if (!lanes) {
    fmt::print(stderr, "xshade info: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  int exit_code = kPass;
  for (harness::Lane lane : *lanes) {
    auto backend = harness::create_backend(lane, backend_options(selection));
    if (!backend) {
      fmt::print("{}: unavailable: {}\n", harness::lane_name(lane), backend.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    const harness::DriverInfo& info = (*backend)->driver_info();
    fmt::print("{}: {}\n", harness::lane_name(lane), info.api);
    fmt::print("  renderer:    {}\n", info.renderer);
    fmt::print("  api version: {}\n", info.api_version);
    fmt::print("  driver:      {}\n", info.driver_version);
    fmt::print("  llvm:        {}\n", info.llvm_version.empty() ? "-" : info.llvm_version);
  }
  fmt::print("compiler: {}\n", spirv::compiler_version());
  return exit_code;
}

}  // namespace xshade::cli
