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

// What a scene's texture becomes for a shader's texture of `shape` (docs/scenes.md): a 2D texture
// with mips of the image; a cube with mips from an equirect image (faces of width / 4) or from six
// faces; a 3D texture from a LUT strip or a .cube file, one level. A built-in colour fills one
// texel of any of these shapes. Fails, saying what the shape needs, for a reference that cannot
// be one (six faces for a Texture2D, a .cube for a cube), for another shape (arrays, 1D,
// multisampled) and for the environment, which the renderer gives itself.
Result<TextureData> texture_data(const TextureRef& texture, TextureShape shape);

}  // namespace xshade::harness
