#include "harness/gate/result_json.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "harness/gate/lane_workers.h"

namespace xshade::harness {
namespace {

LaneResult full_lane() {
  LaneResult lane;
  lane.lane = "vk";
  lane.verdict = Verdict::Fail;
  lane.layers = {{"determinism", Verdict::Pass, "two renders are bit-identical"},
                 {"per_pixel", Verdict::Fail, "12 pixels"}};
  ImageMetrics metrics;
  metrics.max_difference = 0.25;
  metrics.max_x = 3;
  metrics.max_y = 4;
  metrics.psnr = std::numeric_limits<double>::infinity();
  metrics.failing_pixels = 12;
  metrics.max_steps = 7;
  metrics.worst_test = {0.5f, std::numeric_limits<float>::quiet_NaN(), 2.0f, 1.0f};
  metrics.worst_reference = {0.25f, 0.0f, 1.0f, 1.0f};
  metrics.first_failing = std::pair{5u, 6u};
  metrics.hdr_values = 9;
  metrics.float_max_relative = 0.01;
  metrics.metric = MetricFigures{"flip", 0.002, 0.0005, {{"mean", 0.002}, {"max", 0.4}}};
  lane.against_golden = metrics;
  lane.non_finite = {1, 2, 3, std::pair{7u, 8u}};
  lane.image = "scene/vk.png";
  lane.golden = "scene/vk.golden.png";
  lane.golden_exr = "scene/vk.golden.exr";
  lane.diff = "scene/vk.diff.png";
  lane.timings = {{"scene", 1.5}, {"bokeh", 2.25}};
  lane.seconds = 0.75;
  lane.driver = {"Vulkan 1.3 (lavapipe)", "llvmpipe (LLVM 15.0.6, 256 bits)", "1.3.230", "Mesa 22.3.6", "15.0.6"};
  lane.message = "per_pixel: 12 pixels\nsecond line";
  return lane;
}

TEST(LaneResultJson, ReadsBackWhatItWrote) {
  const LaneResult lane = full_lane();
  // Through text, as a worker hands it over.
  auto read = lane_from_json(nlohmann::json::parse(lane_to_json(lane).dump()));
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_EQ(read->lane, "vk");
  EXPECT_EQ(read->verdict, Verdict::Fail);
  ASSERT_EQ(read->layers.size(), 2u);
  EXPECT_EQ(read->layers[1].layer, "per_pixel");
  EXPECT_EQ(read->layers[1].verdict, Verdict::Fail);
  ASSERT_TRUE(read->against_golden);
  EXPECT_EQ(read->against_golden->max_difference, 0.25);
  EXPECT_EQ(read->against_golden->max_steps, 7u);
  EXPECT_EQ(read->against_golden->first_failing, (std::pair{5u, 6u}));
  EXPECT_TRUE(std::isinf(read->against_golden->psnr)) << "identical images' PSNR is infinite, written as null";
  EXPECT_EQ(read->against_golden->hdr_values, 9u);
  EXPECT_EQ(read->against_golden->worst_test[0], 0.5f);
  EXPECT_TRUE(std::isnan(read->against_golden->worst_test[1])) << "a NaN value is written as null";
  EXPECT_EQ(read->against_golden->worst_reference, (std::array<float, 4>{0.25f, 0.0f, 1.0f, 1.0f}));
  ASSERT_TRUE(read->against_golden->metric);
  EXPECT_EQ(read->against_golden->metric->name, "flip");
  EXPECT_EQ(read->against_golden->metric->value, 0.002);
  EXPECT_EQ(read->against_golden->metric->threshold, 0.0005);
  EXPECT_EQ(read->against_golden->metric->figures.size(), 2u);
  EXPECT_EQ(read->golden_exr, "scene/vk.golden.exr");
  EXPECT_EQ(read->non_finite.negative, 3u);
  EXPECT_EQ(read->non_finite.first, (std::pair{7u, 8u}));
  EXPECT_EQ(read->diff, "scene/vk.diff.png");
  ASSERT_EQ(read->timings.size(), 2u);
  EXPECT_EQ(read->timings[1].milliseconds, 2.25);
  EXPECT_EQ(read->driver.llvm_version, "15.0.6");
  EXPECT_EQ(read->message, lane.message);
}

TEST(LaneResultJson, AFieldMissingIsAnInternalErrorNamingIt) {
  nlohmann::json json = lane_to_json(full_lane());
  json.erase("verdict");
  auto read = lane_from_json(json);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().kind, ErrorKind::Internal);
  EXPECT_NE(read.error().message.find("'verdict'"), std::string::npos) << read.error().message;
  EXPECT_FALSE(lane_from_json(nlohmann::json::array()));
}

// A report merge once took a lane named "dx12" and left it out of every check between lanes.
TEST(LaneResultJson, ALaneXshadeDoesNotHaveIsRefused) {
  nlohmann::json json = lane_to_json(full_lane());
  json["lane"] = "dx12";
  auto read = lane_from_json(json);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().kind, ErrorKind::UserInput);
  EXPECT_EQ(read.error().message, "a lane's result names the lane 'dx12', which xshade does not have");
}

TEST(DriverThreads, TheWorkersShareTheCoresOnceAndEachHasOne) {
  EXPECT_EQ(driver_threads_per_worker(8, 2), 4u);
  EXPECT_EQ(driver_threads_per_worker(2, 2), 1u);
  EXPECT_EQ(driver_threads_per_worker(2, 1), 2u);
  EXPECT_EQ(driver_threads_per_worker(2, 8), 1u);
  EXPECT_EQ(driver_threads_per_worker(4, 0), 4u);
}

}  // namespace
}  // namespace xshade::harness
