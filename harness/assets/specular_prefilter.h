// Specular environment light: an equirect environment convolved with the GGX distribution, one
// roughness per mip level, sampled by the shaders at the level their roughness maps to.
//
// Conventions (the shaders depend on them):
// - The result is an RGBA32F equirect texture (mapping in equirect.h) of kPrefilteredLevels
//   levels, base kPrefilteredWidth x kPrefilteredHeight, level i of size (256 >> i) x (128 >> i).
// - Level i holds perceptual roughness r_i with r_i * (1.7 - 0.7 r_i) * 6 = i, Unity's mapping:
//   a shader computes mip = r * (1.7 - 0.7 r) * 6 and samples that (fractional) level.
// - GGX alpha = r (the project's materials use alpha = roughness, not its square).
// - Split-sum assumption n = v = r: the value in direction r is the integral over directions l
//   of L(l) D(n.h) (n.l), normalised by the integral of D(n.h) (n.l), with n = r and
//   h = normalize(n + l). Level 0 (r = 0) is the environment itself, a mirror.
// - Alpha is 1 everywhere.
#pragma once

#include <cstdint>

#include "harness/backend/backend.h"
#include "harness/image/image.h"

namespace xshade::harness {

inline constexpr uint32_t kPrefilteredWidth = 256;
inline constexpr uint32_t kPrefilteredHeight = 128;
inline constexpr uint32_t kPrefilteredLevels = 7;

// The mip level a shader samples for perceptual roughness r in [0, 1]: r * (1.7 - 0.7 r) * 6.
float prefiltered_mip_for_roughness(float roughness);
// Its inverse: the roughness that level `level` (0..kPrefilteredLevels - 1) holds.
float prefiltered_roughness_for_mip(float level);

// The prefiltered texture of an equirect radiance image (resampled to 256 x 128 first if it has
// another size). Each texel of levels 1.. is estimated from a fixed Hammersley set of GGX samples
// (so the result is deterministic), each read from a solid-angle-weighted mip chain of the
// source at the level whose texels cover the sample's share of the lobe (filtered importance
// sampling, Krivanek and Colbert, GPU Gems 3 ch. 20): a constant environment stays constant.
TextureData prefilter_specular(const FloatImage& equirect_radiance);

// One level of a prefiltered texture as an image (for tests and for writing it out).
FloatImage prefiltered_level(const TextureData& texture, uint32_t level);

}  // namespace xshade::harness
