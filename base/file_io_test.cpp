#include "base/file_io.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace xshade {
namespace {

namespace fs = std::filesystem;

TEST(FileIo, WritesAtomicallyAndReadsBackEveryByte) {
  const fs::path folder = fs::temp_directory_path() / "xshade_file_io_test";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string bytes("a\0b\r\n\xff", 6);  // NUL, CR LF and a byte that is not UTF-8 survive
  ASSERT_TRUE(write_file_atomically(folder / "f.bin", bytes).has_value());
  ASSERT_TRUE(write_file_atomically(folder / "f.bin", bytes + "z").has_value());  // replaces
  EXPECT_EQ(read_file(folder / "f.bin"), bytes + "z");
  size_t entries = 0;
  for ([[maybe_unused]] const fs::directory_entry& entry : fs::directory_iterator(folder)) ++entries;
  EXPECT_EQ(entries, 1u);  // no temporary file left beside it
  fs::remove_all(folder);
}

// /proc files say their size is 0; a large file is read whole in one go: both come back whole.
TEST(FileIo, ReadsFilesThatDoNotSayTheirSizeAndLargeOnes) {
  const std::optional<std::string> status = read_file("/proc/self/status");
  ASSERT_TRUE(status.has_value());
  EXPECT_NE(status->find("\nPid:"), std::string::npos) << *status;
  const fs::path large = fs::temp_directory_path() / "xshade_file_io_large.bin";
  std::string bytes(3 * 65536 + 7, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = char(i * 31 % 251);
  ASSERT_TRUE(write_file_atomically(large, bytes).has_value());
  EXPECT_EQ(read_file(large), bytes);
  fs::remove(large);
}

// A size told by an earlier stat is where reading starts, not where it stops: a file that grew
// since (or shrank) still comes back whole.
TEST(FileIo, ReadsARegularFileWholeWhateverSizeItWasToldBefore) {
  const fs::path file = fs::temp_directory_path() / "xshade_file_io_known_size.txt";
  const std::string bytes(100000, 'x');
  ASSERT_TRUE(write_file_atomically(file, bytes).has_value());
  for (size_t told : {size_t(0), size_t(10), bytes.size() - 1, bytes.size(), bytes.size() + 1, 4 * bytes.size()})
    EXPECT_EQ(read_regular_file(file, told), bytes) << told;
  fs::remove(file);
  ReadFailure why = ReadFailure::CannotRead;
  EXPECT_FALSE(read_regular_file(file, 10, &why).has_value());
  EXPECT_EQ(why, ReadFailure::CannotOpen);
}

TEST(FileIo, SaysWhatItCouldNotDo) {
  const fs::path missing = fs::temp_directory_path() / "xshade_file_io_test_missing" / "no" / "f.txt";
  EXPECT_FALSE(read_file(missing).has_value());
  auto written = write_file_atomically(missing, "x");
  ASSERT_FALSE(written.has_value());
  EXPECT_NE(written.error().message.find("f.txt"), std::string::npos) << written.error().message;
}

}  // namespace
}  // namespace xshade
