#include "harness/report/report_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "base/file_io.h"

namespace xshade::harness {

namespace fs = std::filesystem;

Result<ReportLock> ReportLock::take(const fs::path& folder, const std::string& command) {
  std::error_code error;
  fs::create_directories(folder, error);
  const fs::path path = folder / kFileName;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0)
    return fail(ErrorKind::Backend,
                "cannot open the report folder's lock " + path.string() + ": " + std::strerror(errno));
  ReportLock lock(fd);
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno != EWOULDBLOCK)
      return fail(ErrorKind::Backend, "cannot lock " + path.string() + ": " + std::strerror(errno));
    std::string holder = read_file(path).value_or("");
    while (!holder.empty() && holder.back() == '\n') holder.pop_back();
    return fail(ErrorKind::Usage, "the report folder " + folder.string() + " is being written by another xshade (" +
                                      (holder.empty() ? std::string("it has not said which") : holder) +
                                      "); give this run another --report, or wait for that one to finish");
  }
  // Who holds it, for a run that is refused.
  const std::string holder = "process " + std::to_string(::getpid()) + ": " + command + "\n";
  if (::ftruncate(fd, 0) != 0 || !write_all(fd, holder)) {
    const int cause = errno;
    ::unlink(path.c_str());  // held by this process alone: no empty lock is left on a full disk
    return fail(ErrorKind::Backend, "cannot write " + path.string() + ": " + std::strerror(cause));
  }
  return lock;
}

ReportLock::ReportLock(ReportLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

ReportLock& ReportLock::operator=(ReportLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

ReportLock::~ReportLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace xshade::harness
