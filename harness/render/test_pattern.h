// The orientation pattern: the first thing every lane must draw identically.
//
// Clip space, Direct3D convention (+y up): the top-left quadrant is red, the top-right green, the
// bottom-left blue, and the bottom-right quadrant shows a 4x4 texture, uv (0,0) at the quad's
// top-left corner, whose top-left texel is white and every other texel a distinct dark colour.
// A lane that flips y, mirrors x or reads textures upside down puts a colour in the wrong place.
#pragma once

#include <cstdint>

#include <glm/vec4.hpp>

#include "harness/backend/backend.h"
#include "harness/render/lanes.h"

namespace xshade::harness::test_pattern {

inline constexpr glm::vec4 kTopLeft{1.0f, 0.0f, 0.0f, 1.0f};
inline constexpr glm::vec4 kTopRight{0.0f, 1.0f, 0.0f, 1.0f};
inline constexpr glm::vec4 kBottomLeft{0.0f, 0.0f, 1.0f, 1.0f};
inline constexpr glm::vec4 kFirstTexel{1.0f, 1.0f, 1.0f, 1.0f};
inline constexpr uint32_t kTextureSize = 4;

// The texel at (column, row) of the pattern texture, row 0 at the top: kFirstTexel at (0,0).
glm::vec4 texel(uint32_t column, uint32_t row);

// Renders the pattern into a new size x size target of `backend`, which runs `lane`.
Result<FloatImage> render(Backend& backend, Lane lane, uint32_t size);

}  // namespace xshade::harness::test_pattern
