// Cube maps made on the CPU, in the face order and orientation Direct3D, OpenGL and Vulkan share:
// faces +X, -X, +Y, -Y, +Z, -Z, and on each face texel (s, t) = (0, 0) at the first uploaded row's
// left (backend.h). With sc = 2 s - 1 and tc = 2 t - 1 the face's directions are
//   +X (1, -tc, -sc)   -X (-1, -tc, sc)   +Y (sc, 1, tc)   -Y (sc, -1, -tc)   +Z (sc, -tc, 1)   -Z (-sc, -tc, -1)
// in the scene's world (right-handed, +y up): sampling a cube with direction d reads what lies
// along d, as sampling an equirect image with equirect_uv(d) does.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "base/result.h"
#include "harness/backend/backend.h"
#include "harness/image/image.h"

namespace xshade::harness {

inline constexpr uint32_t kCubeFaces = 6;

// The (not normalised) direction through point st in [0, 1]^2 of `face` (0..5, the order above).
glm::vec3 cube_face_direction(uint32_t face, glm::vec2 st);

// A cube of six square faces of one size, with a box-filtered mip chain of each face down to 1x1.
// Fails naming the face that is not square or not the size of the first.
Result<TextureData> cube_from_faces(const std::array<FloatImage, kCubeFaces>& faces);

// A cube of `face_size` texels a side (with mips) from an equirect image (equirect.h): each texel
// the bilinear sample along its centre's direction of the image resampled to 4 x 2 face sizes, so
// that a large image is box-filtered rather than aliased.
TextureData cube_from_equirect(const FloatImage& equirect, uint32_t face_size);

// The cube form of a prefiltered equirect texture (specular_prefilter.h): level i of the cube,
// faces of (width / 4) >> i texels, holds level i of the equirect texture, the same roughness.
TextureData cube_from_prefiltered(const TextureData& prefiltered_equirect);

}  // namespace xshade::harness
