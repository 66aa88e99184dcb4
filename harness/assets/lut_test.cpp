#include "harness/assets/lut.h"

#include <sys/stat.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

namespace xshade::harness {
namespace {

glm::vec4 texel(const TextureData& lut, uint32_t x, uint32_t y, uint32_t z) {
  glm::vec4 value;
  const size_t index = (size_t(z) * lut.height + y) * lut.width + x;
  std::memcpy(&value, lut.levels[0].data() + index * sizeof value, sizeof value);
  return value;
}

// A strip whose texel at (slice b, column r, row from the bottom g) is (r, g, b, 1) / 255.
FloatImage strip(uint32_t n) {
  FloatImage image(n * n, n);
  for (uint32_t b = 0; b < n; ++b)
    for (uint32_t g = 0; g < n; ++g)
      for (uint32_t r = 0; r < n; ++r)
        image.set(b * n + r, n - 1 - g, glm::vec4(float(r), float(g), float(b), 255.0f) / 255.0f);
  return image;
}

TEST(Lut, AStripBecomesRedGreenBlueAlongXYZ) {
  auto lut = lut_from_strip(strip(4));
  ASSERT_TRUE(lut) << lut.error().to_string();
  EXPECT_EQ(lut->dimension, TextureDimension::Tex3D);
  EXPECT_EQ(lut->layers, 4u);
  EXPECT_EQ(lut->levels.size(), 1u);
  EXPECT_TRUE(validate_texture(*lut, 4096));
  for (uint32_t z = 0; z < 4; ++z)
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x)
        EXPECT_EQ(texel(*lut, x, y, z), glm::vec4(float(x), float(y), float(z), 255.0f) / 255.0f);
}

TEST(Lut, AStripMustBeNSquaredByN) {
  auto wrong = lut_from_strip(FloatImage(64, 16));
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().message, "a LUT strip is N * N x N texels (Unity's is 1024 x 32), this image is 64x16");
}

class CubeFile : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    path_ = std::filesystem::temp_directory_path() / ("xshade_lut_" + std::to_string(::getpid()) + ".cube");
    std::ofstream(path_) << text;
    return path_;
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::string error_of(const std::string& text) {
    auto lut = read_cube_lut(write(text));
    return lut ? "no error" : lut.error().where.to_string().substr(path_.string().size()) + ": " + lut.error().message;
  }
  std::filesystem::path path_;
};

TEST_F(CubeFile, ReadsTheTableRedFastest) {
  std::string text = "# a comment\nTITLE \"identity\"\nLUT_3D_SIZE 2\nDOMAIN_MIN 0 0 0\nDOMAIN_MAX 1 1 1\n\n";
  for (int b = 0; b < 2; ++b)
    for (int g = 0; g < 2; ++g)
      for (int r = 0; r < 2; ++r)
        text += std::to_string(r) + " " + std::to_string(g * 0.5) + " " + std::to_string(b) + "\r\n";
  auto lut = read_cube_lut(write(text));
  ASSERT_TRUE(lut) << lut.error().to_string();
  EXPECT_EQ(lut->width, 2u);
  EXPECT_EQ(lut->layers, 2u);
  EXPECT_EQ(texel(*lut, 1, 0, 0), glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(texel(*lut, 0, 1, 0), glm::vec4(0, 0.5f, 0, 1));
  EXPECT_EQ(texel(*lut, 1, 1, 1), glm::vec4(1, 0.5f, 1, 1));
}

TEST_F(CubeFile, ErrorsNameTheLineAndColumn) {
  EXPECT_EQ(error_of("LUT_1D_SIZE 16\n"), ":1:1: a 1D LUT cannot be a 3D texture; give a file with LUT_3D_SIZE");
  EXPECT_EQ(error_of("LUT_3D_SIZE 1\n"), ":1:13: LUT_3D_SIZE: expected an integer in 2..256");
  EXPECT_EQ(error_of("0 0 0\n"), ":1:1: expected LUT_3D_SIZE before the table's values");
  EXPECT_EQ(error_of("LUT_3D_SIZE 2\nDOMAIN_MAX 1 2 1\n"),
            ":2:14: DOMAIN_MAX: expected 1 1 1: xshade reads LUTs over the domain [0, 1]");
  EXPECT_EQ(error_of("LUT_3D_SIZE 2\n0 0 x\n"), ":2:5: expected a number, got 'x'");
  EXPECT_EQ(error_of("LUT_3D_SIZE 2\n0 0\n"), ":2:1: expected three numbers (red green blue), got 2 words");
  EXPECT_EQ(error_of("LUT_3D_SIZE 2\n0 0 0\n"), ": 1 values, LUT_3D_SIZE 2 asks for 8");
  EXPECT_EQ(error_of("TITLE \"x\"\n"), ": no LUT_3D_SIZE line: not a 3D .cube LUT");
}

TEST(CubeFileKind, AFifoIsRefusedWithoutWaitingForAWriter) {
  const auto fifo =
      std::filesystem::temp_directory_path() / ("xshade_lut_fifo_" + std::to_string(::getpid()) + ".cube");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  auto lut = read_cube_lut(fifo);
  std::filesystem::remove(fifo);
  ASSERT_FALSE(lut);
  EXPECT_EQ(lut.error().message, "the LUT file " + fifo.string() + " is a FIFO, not a file");
}

}  // namespace
}  // namespace xshade::harness
