// libFuzzer target: any bytes as golden/MANIFEST.toml. The reader must report, never crash, hang
// or read out of bounds; a manifest it accepts must come back the same through the writer (bless
// rewrites the whole file, so anything it cannot write back would be lost).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/gate/golden_manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace xshade::harness;
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto manifest = parse_golden_manifest(text, "MANIFEST.toml");
  if (!manifest) {
    (void)manifest.error().to_string();
    return 0;
  }
  const std::string written = format_golden_manifest(*manifest);
  auto again = parse_golden_manifest(written, "MANIFEST.toml");
  if (!again || again->entries.size() != manifest->entries.size()) std::abort();
  for (size_t i = 0; i < manifest->entries.size(); ++i) {
    const GoldenEntry& a = manifest->entries[i];
    const GoldenEntry& b = again->entries[i];
    if (a.scene != b.scene || a.lane != b.lane || a.reason != b.reason || a.blessed_by != b.blessed_by ||
        a.date != b.date || a.hash != b.hash || a.float_hash != b.float_hash)
      std::abort();
  }
  return 0;
}
