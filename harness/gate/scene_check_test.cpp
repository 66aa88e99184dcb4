// The gate's decisions fed what must fail them: a render that differs from the one before,
// lanes that disagree, a scene whose lanes did not all pass.
#include "harness/gate/scene_check.h"

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

FloatImage flat(float value, uint32_t size = 4) {
  FloatImage image(size, size);
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = (i % 4 == 3) ? 1.0f : value;
  return image;
}

TEST(Determinism, PassesOnlyBitIdenticalRenders) {
  EXPECT_EQ(determinism_layer(flat(0.5f), flat(0.5f)).verdict, Verdict::Pass);
  FloatImage drifted = flat(0.5f);
  drifted.rgba[4 * 5 + 1] = std::nextafter(0.5f, 1.0f);  // one ulp in one channel of pixel (1, 1)
  const LayerResult layer = determinism_layer(flat(0.5f), drifted);
  EXPECT_EQ(layer.verdict, Verdict::Fail);
  EXPECT_NE(layer.detail.find("at (1, 1)"), std::string::npos) << layer.detail;
}

TEST(CrossLane, EachLaneIsHeldAgainstTheFirstNotAgainstItself) {
  std::map<Lane, FloatImage> images;
  images.emplace(Lane::Gl, flat(0.5f));
  images.emplace(Lane::Vk, flat(0.5f));
  images.emplace(Lane::VkHlsl, flat(0.25f));  // many sRGB steps darker
  const std::vector<LanePairComparison> pairs = compare_lane_images(images, CompareSettings{});
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].first, Lane::Gl);
  EXPECT_EQ(pairs[0].second, Lane::Vk);
  EXPECT_EQ(pairs[0].comparison.verdict, Verdict::Pass);
  EXPECT_EQ(pairs[1].second, Lane::VkHlsl);
  EXPECT_EQ(pairs[1].comparison.verdict, Verdict::Fail);
  EXPECT_EQ(pairs[1].comparison.metrics.failing_pixels, 16u);
}

TEST(CrossLane, OneLaneHasNothingToCompare) {
  std::map<Lane, FloatImage> images;
  images.emplace(Lane::Gl, flat(0.5f));
  EXPECT_TRUE(compare_lane_images(images, CompareSettings{}).empty());
}

TEST(Bless, RefusesLanesThatDisagreeOrDidNotPass) {
  SceneResult agreeing;
  agreeing.scene = "s";
  agreeing.lanes = {LaneResult{}, LaneResult{}};
  agreeing.lanes[0].lane = "gl";
  agreeing.lanes[1].lane = "vk";
  agreeing.cross_lane = {CrossLaneResult{"gl", "vk", Verdict::Pass, {}, {}, false}};
  EXPECT_FALSE(bless_refusal(agreeing));

  SceneResult disagreeing = agreeing;
  disagreeing.cross_lane[0].verdict = Verdict::Fail;
  const auto refused = bless_refusal(disagreeing);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->verdict, Verdict::Fail);
  EXPECT_NE(refused->message.find("gl and vk disagree"), std::string::npos) << refused->message;

  SceneResult crashed = agreeing;
  crashed.lanes[1].verdict = Verdict::Crash;
  crashed.lanes[1].message = "worker died";
  const auto crash = bless_refusal(crashed);
  ASSERT_TRUE(crash);
  EXPECT_EQ(crash->verdict, Verdict::Crash);
  EXPECT_EQ(crash->message, "s on vk: worker died");
}

}  // namespace
}  // namespace xshade::harness
