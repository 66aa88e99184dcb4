#include "harness/image/image.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

TEST(FlipRows, RowsComeInTheOppositeOrderAndTwiceIsTheImage) {
  for (uint32_t height : {1u, 2u, 3u}) {
    FloatImage image(2, height);
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < 2; ++x) image.set(x, y, {float(x), float(y), 0.0f, 1.0f});
    FloatImage flipped = image;
    flip_rows(flipped);
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < 2; ++x) EXPECT_EQ(flipped.at(x, y), image.at(x, height - 1 - y)) << x << "," << y;
    flip_rows(flipped);
    EXPECT_TRUE(bitwise_equal(flipped, image));
  }
}

TEST(ImageDifference, FindsTheLargestChannelDifferenceAndWhere) {
  FloatImage a(4, 3), b(4, 3);
  b.set(1, 0, {0.0f, 0.25f, 0.0f, 0.0f});
  b.set(3, 2, {0.0f, 0.0f, -0.5f, 0.0f});
  ImageDifference difference = max_difference(a, b);
  EXPECT_EQ(difference.max, 0.5);
  EXPECT_EQ(difference.x, 3u);
  EXPECT_EQ(difference.y, 2u);
  EXPECT_EQ(difference.channel, 2u);
  EXPECT_FALSE(bitwise_equal(a, b));
  EXPECT_TRUE(bitwise_equal(a, a));
}

TEST(ImageDifference, NanAndInfinityMatchOnlyThemselves) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  FloatImage a(2, 1), b(2, 1);
  a.set(0, 0, {nan, inf, 0.0f, 0.0f});
  b.set(0, 0, {nan, inf, 0.0f, 0.0f});
  EXPECT_EQ(max_difference(a, b).max, 0.0);
  b.set(1, 0, {nan, 0.0f, 0.0f, 0.0f});
  EXPECT_TRUE(std::isinf(max_difference(a, b).max));
  EXPECT_EQ(max_difference(a, b).x, 1u);
}

// A worker's image comes back bit for bit (NaN and infinities too); bytes that are not such an
// image, or are cut short, are refused rather than read.
TEST(FloatImageBytes, AnImageComesBackBitForBitAndOtherBytesAreRefused) {
  FloatImage image(3, 2);
  image.set(0, 0, {std::numeric_limits<float>::quiet_NaN(), -0.0f, std::numeric_limits<float>::infinity(), 1e-40f});
  image.set(2, 1, {0.25f, -7.0f, 65504.0f, 1.0f});
  const std::string bytes = float_image_bytes(image);
  const std::optional<FloatImage> back = float_image_from(bytes);
  ASSERT_TRUE(back);
  EXPECT_TRUE(bitwise_equal(*back, image));
  EXPECT_FALSE(float_image_from(std::string_view(bytes).substr(0, bytes.size() - 1)));
  EXPECT_FALSE(float_image_from("xsfimg2" + bytes.substr(7)));
  EXPECT_FALSE(float_image_from(""));
}

}  // namespace
}  // namespace xshade::harness
