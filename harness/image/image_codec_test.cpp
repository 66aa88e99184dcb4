#include "harness/image/image_codec.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

// Whether OpenImageIO's library is mapped into this process.
bool image_library_loaded() {
  std::ifstream maps("/proc/self/maps");
  const std::string text{std::istreambuf_iterator<char>(maps), std::istreambuf_iterator<char>()};
  return text.find("libOpenImageIO") != std::string::npos;
}

// A process that reads and writes no image never loads OpenImageIO (nor its 260 libraries); the
// first image it writes loads it. Checked in a child, so that the answer is this process's alone.
TEST(ImageCodec, TheImageLibraryIsLoadedByTheFirstImageAndNotBefore) {
  if (image_library_loaded()) GTEST_SKIP() << "an earlier test of this process has loaded the image library";
  const auto path =
      std::filesystem::temp_directory_path() / ("xshade_codec_test_" + std::to_string(::getpid()) + ".png");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (image_library_loaded()) ::_exit(10);
    FloatImage image(2, 2);
    image.set(1, 1, {1.0f, 0.5f, 0.25f, 1.0f});
    if (!write_png(image, path)) ::_exit(11);
    ::_exit(image_library_loaded() ? 0 : 12);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  std::filesystem::remove(path);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 10) << "loaded before any image was read or written";
  EXPECT_NE(WEXITSTATUS(status), 11) << "the PNG was not written";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "written without the image library";
}

TEST(ImageCodec, EveryCallGivesTheSameCodec) {
  auto first = image_codec();
  ASSERT_TRUE(first) << first.error().to_string();
  auto second = image_codec();
  ASSERT_TRUE(second);
  EXPECT_EQ(*first, *second);
}

}  // namespace
}  // namespace xshade::harness
