#include "harness/assets/scene_textures.h"

#include <cstring>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

FloatImage filled(uint32_t size, glm::vec4 color) {
  FloatImage image(size, size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) image.set(x, y, color);
  return image;
}

// 8 x 8 squares of 8 texels, black at the top-left: coarse enough to read at the fixed scenes'
// sizes, fine enough that its mips matter.
FloatImage checker() {
  constexpr uint32_t kSize = 64;
  constexpr uint32_t kSquare = 8;
  FloatImage image(kSize, kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const float value = ((x / kSquare + y / kSquare) % 2) ? 1.0f : 0.0f;
      image.set(x, y, {value, value, value, 1.0f});
    }
  return image;
}

}  // namespace

FloatImage half_size(const FloatImage& image) {
  FloatImage out(std::max(1u, image.width / 2), std::max(1u, image.height / 2));
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      // Odd sizes: the last row or column is read twice rather than dropped.
      const uint32_t x0 = std::min(2 * x, image.width - 1), x1 = std::min(2 * x + 1, image.width - 1);
      const uint32_t y0 = std::min(2 * y, image.height - 1), y1 = std::min(2 * y + 1, image.height - 1);
      out.set(x, y, (image.at(x0, y0) + image.at(x1, y0) + image.at(x0, y1) + image.at(x1, y1)) * 0.25f);
    }
  return out;
}

std::vector<std::byte> float_bytes(const FloatImage& image) {
  std::vector<std::byte> bytes(image.rgba.size() * sizeof(float));
  std::memcpy(bytes.data(), image.rgba.data(), bytes.size());
  return bytes;
}

TextureData texture_with_mips(const FloatImage& image) {
  TextureData texture{TextureFormat::Rgba32Float, image.width, image.height, {}};
  FloatImage level = image;
  texture.levels.push_back(float_bytes(level));
  while (level.width > 1 || level.height > 1) {
    level = half_size(level);
    texture.levels.push_back(float_bytes(level));
  }
  return texture;
}

Result<FloatImage> texture_image(const TextureRef& texture) {
  switch (texture.source) {
    case TextureOrigin::White: return filled(1, {1.0f, 1.0f, 1.0f, 1.0f});
    case TextureOrigin::Black: return filled(1, {0.0f, 0.0f, 0.0f, 1.0f});
    case TextureOrigin::Normal: return filled(1, {0.5f, 0.5f, 1.0f, 1.0f});
    case TextureOrigin::Checker: return checker();
    case TextureOrigin::File: return read_image(texture.file);
  }
  return fail("unknown texture source");
}

}  // namespace xshade::harness
