// The folders a scene's shader sources come from, in order: a user's own folders first, then the
// shader library xshade ships. A scene names a source by its library path ("materials/toon.hlsl");
// the first folder that has that file supplies it, so a user's file of the same path takes the
// place of the library's. Every folder is also an #include directory of every compile.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "base/result.h"

namespace xshade::harness {

class ShaderSearchPath {
 public:
  // One folder: the library alone. Not explicit, so that code which knows only the library
  // (the stability suite, the accuracy studies) passes its folder as it always did.
  ShaderSearchPath(std::filesystem::path library);  // NOLINT(google-explicit-constructor)
  explicit ShaderSearchPath(std::vector<std::filesystem::path> folders);

  const std::vector<std::filesystem::path>& folders() const { return folders_; }

  // The file `library_path` names, from the first folder that has it. Fails when no folder has
  // it, and when it leads out of its folder (`..`, or a symbolic link pointing elsewhere): such a
  // path is refused before anything reads it. `looked_in`, when given, gets each place it looked,
  // in order, up to the one that has it (every folder's, when none has it; none for a path
  // refused): where a file made later would be found.
  Result<std::filesystem::path> find(const std::string& library_path,
                                     std::vector<std::filesystem::path>* looked_in = nullptr) const;

  // The library paths of every .hlsl file in the subfolder `kind` ("materials", "post") of any
  // folder, sorted, each once.
  std::vector<std::string> files(const std::string& kind) const;

  // "a, b, c": the folders, for messages.
  std::string describe() const;

 private:
  std::vector<std::filesystem::path> folders_;
};

}  // namespace xshade::harness
