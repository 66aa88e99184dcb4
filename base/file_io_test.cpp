#include "base/file_io.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
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
  EXPECT_EQ(written.error().message.find("cannot write " + missing.string() + ": No such file or directory"), 0u)
      << written.error().message;
  EXPECT_EQ(written.error().kind, ErrorKind::Backend);  // the environment's: exit 3
}

TEST(FileIo, CopiesAFileWholeOrLeavesNothing) {
  const fs::path folder = fs::temp_directory_path() / ("xshade_file_io_copy_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  ASSERT_TRUE(write_file_atomically(folder / "from.bin", std::string("a\0b", 3)));
  ASSERT_TRUE(copy_file_whole(folder / "from.bin", folder / "to.bin"));
  EXPECT_EQ(read_file(folder / "to.bin"), std::string("a\0b", 3));
  auto unread = copy_file_whole(folder / "absent.bin", folder / "to2.bin");
  ASSERT_FALSE(unread);
  EXPECT_EQ(unread.error().message, "cannot read " + (folder / "absent.bin").string());
  EXPECT_EQ(unread.error().kind, ErrorKind::Backend);
  EXPECT_FALSE(fs::exists(folder / "to2.bin"));
  EXPECT_FALSE(copy_file_whole(folder / "from.bin", folder / "no" / "to.bin"));
  fs::remove_all(folder);
}

// A file a user gives is opened without waiting and checked before it is read: a FIFO (which a
// read would wait on forever), a directory, a link to nothing, a device, or a file past its limit
// is refused at once, naming what it is.
TEST(FileIo, AnInputFileThatIsNotAFileOrTooLargeIsRefusedBeforeItIsRead) {
  const fs::path root = fs::temp_directory_path() / ("xshade_file_io_input_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "folder");
  ASSERT_TRUE(write_file_atomically(root / "small.toml", "a = 1\n"));
  ASSERT_EQ(::mkfifo((root / "fifo.toml").c_str(), 0600), 0);
  fs::create_symlink(root / "gone.toml", root / "dangling.toml");
  fs::create_symlink(root / "small.toml", root / "link.toml");

  auto small = read_input_file(root / "small.toml", 6, "scene file");
  ASSERT_TRUE(small) << small.error().message;
  EXPECT_EQ(*small, "a = 1\n");
  EXPECT_TRUE(read_input_file(root / "link.toml", 6, "scene file")) << "a link to a file is that file";
  const auto refusal = [&](const fs::path& path, size_t limit = 1000) {
    const auto started = std::chrono::steady_clock::now();
    auto read = read_input_file(path, limit, "scene file");
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5)) << "waited on " << path;
    return read ? std::string("(read)") : read.error().message;
  };
  EXPECT_EQ(refusal(root / "fifo.toml"), "scene file " + (root / "fifo.toml").string() + " is a FIFO, not a file");
  EXPECT_EQ(refusal(root / "folder"), "scene file " + (root / "folder").string() + " is a directory, not a file");
  EXPECT_EQ(refusal(root / "dangling.toml"),
            "scene file " + (root / "dangling.toml").string() + " is a symbolic link to nothing, not a file");
  EXPECT_EQ(refusal("/dev/zero"), "scene file /dev/zero is a device, not a file");
  EXPECT_EQ(refusal(root / "small.toml", 5),
            "scene file " + (root / "small.toml").string() + " is 6 bytes, more than the 5 a scene file may have");
  auto missing = read_input_file(root / "none.toml", 5, "scene file");
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::UserInput);
  EXPECT_EQ(missing.error().message,
            "scene file " + (root / "none.toml").string() + " cannot be opened: No such file or directory");
  EXPECT_EQ(not_a_file(root / "small.toml"), "");
  EXPECT_EQ(not_a_file(root / "none.toml"), "");
  fs::remove_all(root);
}

// The compile cache's folder: made 0700; one that others can write, that is not a folder, or
// (where the test may change owners) that another user owns is refused, saying why.
TEST(FileIo, APrivateFolderIsMadeOwnerOnlyAndAnotherKindIsRefused) {
  const fs::path root = fs::temp_directory_path() / ("xshade_private_" + std::to_string(::getpid()));
  fs::remove_all(root);
  const fs::path made = root / "deep" / "cache";
  ASSERT_TRUE(make_private_folder(made));
  struct stat status {};
  ASSERT_EQ(::stat(made.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0700u);
  EXPECT_TRUE(make_private_folder(made)) << "the same folder again";

  fs::permissions(made, fs::perms::all);
  auto open = make_private_folder(made);
  ASSERT_FALSE(open);
  EXPECT_EQ(open.error().message,
            made.string() + " can be written by other users (mode 777); make it private with chmod 700");
  EXPECT_EQ(open.error().kind, ErrorKind::Backend);  // the environment's folder, not an input
  ASSERT_TRUE(write_file_atomically(root / "file", "x"));
  auto file = make_private_folder(root / "file");
  ASSERT_FALSE(file);
  EXPECT_EQ(file.error().message, (root / "file").string() + " is a file, not a folder");
  EXPECT_EQ(file.error().kind, ErrorKind::Backend);
  if (::geteuid() == 0) {  // only root can give a folder away
    fs::permissions(made, fs::perms::owner_all, fs::perm_options::replace);
    ASSERT_EQ(::chown(made.c_str(), 65534, 65534), 0);
    auto theirs = make_private_folder(made);
    ASSERT_FALSE(theirs);
    EXPECT_EQ(theirs.error().message, made.string() + " belongs to another user (uid 65534)");
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace xshade
