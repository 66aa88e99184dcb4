// A driver library opened at run time (dlopen), so that the binary links no driver and a machine
// without one still runs the lanes that do not need it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "base/result.h"

namespace xshade::harness {

class SharedLibrary {
 public:
  // RTLD_NODELETE: Mesa and LLVM stay loaded after the last dlclose; unloading and reloading
  // them for every backend gains nothing and risks their global state. Fails with dlerror's words.
  static Result<SharedLibrary> open(const std::string& path);

  SharedLibrary() = default;
  SharedLibrary(SharedLibrary&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  SharedLibrary& operator=(SharedLibrary&& other) noexcept;
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;
  ~SharedLibrary();

  // The address of an exported symbol, or null.
  void* symbol(const char* name) const;
  // Points `function` at the symbol `name`, or adds `name` to `missing` when there is none.
  template <class Function>
  void load(Function& function, const char* name, std::vector<std::string>& missing) const {
    // A function pointer travels through void* here, as with dlsym; POSIX guarantees this works.
    function = reinterpret_cast<Function>(symbol(name));
    if (function == nullptr) missing.emplace_back(name);
  }

 private:
  explicit SharedLibrary(void* handle) : handle_(handle) {}
  void* handle_ = nullptr;
};

// `given` when it is not empty, else the environment variable `variable` when set and not empty,
// else `fallback`: how a driver library's name is chosen (XSHADE_OSMESA_LIBRARY, XSHADE_EGL_LIBRARY).
std::string library_name(const std::string& given, const char* variable, const char* fallback);

}  // namespace xshade::harness
