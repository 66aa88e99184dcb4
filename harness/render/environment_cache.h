// Environments built once: a scene's [environment] is its SH and its prefiltered specular mips,
// 90 to 130 ms to compute, and the same environment serves many scenes and every lane. Each is
// kept in memory for the process (a worker renders many scenes) and, with a folder, on disk
// between runs, by the hash of what it is made from: the spec, the image file's bytes for an
// equirect, and the build of xshade that computes it. Every entry carries the hash of its
// contents, checked on read: a damaged one is built again and rewritten, never used.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "harness/assets/environment.h"

namespace xshade::harness {

class EnvironmentCache {
 public:
  // `folder` empty: in memory only. `builder_identity` changes whenever the build could compute
  // another environment (compiler_identity()).
  EnvironmentCache(std::filesystem::path folder, std::string builder_identity);

  // The environment of `spec`, built at most once per process, and on a warm folder not at all.
  Result<std::shared_ptr<const Environment>> get(const EnvironmentSpec& spec);

  size_t built() const { return built_; }  // computed here, rather than found

 private:
  std::filesystem::path folder_;
  std::string builder_identity_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const Environment>> kept_;  // by key
  size_t built_ = 0;
};

}  // namespace xshade::harness
