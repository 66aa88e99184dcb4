// The --lane and --gl-platform options: a name that is not one is the command line's mistake
// (ErrorKind::Usage, exit 2), never the input's or the driver's.
#include "cli/lane_selection.h"

#include <gtest/gtest.h>

namespace xshade::cli {
namespace {

TEST(ResolveLanes, NamesEveryLaneOrTheOnesGiven) {
  auto every = resolve_lanes({});
  ASSERT_TRUE(every) << every.error().message;
  EXPECT_EQ(*every, harness::all_lanes());
  auto one = resolve_lanes({.lanes = {"vk"}});
  ASSERT_TRUE(one) << one.error().message;
  EXPECT_EQ(*one, std::vector<harness::Lane>{harness::Lane::Vk});
}

TEST(ResolveLanes, AnUnknownLaneIsTheCommandLinesMistake) {
  auto lanes = resolve_lanes({.lanes = {"gl", "dx12"}});
  ASSERT_FALSE(lanes);
  EXPECT_EQ(lanes.error().message, "unknown lane 'dx12' (lanes: gl, vk, vk-hlsl)");
  EXPECT_EQ(lanes.error().kind, ErrorKind::Usage);
  EXPECT_EQ(exit_code_of(lanes.error().kind), kBadInput);
}

TEST(ResolveLanes, AnUnknownGlPlatformIsTheCommandLinesMistake) {
  auto lanes = resolve_lanes({.lanes = {}, .validation = false, .gl_platform = "wayland"});
  ASSERT_FALSE(lanes);
  EXPECT_EQ(lanes.error().message, "unknown --gl-platform 'wayland' (auto, osmesa, egl)");
  EXPECT_EQ(lanes.error().kind, ErrorKind::Usage);
}

}  // namespace
}  // namespace xshade::cli
