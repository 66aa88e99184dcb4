// Images in memory: float RGBA, row 0 at the top.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

namespace xshade::harness {

struct FloatImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // width * height * 4 floats, row-major, row 0 at the top

  FloatImage() = default;
  FloatImage(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t(w) * h * 4, 0.0f) {}

  glm::vec4 at(uint32_t x, uint32_t y) const {
    const float* p = &rgba[(size_t(y) * width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
  void set(uint32_t x, uint32_t y, glm::vec4 value) {
    float* p = &rgba[(size_t(y) * width + x) * 4];
    p[0] = value.r, p[1] = value.g, p[2] = value.b, p[3] = value.a;
  }
};

}  // namespace xshade::harness

namespace xshade::harness {

// Bit-for-bit equality of two images of the same size (NaN equals NaN with the same bits).
bool bitwise_equal(const FloatImage& a, const FloatImage& b);

// The image with its rows in the opposite order: a target stored bottom row first, upright.
void flip_rows(FloatImage& image);

// The largest per-channel absolute difference and where it is. A channel where one image is NaN
// or infinite and the other is not the same value counts as an infinite difference.
struct ImageDifference {
  double max = 0.0;
  uint32_t x = 0;
  uint32_t y = 0;
  uint32_t channel = 0;
};
ImageDifference max_difference(const FloatImage& a, const FloatImage& b);

// The float image as bytes, exact and quick to write and read: how a worker hands its image to
// the process that started it ("xsfimg1\0", width and height as uint32 in host order, since both
// are one program on one machine, then the RGBA floats).
std::string float_image_bytes(const FloatImage& image);
// The image of float_image_bytes; empty when `bytes` are not such an image.
std::optional<FloatImage> float_image_from(std::string_view bytes);

}  // namespace xshade::harness
