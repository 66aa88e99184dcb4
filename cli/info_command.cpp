// xshade info: what each lane runs on (every report carries the same strings), and which folders
// a run here would use.
#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>

#include "cli/command_options.h"
#include "cli/commands.h"
#include "cli/lane_selection.h"

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

  const OwnFolders& own = own_folders();
  fmt::print("xshade {}: shader library {} ({})\n", XSHADE_VERSION, own.shaders.string(),
             own.installed ? "installed" : "the source tree of this build");
  auto folders = resolve_folders({}, std::filesystem::current_path(), GoldenUse::None);
  if (!folders) {
    fmt::print(stderr, "xshade info: {}\n", folders.error().to_string());
    return kBadInput;
  }
  fmt::print("project file: {}\n",
             folders->project_file.empty() ? "none (xshade's own scenes and goldens)" : folders->project_file.string());
  fmt::print("  scenes:  {}\n", folders->scenes.string());
  fmt::print("  golden:  {}\n", folders->golden.empty() ? "not set" : folders->golden.string());
  fmt::print("  shaders: {}\n", folders->shaders.describe());
  return exit_code;
}

Verb add_info_command(CLI::App& app) {
  auto options = std::make_shared<LaneSelection>();
  CLI::App* info = app.add_subcommand(
      "info",
      "Print each lane's driver (route, renderer, API, Mesa and LLVM versions) and the folders a run here "
      "would use (the project file's, xshade's own)");
  add_lane_options(*info, *options);
  return {info, [options](const std::string&) { return run_info(*options); }};
}

}  // namespace xshade::cli
