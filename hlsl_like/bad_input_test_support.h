// What the bad-input tests share: a compile of text, its diagnostics rendered, a temporary folder
// of files to include, and the limits a hostile input must stay within.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/compiler.h"

namespace xshade::hlsl::bad_input {

namespace fs = std::filesystem;
using Strings = std::vector<std::string>;
using namespace std::string_literals;

// No single hostile input may take longer than this (optimised build). The largest are 1 MiB, which
// a linear pass reads in 0.15-0.2 s here, and the suite runs two tests at once on two cores, which
// can double that; a pass quadratic in the input would take minutes (10^12 steps). 1 s tells the
// two apart with room, where 0.25 s failed under a loaded run.
inline constexpr double kFastSeconds = 1.0;
// The whole rendered output of a hostile input stays readable.
inline constexpr size_t kShortRender = 4096;

inline std::unique_ptr<Module> compile(const std::string& name, const std::string& text,
                                       const CompileOptions& options = {}) {
  return compile_text(name, text, options);
}

// Diagnostic `index` as rendered; "" when there is none, so that a missing one fails readably.
inline std::string rendered(const Module& module, size_t index) {
  return index < module.diagnostics.diagnostics().size() ? module.diagnostics.render(index) : std::string();
}
inline std::string first(const Module& module) { return rendered(module, 0); }

inline Strings all_rendered(const Module& module) {
  Strings out;
  for (size_t i = 0; i < module.diagnostics.diagnostics().size(); ++i) out.push_back(module.diagnostics.render(i));
  return out;
}

// The errors only, rendered (warnings and notes left out).
inline Strings errors_rendered(const Module& module) {
  Strings out;
  const auto& diagnostics = module.diagnostics.diagnostics();
  for (size_t i = 0; i < diagnostics.size(); ++i)
    if (diagnostics[i].severity == Severity::Error) out.push_back(module.diagnostics.render(i));
  return out;
}

// "file:line:col: severity: message" of every diagnostic, without the source excerpt.
inline Strings headers(const Module& module) {
  Strings out;
  for (const Diagnostic& d : module.diagnostics.diagnostics()) out.push_back(d.to_string());
  return out;
}

// A fresh folder under the system's temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::random_device random;
    for (;;) {
      const fs::path candidate =
          fs::temp_directory_path() / ("xshade_bad_input_" + std::to_string(random()) + "_" + std::to_string(random()));
      if (fs::create_directory(candidate)) {
        path_ = fs::canonical(candidate);  // the front end names included files by canonical path
        return;
      }
    }
  }
  ~TempDir() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

 private:
  fs::path path_;
};

// True when every byte is printable ASCII or a line break: what a terminal can show as it is.
inline bool printable(const std::string& text) {
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c != '\n' && (byte < 0x20 || byte >= 0x7f)) return false;
  }
  return true;
}

}  // namespace xshade::hlsl::bad_input
