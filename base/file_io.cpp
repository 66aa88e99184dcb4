#include "base/file_io.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include <fcntl.h>
#include <unistd.h>

namespace xshade {

namespace fs = std::filesystem;

// In one read into a string of the file's size where the size is known: through a stringstream,
// hashing the 14 MB executable for the shader cache's key took a quarter of a second, most of
// it copying. Files that do not say their size (/proc, pipes) are read in chunks until the end.
std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  std::string bytes;
  std::error_code error;
  const uintmax_t size = fs::file_size(path, error);
  if (!error && size > 0) {
    bytes.resize(size_t(size));
    file.read(bytes.data(), std::streamsize(size));
    bytes.resize(size_t(file.gcount()));
  }
  char chunk[65536];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) bytes.append(chunk, size_t(file.gcount()));
  if (file.bad()) return std::nullopt;
  return bytes;
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
  if (fd < 0) return fail("cannot write " + temporary + ": " + std::strerror(errno));
  const bool complete = write_all(fd, bytes);
  const int error_number = errno;
  const bool ok = ::close(fd) == 0 && complete;
  std::error_code error;
  if (ok) fs::rename(temporary, path, error);
  if (!ok || error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return fail("cannot write " + (ok ? path.string() + ": " + error.message()
                                      : temporary + ": " + std::strerror(error_number)));
  }
  return {};
}

}  // namespace xshade
