// The orientation pattern lands in the same, expected place on every lane.
#include <gtest/gtest.h>

#include "harness/render/test_pattern.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

namespace pattern = harness::test_pattern;
using harness::Lane;

constexpr uint32_t kOrientationImageSize = 64;

class Orientation : public LaneTest {};

TEST_F(Orientation, QuadrantsAndFirstTexelAreWhereDirect3DPutsThem) {
  std::map<Lane, harness::FloatImage> images;
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image = pattern::render(backend(lane), lane, kOrientationImageSize);
    ASSERT_TRUE(image) << image.error().to_string();
    // Quadrant centres: clip +y is the top of the image, row 0 the top row.
    EXPECT_EQ(image->at(16, 16), pattern::kTopLeft);
    EXPECT_EQ(image->at(48, 16), pattern::kTopRight);
    EXPECT_EQ(image->at(16, 48), pattern::kBottomLeft);
    // The bottom-right quadrant shows the 4x4 texture, 8x8 pixels a texel, uv (0,0) top-left.
    for (uint32_t row = 0; row < pattern::kTextureSize; ++row)
      for (uint32_t column = 0; column < pattern::kTextureSize; ++column) {
        const glm::vec4 expected = pattern::texel(column, row);
        const glm::vec4 got = image->at(32 + column * 8 + 4, 32 + row * 8 + 4);
        for (int c = 0; c < 4; ++c)  // 8-bit unorm texels decode to code/255 up to float rounding
          EXPECT_NEAR(got[c], expected[c], 1e-6) << "texel " << column << "," << row;
      }
    images.emplace(lane, std::move(*image));
  }
  // The pattern moves colours and texels without arithmetic: every lane must agree bit for bit.
  for (Lane lane : harness::all_lanes())
    EXPECT_TRUE(harness::bitwise_equal(images.at(Lane::Gl), images.at(lane))) << harness::lane_name(lane);
}

}  // namespace
}  // namespace xshade::tests
