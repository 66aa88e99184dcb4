// Textures a scene names: the built-ins (white, black, checker, flat normal) and image files,
// each uploaded as RGBA32F with a full mip chain so that minified materials filter the same way
// on every lane.
#pragma once

#include "harness/backend/backend.h"
#include "harness/image/image.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

// A box-filtered mip chain down to 1x1, level 0 = `image`.
TextureData texture_with_mips(const FloatImage& image);

// The next mip level of `image`: half its size (at least 1), each texel the mean of four.
FloatImage half_size(const FloatImage& image);

// The image's floats as a texture level's bytes (RGBA32F).
std::vector<std::byte> float_bytes(const FloatImage& image);

// The image of a texture reference: a built-in is generated, a file read (linear RGBA).
Result<FloatImage> texture_image(const TextureRef& texture);

}  // namespace xshade::harness
