#include "harness/image/image_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "harness/image/forged_image_headers.h"
#include "harness/image/image_limits.h"

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
  EXPECT_EQ(linear_to_srgb8(0.5f), 188);  // 0.7354 * 255
  EXPECT_EQ(linear_to_srgb8(0.002f), 7);  // the linear segment: 12.92 * 0.002 * 255 = 6.6
  EXPECT_EQ(linear_to_srgb8(-3.0f), 0);
  EXPECT_EQ(linear_to_srgb8(7.0f), 255);
  EXPECT_EQ(linear_to_srgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  for (int code = 0; code < 256; ++code) EXPECT_EQ(linear_to_srgb8(srgb8_to_linear(uint8_t(code))), code) << code;
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

// A header's size is checked before anything is allocated: these files made 65535 x 65535 (and
// more) RGBA float buffers, which ended the process with std::bad_alloc.
TEST(ImageIo, AHeaderClaimingMoreThanTheLimitIsRefusedNamingTheFileItsSizeAndTheLimit) {
  const std::string limit = "xshade reads images of at most 16384 pixels a side and 33554432 pixels in all";
  const std::pair<std::string, std::string> files[] = {
      {"huge.png", forged::png(65535, 65535)},
      {"huge.exr", forged::exr(1000000, 1000000)},
      {"huge.hdr", forged::hdr(100000, 100000)},
  };
  const std::string sizes[] = {"65535 x 65535", "1000000 x 1000000", "100000 x 100000"};
  for (size_t i = 0; i < std::size(files); ++i) {
    const auto path = temp_path(files[i].first);
    forged::write(path, files[i].second);
    auto read = read_image(path);
    ASSERT_FALSE(read) << files[i].first;
    EXPECT_EQ(read.error().message, "cannot read image " + path.string() + ": it is " + sizes[i] + " pixels; " + limit);
    EXPECT_EQ(read.error().kind, ErrorKind::UserInput);
  }
  EXPECT_EQ(forged::png(1, 1).size(), 68u);
}

TEST(ImageIo, TheLimitsAreOnEachSideAndOnThePixelsInAll) {
  // One side too long, the other short: few pixels, still refused.
  const auto wide = temp_path("wide.png");
  forged::write(wide, forged::png(kMaxImageFileSide + 1, 1));
  auto read = read_image(wide);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("it is 16385 x 1 pixels"), std::string::npos) << read.error().message;
  // Both sides within the limit, too many pixels in all.
  const auto square = temp_path("square.hdr");
  forged::write(square, forged::hdr(8192, 4097));
  read = read_image(square);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("it is 8192 x 4097 pixels"), std::string::npos) << read.error().message;
  // At the limit the header passes, and the missing pixels are what is reported.
  const auto small = temp_path("small_but_truncated.png");
  forged::write(small, forged::png(64, 64));
  read = read_image(small);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().message.find("pixels a side"), std::string::npos) << read.error().message;
}

// OpenEXR believes its header: an attribute claiming 2 GB in a file of a few hundred bytes was
// allocated and zeroed (12 s, 2 GB), and a data window sizes the offset table it allocates on
// open. Both are refused from the header's bytes, whatever the file is called.
TEST(ImageIo, AnExrHeaderThatClaimsMoreThanTheFileHoldsIsRefusedBeforeOpenExrReadsIt) {
  const std::string lying = forged::exr_attribute("comments", "string", 0x772f005b, "not two gigabytes");
  for (const char* name : {"lying.exr", "lying_exr_named.png"}) {
    const auto path = temp_path(name);
    forged::write(path, forged::exr(16, 16, true, lying));
    auto read = read_image(path);
    ASSERT_FALSE(read) << name;
    EXPECT_EQ(read.error().message, "cannot read image " + path.string() +
                                        ": its header's attribute 'comments' claims 1999568987 bytes, more "
                                        "than the file holds (" +
                                        std::to_string(std::filesystem::file_size(path)) + " bytes in all)");
    EXPECT_EQ(read.error().kind, ErrorKind::UserInput);
  }
  // 2^30 lines and no offset table: refused by its data window alone, in a file of 300 bytes.
  const auto tall = temp_path("tall.exr");
  forged::write(tall, forged::exr(1, 1 << 30, false));
  auto read = read_image(tall);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("it is 1 x 1073741824 pixels"), std::string::npos) << read.error().message;
  // An attribute name past OpenEXR's short-name length (31 bytes), which OpenEXR reads all the same,
  // does not end the walk before OpenEXR's open does.
  const auto wide = temp_path("wide_long_name.exr");
  forged::write(wide, forged::exr(1 << 24, 1, false, forged::exr_attribute(std::string(100, 'K'), "string", 2, "ok")));
  read = read_image(wide);
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message.find("it is 16777216 x 1 pixels"), std::string::npos) << read.error().message;
  // A truthful header of the same shape still reads as far as its missing pixels.
  const auto honest = temp_path("honest.exr");
  forged::write(honest, forged::exr(16, 16, true, forged::exr_attribute("comments", "string", 2, "ok")));
  read = read_image(honest);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().message.find("claims"), std::string::npos) << read.error().message;
  EXPECT_EQ(read.error().message.find("pixels a side"), std::string::npos) << read.error().message;
}

TEST(ImageIo, UnwritablePathIsAnError) { EXPECT_FALSE(write_png(FloatImage(1, 1), "/nonexistent_dir/x.png")); }

}  // namespace
}  // namespace xshade::harness
