// libFuzzer target: any bytes as a scene file. The reader must report, never crash, hang or read
// out of bounds; what it accepts must expand into instances within the scene's work budget.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Paths in the scene resolve against this folder, which need not exist: they are checked for form.
  auto scene = xshade::harness::parse_scene(text, "/tmp/xshade_fuzz/scenes/fuzz.toml");
  if (!scene) {
    (void)scene.error().to_string();
    return 0;
  }
  const size_t instances = xshade::harness::expand_instances(*scene).size();
  if (instances > xshade::harness::kMaxSceneDraws) std::abort();  // the budget let a scene through
  return 0;
}
