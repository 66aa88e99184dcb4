// The equirectangular (latitude-longitude) mapping between directions and images, shared by the
// environment code and the shaders that sample environments.
//
// World space is right-handed with +y up; directions are unit vectors. A direction d maps to
//   u = 0.5 + atan2(d.x, d.z) / (2 pi),   v = acos(clamp(d.y, -1, 1)) / pi,
// so v = 0 (image row 0, the top) is straight up, v = 1 straight down, u = 0.5 is +z, u = 0.75
// is +x, and the seam u = 0 = 1 lies at -z: behind the objects as the default camera (at +z,
// looking toward -z) sees them. Texel (x, y) of a W x H image has its centre at
// uv ((x + 0.5) / W, (y + 0.5) / H).
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "harness/image/image.h"

namespace xshade::harness {

glm::vec2 equirect_uv(glm::vec3 direction);
// The inverse of equirect_uv: the unit direction at uv.
glm::vec3 equirect_direction(glm::vec2 uv);
// The direction through the centre of texel (x, y) of a width x height image.
glm::vec3 equirect_texel_direction(uint32_t x, uint32_t y, uint32_t width, uint32_t height);

// The exact solid angle of one texel in row y of a width x height equirect image, in steradians:
// (2 pi / width) * (cos(theta_top) - cos(theta_bottom)). A whole image sums to 4 pi.
double equirect_texel_solid_angle(uint32_t y, uint32_t width, uint32_t height);

// Bilinear filtering at uv, wrapping across the u seam and clamping at the poles (v).
glm::vec4 sample_equirect(const FloatImage& image, glm::vec2 uv);

// The image resampled to width x height: each output texel averages a square grid of bilinear
// samples spaced as finely as the source's texels, a box filter when shrinking and plain
// bilinear filtering when enlarging.
FloatImage resample_equirect(const FloatImage& image, uint32_t width, uint32_t height);

}  // namespace xshade::harness
