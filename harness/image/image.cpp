#include "harness/image/image.h"

#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

namespace xshade::harness {

bool bitwise_equal(const FloatImage& a, const FloatImage& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
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

}  // namespace xshade::harness
