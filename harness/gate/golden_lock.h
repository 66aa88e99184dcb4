// The advisory lock of a golden folder (flock on <folder>/.golden.lock).
//
// bless holds it exclusively for its whole read-modify-write of MANIFEST.toml and the images, so
// that two blesses into one folder never lose each other's entries; a reader holds it shared, so
// that it never reads a manifest from one bless and an image from another. Advisory: it orders
// xshade processes, not a user's own `cp`; the manifest's hashes catch those.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "base/result.h"

namespace xshade::harness {

// Told once, with a message naming the lock file, when another process holds the lock and this
// one waits for it: a bless that seems to hang says why.
using LockWaitNotice = std::function<void(const std::string& message)>;

class GoldenLock {
 public:
  enum class Mode { Shared, Exclusive };

  static constexpr const char* kFileName = ".golden.lock";

  // Takes the lock on `folder`/.golden.lock, creating the file, waiting while another process
  // holds it in a conflicting mode. `folder` must exist. A shared lock on a folder this process
  // cannot write to (a read-only checkout) is returned unheld: no bless can be writing there.
  static Result<GoldenLock> acquire(const std::filesystem::path& folder, Mode mode, const LockWaitNotice& notice = {});

  GoldenLock(GoldenLock&& other) noexcept;
  GoldenLock& operator=(GoldenLock&& other) noexcept;
  GoldenLock(const GoldenLock&) = delete;
  GoldenLock& operator=(const GoldenLock&) = delete;
  ~GoldenLock();

  // Whether the lock is held (false only for the read-only case above).
  bool held() const { return fd_ >= 0; }
  Mode mode() const { return mode_; }
  // From shared to exclusive, waiting as acquire() does. flock converts by releasing first, so
  // two readers upgrading at once cannot deadlock; whatever was seen under the shared lock must
  // be looked at again.
  Result<void> upgrade(const LockWaitNotice& notice = {});

 private:
  GoldenLock(int fd, Mode mode, std::filesystem::path path) : fd_(fd), mode_(mode), path_(std::move(path)) {}

  int fd_ = -1;
  Mode mode_ = Mode::Shared;
  std::filesystem::path path_;
};

}  // namespace xshade::harness
