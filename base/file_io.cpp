#include "base/file_io.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace xshade {

namespace fs = std::filesystem;

namespace {

// The file opened to read, or -1 with `why` set.
int open_to_read(const fs::path& path, ReadFailure* why) {
  // O_NONBLOCK: a FIFO opens at once instead of waiting for a writer, and is then refused.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0 && why) *why = errno == EISDIR ? ReadFailure::IsDirectory : ReadFailure::CannotOpen;
  return fd;
}

// The bytes of an open file, `expected` of them or more; `regular`: a short read is its end.
std::optional<std::string> read_open_file(int fd, size_t expected, bool regular, ReadFailure* why) {
  std::string bytes(expected > 0 ? expected + 1 : 65536, '\0');  // +1: a read that fills it says the file grew
  size_t size = 0;
  for (;;) {
    if (size == bytes.size()) bytes.resize(bytes.size() * 2);
    const ssize_t n = ::read(fd, bytes.data() + size, bytes.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      if (why) *why = ReadFailure::CannotRead;
      return std::nullopt;
    }
    if (n == 0) break;
    size += size_t(n);
    // A regular file reads short only at its end: no second read to see that.
    if (regular && size < bytes.size()) break;
  }
  ::close(fd);
  bytes.resize(size);
  return bytes;
}

}  // namespace

// One open, fstat and read of the file's size for a regular file: the front end reads its
// includes for every compile and the shader cache hashes the 14 MB executable, where a stream
// (and a stringstream before it) cost more than the reading. Files that do not say their size
// (/proc) are read on to their end.
std::optional<std::string> read_file(const fs::path& path, ReadFailure* why) {
  const int fd = open_to_read(path, why);
  if (fd < 0) return std::nullopt;
  struct stat status {};
  if (::fstat(fd, &status) == 0 && !S_ISREG(status.st_mode)) {
    ::close(fd);
    if (why) *why = S_ISDIR(status.st_mode) ? ReadFailure::IsDirectory : ReadFailure::NotAFile;
    return std::nullopt;
  }
  return read_open_file(fd, status.st_size > 0 ? size_t(status.st_size) : 0, true, why);
}

std::optional<std::string> read_regular_file(const fs::path& path, size_t known_size, ReadFailure* why) {
  const int fd = open_to_read(path, why);
  if (fd < 0) return std::nullopt;
  return read_open_file(fd, known_size, true, why);
}

namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return S_ISREG(mode) ? "" : "not a regular file";
}

}  // namespace

std::string not_a_file(const fs::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0) return kind_of(status.st_mode);
  if (::lstat(path.c_str(), &status) == 0 && S_ISLNK(status.st_mode)) return "a symbolic link to nothing";
  return "";
}

Result<std::string> read_input_file(const fs::path& path, size_t max_bytes, std::string_view what) {
  const std::string named = std::string(what) + " " + path.string();
  // O_NONBLOCK: opening a FIFO to read returns at once instead of waiting for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (std::string kind = not_a_file(path); !kind.empty())
      return fail(ErrorKind::UserInput, named + " is " + kind + ", not a file");
    return fail(error == ENOENT ? ErrorKind::UserInput : ErrorKind::Backend,
                named + " cannot be opened: " + std::strerror(error));
  }
  struct stat status {};
  if (::fstat(fd, &status) != 0) {
    const int error = errno;
    ::close(fd);
    return fail(ErrorKind::Backend, named + " cannot be read: " + std::strerror(error));
  }
  if (!S_ISREG(status.st_mode)) {
    ::close(fd);
    return fail(ErrorKind::UserInput, named + " is " + kind_of(status.st_mode) + ", not a file");
  }
  if (size_t(status.st_size) > max_bytes) {
    ::close(fd);
    return fail(ErrorKind::UserInput, named + " is " + std::to_string(status.st_size) + " bytes, more than the " +
                                          std::to_string(max_bytes) + " a " + std::string(what) + " may have");
  }
  ReadFailure why{};
  auto bytes = read_open_file(fd, size_t(status.st_size), true, &why);
  if (!bytes) return fail(ErrorKind::Backend, named + " cannot be read: " + std::strerror(errno));
  // A file that grew past the limit while it was read.
  if (bytes->size() > max_bytes)
    return fail(ErrorKind::UserInput,
                named + " grew past the " + std::to_string(max_bytes) + " bytes a " + std::string(what) + " may have");
  return std::move(*bytes);
}

Result<void> copy_file_whole(const fs::path& from, const fs::path& to) {
  const std::optional<std::string> bytes = read_file(from);
  if (!bytes) return fail(ErrorKind::Backend, "cannot read " + from.string());
  return write_file_atomically(to, *bytes);
}

Result<void> make_private_folder(const fs::path& folder) {
  std::error_code error;
  if (!fs::exists(folder, error)) {
    fs::create_directories(folder.parent_path(), error);
    if (::mkdir(folder.c_str(), 0700) != 0 && errno != EEXIST)
      return fail(ErrorKind::Backend, "cannot make the folder " + folder.string() + ": " + std::strerror(errno));
  }
  struct stat status {};
  if (::stat(folder.c_str(), &status) != 0)
    return fail(ErrorKind::Backend, "cannot read the folder " + folder.string() + ": " + std::strerror(errno));
  if (!S_ISDIR(status.st_mode))
    return fail(
        ErrorKind::Backend,
        folder.string() + " is " + (S_ISREG(status.st_mode) ? "a file" : kind_of(status.st_mode)) + ", not a folder");
  if (status.st_uid != ::geteuid())
    return fail(ErrorKind::Backend,
                folder.string() + " belongs to another user (uid " + std::to_string(status.st_uid) + ")");
  if (status.st_mode & (S_IWGRP | S_IWOTH))
    return fail(
        ErrorKind::Backend, folder.string() + " can be written by other users (mode " + [&] {
          char octal[8];
          std::snprintf(octal, sizeof octal, "%03o", unsigned(status.st_mode & 0777));
          return std::string(octal);
        }() + "); make it private with chmod 700");
  return {};
}

bool write_all(int fd, std::string_view bytes) {
  size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    written += size_t(n);
  }
  return true;
}

Result<void> write_file_atomically(const fs::path& path, std::string_view bytes) {
  // Beside the target, so that the rename stays within one file system and is atomic. The pid
  // and a counter make the name unique among the processes and threads writing the same file at
  // once (the last rename wins, and each is a whole file); O_EXCL steps over a temporary that a
  // killed process with the same pid left.
  static std::atomic<unsigned> counter = 0;
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0 && attempt < 100; ++attempt) {
    temporary = path.string() + ".tmp" + std::to_string(::getpid()) + "." + std::to_string(counter++);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  // A full disk, a read-only folder, an I/O error: the environment's (exit 3), named by the file
  // the caller asked for, and no temporary left behind.
  if (fd < 0) return fail(ErrorKind::Backend, "cannot write " + path.string() + ": " + std::strerror(errno));
  const bool complete = write_all(fd, bytes);
  int error_number = errno;
  const bool closed = ::close(fd) == 0;
  if (complete && !closed) error_number = errno;  // a deferred write error (NFS, a full quota)
  std::error_code error;
  if (complete && closed) fs::rename(temporary, path, error);
  if (!complete || !closed || error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return fail(ErrorKind::Backend, "cannot write " + path.string() + ": " +
                                        (error ? error.message() : std::string(std::strerror(error_number))));
  }
  return {};
}

}  // namespace xshade
