#include "harness/assets/equirect.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace xshade::harness {

glm::vec2 equirect_uv(glm::vec3 direction) {
  double u = 0.5 + std::atan2(double(direction.x), double(direction.z)) / (2.0 * std::numbers::pi);
  double v = std::acos(std::clamp(double(direction.y), -1.0, 1.0)) / std::numbers::pi;
  return {float(u), float(v)};
}

glm::vec3 equirect_direction(glm::vec2 uv) {
  double phi = (double(uv.x) - 0.5) * 2.0 * std::numbers::pi;
  double theta = double(uv.y) * std::numbers::pi;
  double sin_theta = std::sin(theta);
  return {float(sin_theta * std::sin(phi)), float(std::cos(theta)), float(sin_theta * std::cos(phi))};
}

glm::vec3 equirect_texel_direction(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
  return equirect_direction({float((x + 0.5) / width), float((y + 0.5) / height)});
}

double equirect_texel_solid_angle(uint32_t y, uint32_t width, uint32_t height) {
  double theta_top = std::numbers::pi * y / height;
  double theta_bottom = std::numbers::pi * (y + 1) / height;
  return (2.0 * std::numbers::pi / width) * (std::cos(theta_top) - std::cos(theta_bottom));
}

glm::vec4 sample_equirect(const FloatImage& image, glm::vec2 uv) {
  const auto width = int64_t(image.width), height = int64_t(image.height);
  double x = double(uv.x) * double(width) - 0.5;
  double y = double(uv.y) * double(height) - 0.5;
  double x_floor = std::floor(x), y_floor = std::floor(y);
  auto fx = float(x - x_floor), fy = float(y - y_floor);
  auto column = [width](int64_t i) { return uint32_t(((i % width) + width) % width); };
  auto row = [height](int64_t j) { return uint32_t(std::clamp<int64_t>(j, 0, height - 1)); };
  const auto x0 = int64_t(x_floor), y0 = int64_t(y_floor);
  glm::vec4 top = glm::mix(image.at(column(x0), row(y0)), image.at(column(x0 + 1), row(y0)), fx);
  glm::vec4 bottom = glm::mix(image.at(column(x0), row(y0 + 1)), image.at(column(x0 + 1), row(y0 + 1)), fx);
  return glm::mix(top, bottom, fy);
}

FloatImage resample_equirect(const FloatImage& image, uint32_t width, uint32_t height) {
  FloatImage result(width, height);
  // Enough samples per output texel to touch every source texel under it.
  const uint32_t grid_x = std::max(1u, (image.width + width - 1) / width);
  const uint32_t grid_y = std::max(1u, (image.height + height - 1) / height);
  const float weight = 1.0f / float(grid_x * grid_y);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      glm::vec4 sum(0.0f);
      for (uint32_t j = 0; j < grid_y; ++j)
        for (uint32_t i = 0; i < grid_x; ++i) {
          glm::vec2 uv{float((x + (i + 0.5) / grid_x) / width), float((y + (j + 0.5) / grid_y) / height)};
          sum += sample_equirect(image, uv);
        }
      result.set(x, y, sum * weight);
    }
  return result;
}

}  // namespace xshade::harness
