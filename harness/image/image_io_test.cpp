#include "harness/image/image_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

std::filesystem::path temp_path(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / "xshade_image_io_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(Srgb, EncodesTheStandardCurve) {
  EXPECT_EQ(linear_to_srgb8(0.0f), 0);
  EXPECT_EQ(linear_to_srgb8(1.0f), 255);
  EXPECT_EQ(linear_to_srgb8(0.5f), 188);     // 0.7354 * 255
  EXPECT_EQ(linear_to_srgb8(0.002f), 7);     // the linear segment: 12.92 * 0.002 * 255 = 6.6
  EXPECT_EQ(linear_to_srgb8(-3.0f), 0);
  EXPECT_EQ(linear_to_srgb8(7.0f), 255);
  EXPECT_EQ(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  for (int code = 0; code < 256; ++code)
    EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(uint8_t(code))), code) << code;
}

TEST(ImageIo, ExrKeepsEveryFloat) {
  FloatImage image(3, 2);
  const float inf = std::numeric_limits<float>::infinity();
  image.set(0, 0, {2.5f, -1.0f, inf, 1e-30f});
  image.set(2, 1, {std::numeric_limits<float>::quiet_NaN(), -inf, 65504.0f, 0.0f});
  auto path = temp_path("floats.exr");
  ASSERT_TRUE(write_exr(image, path));
  auto back = read_image(path);
  ASSERT_TRUE(back) << back.error().to_string();
  ASSERT_EQ(back->width, 3u);
  ASSERT_EQ(back->height, 2u);
  EXPECT_EQ(back->at(0, 0), image.at(0, 0));
  EXPECT_TRUE(std::isnan(back->at(2, 1).r));
  EXPECT_EQ(back->at(2, 1).g, -inf);
  EXPECT_EQ(back->at(2, 1).b, 65504.0f);
}

TEST(ImageIo, PngIsClampedSrgbWithRowZeroAtTheTop) {
  FloatImage image(2, 2);
  image.set(0, 0, {1.0f, 0.0f, 0.0f, 1.0f});  // top-left red
  image.set(1, 1, {0.5f, 3.0f, -1.0f, 0.25f});
  auto path = temp_path("clamped.png");
  ASSERT_TRUE(write_png(image, path));
  auto back = read_image(path);
  ASSERT_TRUE(back) << back.error().to_string();
  EXPECT_EQ(back->at(0, 0), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  // The file holds the 8-bit code; reading decodes exactly that code.
  EXPECT_EQ(back->at(1, 1).r, srgb8_to_linear(linear_to_srgb8(0.5f)));
  EXPECT_EQ(back->at(1, 1).g, 1.0f);
  EXPECT_EQ(back->at(1, 1).b, 0.0f);
  EXPECT_NEAR(back->at(1, 1).a, 0.25f, 0.5f / 255.0f);
}

TEST(ImageIo, MissingAndCorruptFilesAreErrorsNamingTheFile) {
  auto missing = read_image(temp_path("does_not_exist.png"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("does_not_exist.png"), std::string::npos);

  auto corrupt_path = temp_path("corrupt.png");
  std::ofstream(corrupt_path) << "\x89PNG\r\n\x1a\n this is not a png";
  auto corrupt = read_image(corrupt_path);
  ASSERT_FALSE(corrupt);
  EXPECT_NE(corrupt.error().message.find("corrupt.png"), std::string::npos);
}

TEST(ImageIo, UnwritablePathIsAnError) {
  EXPECT_FALSE(write_png(FloatImage(1, 1), "/nonexistent_dir/x.png"));
}

}  // namespace
}  // namespace xshade::harness
