// The driver's compile messages of shaders Mesa's on-disk shader cache may skip compiling.
//
// With the cache on, Mesa compiles a shader it has seen before (in this process or an earlier
// one) no more: it loads the result, and the compiler's warnings, which come only from a compile,
// are gone. A run would then pass on a second try what it failed on the first. So the messages of
// every compile that gave some are kept beside the cache, under the driver and the source, and a
// compile that gives none where that one gave some is given them again.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace xshade::harness {

class CompileMessages {
 public:
  // `folder` empty: nothing is kept (the shader cache is off, and every compile speaks for itself).
  explicit CompileMessages(std::filesystem::path folder) : folder_(std::move(folder)) {}

  // `fresh`: what the driver said compiling `source` just now; `driver` names the driver and its
  // version. Returns `fresh`, keeping it when it says something; or, when the driver said nothing
  // and an earlier compile of the same source on the same driver did, what that one said. An
  // entry whose contents do not match their hash is not used.
  std::vector<std::string> settle(const std::string& driver, const std::string& source,
                                  std::vector<std::string> fresh) const;

 private:
  std::filesystem::path folder_;
};

}  // namespace xshade::harness
