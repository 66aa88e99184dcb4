#include "harness/backend.h"

namespace xshade::harness {

size_t bytes_per_texel(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm:
    case TextureFormat::Rgba8Srgb: return 4;
    case TextureFormat::Rgba32Float: return 16;
  }
  return 0;
}

}  // namespace xshade::harness
