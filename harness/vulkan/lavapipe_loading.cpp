#include "harness/vulkan/lavapipe_loading.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace xshade::harness {
namespace {

// lavapipe's driver manifest where the loader looks for manifests (XDG_DATA_DIRS, then /etc),
// or empty.
std::string lavapipe_manifest() {
  const char* data = std::getenv("XDG_DATA_DIRS");
  std::string folders = std::string(data && *data ? data : "/usr/local/share:/usr/share") + ":/etc";
  for (size_t start = 0; start <= folders.size();) {
    const size_t end = std::min(folders.find(':', start), folders.size());
    std::error_code error;
    for (const auto& entry :
         std::filesystem::directory_iterator(folders.substr(start, end - start) + "/vulkan/icd.d", error))
      if (entry.path().filename().string().starts_with("lvp_icd")) return entry.path().string();
    start = end + 1;
  }
  return {};
}

}  // namespace

void keep_lavapipe_loaded() {
  static const bool kept = [] {
    if (!std::getenv("VK_LOADER_DRIVERS_SELECT") && !std::getenv("VK_DRIVER_FILES") && !std::getenv("VK_ICD_FILENAMES"))
      if (const std::string manifest = lavapipe_manifest(); !manifest.empty())
        setenv("VK_DRIVER_FILES", manifest.c_str(), 0);
    for (const char* library : {"libvulkan.so.1", "libvulkan_lvp.so"})
      dlopen(library, RTLD_NOW | RTLD_NODELETE);  // a missing one is reported where it is used
    return true;
  }();
  (void)kept;
}

}  // namespace xshade::harness
