// xshade run: render on every lane, write the images, and compare the lanes.
//
// Until scenes exist the one thing the harness renders is the orientation test pattern.
#include <fmt/core.h>

#include <map>
#include <system_error>

#include "harness/cli/commands.h"
#include "harness/cli/lane_selection.h"
#include "harness/image_io.h"
#include "harness/test_pattern.h"

namespace xshade::cli {
namespace {

constexpr uint32_t kPatternSize = 256;
constexpr const char* kSceneName = "test_pattern";

}  // namespace

int run_run(const RunOptions& options) {
  auto lanes = resolve_lanes(options.selection);
  if (!lanes) {
    fmt::print(stderr, "xshade run: {}\n", lanes.error().to_string());
    return kBadInput;
  }
  std::error_code error;
  std::filesystem::create_directories(options.report_dir, error);
  if (error) {
    fmt::print(stderr, "xshade run: cannot create {}: {}\n", options.report_dir.string(), error.message());
    return kBadInput;
  }

  int exit_code = kPass;
  std::map<harness::Lane, harness::FloatImage> images;
  for (size_t i = 0; i < lanes->size(); ++i) {
    const harness::Lane lane = (*lanes)[i];
    const std::string_view name = harness::lane_name(lane);
    fmt::print("[{}/{}] {} on {}\n", i + 1, lanes->size(), kSceneName, name);
    std::fflush(stdout);
    auto backend = harness::create_backend(lane, {.validation = options.selection.validation});
    if (!backend) {
      fmt::print("  {}: unavailable: {}\n", name, backend.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    auto image = harness::test_pattern::render(**backend, lane, kPatternSize);
    if (!image) {
      fmt::print("  {}: render failed: {}\n", name, image.error().to_string());
      exit_code = kBackendError;
      continue;
    }
    for (const std::string& message : (*backend)->take_driver_messages()) {
      fmt::print("  {}: driver message: {}\n", name, message);
      if (exit_code == kPass) exit_code = kTestFailed;
    }
    const auto lane_dir = options.report_dir / std::string(name);
    std::filesystem::create_directories(lane_dir, error);
    for (auto written : {harness::write_png(*image, lane_dir / (std::string(kSceneName) + ".png")),
                         harness::write_exr(*image, lane_dir / (std::string(kSceneName) + ".exr"))}) {
      if (!written) {
        fmt::print(stderr, "xshade run: {}\n", written.error().to_string());
        exit_code = kBackendError;
      }
    }
    images.emplace(lane, std::move(*image));
  }

  // Every lane against the first one that rendered.
  if (images.size() > 1) {
    const auto& [first_lane, first] = *images.begin();
    for (const auto& [lane, image] : images) {
      if (lane == first_lane) continue;
      const harness::ImageDifference difference = harness::max_difference(first, image);
      if (harness::bitwise_equal(first, image)) {
        fmt::print("{}: {} and {} are bit-identical\n", kSceneName, harness::lane_name(first_lane),
                   harness::lane_name(lane));
      } else {
        fmt::print("{}: {} and {} differ: max {} at ({}, {}) channel {}\n", kSceneName,
                   harness::lane_name(first_lane), harness::lane_name(lane), difference.max,
                   difference.x, difference.y, difference.channel);
        if (exit_code == kPass) exit_code = kTestFailed;
      }
    }
  }
  fmt::print("images in {}\n", options.report_dir.string());
  return exit_code;
}

}  // namespace xshade::cli
