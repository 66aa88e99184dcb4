// One report folder, one run: a run holds the folder's lock (flock on <folder>/.xshade-report.lock)
// from before its first file to after its last, so that two runs into one --report (two shards at
// once) cannot leave a report of one of them that says it is both. The lock file says which run
// holds it, for the one that is refused.
#pragma once

#include <filesystem>
#include <string>

#include "base/result.h"

namespace xshade::harness {

class ReportLock {
 public:
  static constexpr const char* kFileName = ".xshade-report.lock";

  // Takes the lock of `folder` (made if missing) without waiting; a user's error naming the run
  // that holds it (its process and command line) when another does. `command` is this run's.
  static Result<ReportLock> take(const std::filesystem::path& folder, const std::string& command);

  ReportLock(ReportLock&& other) noexcept;
  ReportLock& operator=(ReportLock&& other) noexcept;
  ReportLock(const ReportLock&) = delete;
  ReportLock& operator=(const ReportLock&) = delete;
  ~ReportLock();  // closing the descriptor releases the lock

 private:
  explicit ReportLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace xshade::harness
