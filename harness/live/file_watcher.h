// The files `xshade watch` renders from, watched with inotify. The folders that hold them are
// watched rather than the files: an editor that saves by writing a new file and renaming it over
// the old one replaces the file, and a watch on the file itself would end with it.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "base/result.h"

namespace xshade::harness {

class FileWatcher {
 public:
  static Result<FileWatcher> make();
  FileWatcher(FileWatcher&& other) noexcept;
  FileWatcher& operator=(FileWatcher&&) = delete;
  ~FileWatcher();

  // Watches `files` too, from now on. Each is made absolute and normal; a file that does not
  // exist yet is watched for its creation, so its folder must exist. A file whose folder cannot
  // be watched is the error (the first such); the others are watched all the same.
  Result<void> watch(const std::set<std::filesystem::path>& files);
  // Watches only `files` from now on (the folders of watch_new_files stay).
  Result<void> watch_only(const std::set<std::filesystem::path>& files);
  // Reports every file whose name ends in `extension` (".toml") made, changed or removed in
  // `folder` too, from now on: the scenes of a folder, when a scene is added.
  Result<void> watch_new_files(const std::filesystem::path& folder, const std::string& extension);
  const std::set<std::filesystem::path>& files() const { return files_; }

  // Waits up to `timeout` for a watched file to be written, created, renamed into place or
  // removed, then gathers the changes that follow until `settle` passes without one (an editor's
  // save is several: a write, a rename, a change of attributes) and returns the changed files.
  // Empty when the time ran out, or a signal interrupted the wait (base/interrupt.h).
  std::set<std::filesystem::path> wait(std::chrono::milliseconds timeout, std::chrono::milliseconds settle);

 private:
  explicit FileWatcher(int fd) : fd_(fd) {}
  // Reads the events waiting, adding the watched files they name to `changed`.
  void read_events(std::set<std::filesystem::path>& changed);

  int fd_ = -1;
  std::map<int, std::filesystem::path> folders_;  // by watch descriptor
  std::set<std::filesystem::path> files_;
  std::map<std::filesystem::path, std::string> new_files_;  // folder -> extension
};

// `path` absolute and without "." and ".." (symbolic links are left as they are: a file is known
// by the name the scene gave it).
std::filesystem::path normal_file_path(const std::filesystem::path& path);

}  // namespace xshade::harness
