#include "harness/image/image.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

namespace xshade::harness {

bool bitwise_equal(const FloatImage& a, const FloatImage& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

void flip_rows(FloatImage& image) {
  const size_t row = size_t(image.width) * 4;
  for (uint32_t top = 0, bottom = image.height; top + 1 < bottom; ++top, --bottom)
    std::swap_ranges(image.rgba.begin() + top * row, image.rgba.begin() + (top + 1) * row,
                     image.rgba.begin() + (bottom - 1) * row);
}

ImageDifference max_difference(const FloatImage& a, const FloatImage& b) {
  assert(a.width == b.width && a.height == b.height);
  ImageDifference worst;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    const float va = a.rgba[i];
    const float vb = b.rgba[i];
    double difference = 0.0;
    if (std::isnan(va) || std::isnan(vb)) {
      difference = std::isnan(va) && std::isnan(vb) ? 0.0 : std::numeric_limits<double>::infinity();
    } else if (va != vb) {
      difference = std::fabs(double(va) - double(vb));  // inf - finite is inf; inf - inf is equal
    }
    if (difference > worst.max) {
      const size_t pixel = i / 4;
      worst = {difference, uint32_t(pixel % a.width), uint32_t(pixel / a.width), uint32_t(i % 4)};
    }
  }
  return worst;
}

namespace {
constexpr char kImageMagic[8] = "xsfimg1";
}  // namespace

std::string float_image_bytes(const FloatImage& image) {
  std::string bytes(kImageMagic, sizeof kImageMagic);
  bytes.append(reinterpret_cast<const char*>(&image.width), sizeof image.width);
  bytes.append(reinterpret_cast<const char*>(&image.height), sizeof image.height);
  bytes.append(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size() * sizeof(float));
  return bytes;
}

std::optional<FloatImage> float_image_from(std::string_view bytes) {
  constexpr size_t header = sizeof kImageMagic + 2 * sizeof(uint32_t);
  if (bytes.size() < header || std::memcmp(bytes.data(), kImageMagic, sizeof kImageMagic) != 0) return std::nullopt;
  uint32_t width = 0, height = 0;
  std::memcpy(&width, bytes.data() + sizeof kImageMagic, sizeof width);
  std::memcpy(&height, bytes.data() + sizeof kImageMagic + sizeof width, sizeof height);
  if (bytes.size() != header + size_t(width) * height * 4 * sizeof(float)) return std::nullopt;
  FloatImage image(width, height);
  std::memcpy(image.rgba.data(), bytes.data() + header, image.rgba.size() * sizeof(float));
  return image;
}

}  // namespace xshade::harness
