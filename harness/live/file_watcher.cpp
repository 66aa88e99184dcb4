#include "harness/live/file_watcher.h"

#include <poll.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <utility>

namespace xshade::harness {

namespace fs = std::filesystem;

namespace {

// What a save can do to a file in a watched folder.
constexpr uint32_t kChanges = IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE | IN_DELETE | IN_MOVED_FROM | IN_ATTRIB;

// Milliseconds left until `deadline`, for poll(2).
int left_until(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
  return left.count() <= 0 ? 0 : int(left.count());
}

}  // namespace

fs::path normal_file_path(const fs::path& path) {
  std::error_code error;
  const fs::path absolute = fs::absolute(path, error);
  return (error ? path : absolute).lexically_normal();
}

Result<FileWatcher> FileWatcher::make() {
  const int fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd < 0)
    return fail(ErrorKind::Backend, std::string("cannot watch files (inotify_init1): ") + std::strerror(errno) +
                                        "; /proc/sys/fs/inotify/max_user_instances limits how many a user may have");
  return FileWatcher(fd);
}

FileWatcher::FileWatcher(FileWatcher&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), folders_(std::move(other.folders_)), files_(std::move(other.files_)) {}

FileWatcher::~FileWatcher() {
  if (fd_ >= 0) close(fd_);  // closing the instance removes its watches
}

Result<void> FileWatcher::watch(const std::set<fs::path>& files) {
  std::optional<Error> first_failure;
  for (const fs::path& given : files) {
    const fs::path file = normal_file_path(given);
    const fs::path folder = file.parent_path();
    const int watch = inotify_add_watch(fd_, folder.c_str(), kChanges | IN_ONLYDIR);
    if (watch < 0) {
      // The others are still watched: one folder gone is no reason to go blind to the rest.
      if (!first_failure)
        first_failure = Error{"cannot watch " + folder.string() + " for changes to " + file.filename().string() + ": " +
                                  std::strerror(errno) +
                                  (errno == ENOSPC ? " (/proc/sys/fs/inotify/max_user_watches limits how many "
                                                     "folders a user may watch)"
                                                   : ""),
                              {},
                              {},
                              ErrorKind::UserInput};
      continue;
    }
    folders_[watch] = folder;  // the same descriptor again for a folder watched already
    files_.insert(file);
  }
  if (first_failure) return fail(*first_failure);
  return {};
}

Result<void> FileWatcher::watch_only(const std::set<fs::path>& files) {
  // Folders stay watched (a watch costs a little kernel memory); only the files listed count.
  files_.clear();
  return watch(files);
}

Result<void> FileWatcher::watch_new_files(const fs::path& folder, const std::string& extension) {
  const fs::path normal = normal_file_path(folder);
  const int watch = inotify_add_watch(fd_, normal.c_str(), kChanges | IN_ONLYDIR);
  if (watch < 0)
    return fail(ErrorKind::UserInput,
                "cannot watch " + normal.string() + " for new " + extension + " files: " + std::strerror(errno));
  folders_[watch] = normal;
  new_files_[normal] = extension;
  return {};
}

void FileWatcher::read_events(std::set<fs::path>& changed) {
  alignas(inotify_event) char buffer[16384];
  for (;;) {
    const ssize_t length = read(fd_, buffer, sizeof buffer);
    if (length <= 0) return;  // EAGAIN: nothing more waiting
    for (ssize_t at = 0; at < length;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      at += ssize_t(sizeof(inotify_event) + event->len);
      const auto folder = folders_.find(event->wd);
      if (folder == folders_.end() || event->len == 0) continue;
      const fs::path file = folder->second / event->name;
      const auto kind = new_files_.find(folder->second);
      if (files_.count(file) || (kind != new_files_.end() && file.extension() == kind->second)) changed.insert(file);
    }
  }
}

std::set<fs::path> FileWatcher::wait(std::chrono::milliseconds timeout, std::chrono::milliseconds settle) {
  std::set<fs::path> changed;
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (changed.empty()) {
    pollfd waiting{fd_, POLLIN, 0};
    const int ready = poll(&waiting, 1, left_until(give_up));
    if (ready <= 0) return changed;  // the time ran out, or a signal came
    read_events(changed);
  }
  // The rest of the save: quiet for `settle`, then it is whole.
  for (;;) {
    pollfd waiting{fd_, POLLIN, 0};
    if (poll(&waiting, 1, int(settle.count())) <= 0) return changed;
    read_events(changed);
  }
}

}  // namespace xshade::harness
