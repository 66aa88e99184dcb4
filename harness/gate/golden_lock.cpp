#include "harness/gate/golden_lock.h"

#include <cerrno>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/format.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// Tries without waiting first, so that the notice is given only when there is something to wait for.
Result<void> take_flock(int fd, GoldenLock::Mode mode, const fs::path& path, const LockWaitNotice& notice) {
  const int operation = mode == GoldenLock::Mode::Exclusive ? LOCK_EX : LOCK_SH;
  if (::flock(fd, operation | LOCK_NB) == 0) return {};
  if (errno != EWOULDBLOCK)
    return fail(ErrorKind::Backend, fmt::format("cannot lock {}: {}", path.string(), std::strerror(errno)));
  if (notice)
    notice(fmt::format("waiting for another xshade to finish writing {} (it holds {})", path.parent_path().string(),
                       path.string()));
  while (::flock(fd, operation) != 0)
    if (errno != EINTR)
      return fail(ErrorKind::Backend, fmt::format("cannot lock {}: {}", path.string(), std::strerror(errno)));
  return {};
}

}  // namespace

Result<GoldenLock> GoldenLock::acquire(const fs::path& folder, Mode mode, const LockWaitNotice& notice) {
  const fs::path path = folder / kFileName;
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0 && mode == Mode::Shared && (errno == EACCES || errno == EROFS || errno == EPERM)) {
    // The lock file may exist in a folder we cannot write to: then share it, as a writer would see.
    fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return GoldenLock(-1, mode, path);
  }
  if (fd < 0)
    return fail(ErrorKind::Backend,
                fmt::format("cannot open the golden folder's lock {}: {}", path.string(), std::strerror(errno)));
  GoldenLock held(fd, mode, path);
  if (Result<void> locked = take_flock(fd, mode, path, notice); !locked) return fail(locked.error());
  return held;
}

Result<void> GoldenLock::upgrade(const LockWaitNotice& notice) {
  if (fd_ < 0) return fail(ErrorKind::Internal, "upgrade of a golden lock that is not held");
  if (mode_ == Mode::Exclusive) return {};
  ::flock(fd_, LOCK_UN);
  mode_ = Mode::Exclusive;
  return take_flock(fd_, mode_, path_, notice);
}

GoldenLock::GoldenLock(GoldenLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), mode_(other.mode_), path_(std::move(other.path_)) {}

GoldenLock& GoldenLock::operator=(GoldenLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    mode_ = other.mode_;
    path_ = std::move(other.path_);
  }
  return *this;
}

// Closing the descriptor releases the lock.
GoldenLock::~GoldenLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace xshade::harness
