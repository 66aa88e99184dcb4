#include "harness/assets/scene_textures.h"

#include <cstring>

#include "harness/assets/cube_map.h"
#include "harness/assets/lut.h"
#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

FloatImage filled(uint32_t size, glm::vec4 color) {
  FloatImage image(size, size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) image.set(x, y, color);
  return image;
}

// 8 x 8 squares of 8 texels, black at the top-left: coarse enough to read at the fixed scenes'
// sizes, fine enough that its mips matter.
FloatImage checker() {
  constexpr uint32_t kSize = 64;
  constexpr uint32_t kSquare = 8;
  FloatImage image(kSize, kSize);
  for (uint32_t y = 0; y < kSize; ++y)
    for (uint32_t x = 0; x < kSize; ++x) {
      const float value = ((x / kSquare + y / kSquare) % 2) ? 1.0f : 0.0f;
      image.set(x, y, {value, value, value, 1.0f});
    }
  return image;
}

}  // namespace

FloatImage half_size(const FloatImage& image) {
  FloatImage out(std::max(1u, image.width / 2), std::max(1u, image.height / 2));
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      // Odd sizes: the last row or column is read twice rather than dropped.
      const uint32_t x0 = std::min(2 * x, image.width - 1), x1 = std::min(2 * x + 1, image.width - 1);
      const uint32_t y0 = std::min(2 * y, image.height - 1), y1 = std::min(2 * y + 1, image.height - 1);
      out.set(x, y, (image.at(x0, y0) + image.at(x1, y0) + image.at(x0, y1) + image.at(x1, y1)) * 0.25f);
    }
  return out;
}

std::vector<std::byte> float_bytes(const FloatImage& image) {
  std::vector<std::byte> bytes(image.rgba.size() * sizeof(float));
  std::memcpy(bytes.data(), image.rgba.data(), bytes.size());
  return bytes;
}

TextureData texture_with_mips(const FloatImage& image) {
  TextureData texture{TextureFormat::Rgba32Float, image.width, image.height, {}};
  FloatImage level = image;
  texture.levels.push_back(float_bytes(level));
  while (level.width > 1 || level.height > 1) {
    level = half_size(level);
    texture.levels.push_back(float_bytes(level));
  }
  return texture;
}

Result<FloatImage> texture_image(const TextureRef& texture) {
  switch (texture.source) {
    case TextureOrigin::White: return filled(1, {1.0f, 1.0f, 1.0f, 1.0f});
    case TextureOrigin::Black: return filled(1, {0.0f, 0.0f, 0.0f, 1.0f});
    case TextureOrigin::Normal: return filled(1, {0.5f, 0.5f, 1.0f, 1.0f});
    case TextureOrigin::Gray: return filled(1, {0.5f, 0.5f, 0.5f, 0.5f});
    case TextureOrigin::Red: return filled(1, {1.0f, 0.0f, 0.0f, 0.0f});
    case TextureOrigin::Clear: return filled(1, {0.0f, 0.0f, 0.0f, 0.0f});
    case TextureOrigin::Checker: return checker();
    case TextureOrigin::File: return read_image(texture.file, texture.srgb);
    case TextureOrigin::Faces:
      return fail(ErrorKind::UserInput,
                  "six faces make a cube map, not an image: the shader must declare a TextureCube");
    case TextureOrigin::Environment:
      return fail(ErrorKind::UserInput,
                  "the environment is a cube map, not an image: the shader must declare a TextureCube");
  }
  return fail(ErrorKind::Internal, "unknown texture source");
}

namespace {
// A built-in as one texel: its mean (the checker's is mid grey).
FloatImage one_texel(FloatImage image) {
  while (image.width > 1 || image.height > 1) image = half_size(image);
  return image;
}
}  // namespace

Result<TextureData> texture_data(const TextureRef& texture, TextureShape shape) {
  const bool lut_file = texture.source == TextureOrigin::File && texture.file.extension() == ".cube";
  const bool built_in = texture.source != TextureOrigin::File && texture.source != TextureOrigin::Faces &&
                        texture.source != TextureOrigin::Environment;
  if (shape.multisampled || (shape.dimension != TextureDimension::Tex2D && shape.dimension != TextureDimension::Cube &&
                             shape.dimension != TextureDimension::Tex3D))
    return fail(ErrorKind::UserInput, "the shader declares a " + shape_name(shape) +
                                          ", and a scene gives 2D textures, cube maps and 3D textures only");
  if (texture.source == TextureOrigin::Environment)
    return fail(ErrorKind::Internal, "the environment is given by the renderer, not made here");  // scene_renderer.cpp
  if (shape.dimension == TextureDimension::Tex2D) {
    if (lut_file) return fail(ErrorKind::UserInput, "a .cube file is a 3D LUT: the shader must declare a Texture3D");
    auto image = texture_image(texture);
    if (!image) return fail(image.error());
    return texture_with_mips(*image);
  }
  if (built_in) {  // one texel of the shape
    auto image = texture_image(texture);
    if (!image) return fail(image.error());
    TextureData data{TextureFormat::Rgba32Float, 1, 1, {}};
    data.dimension = shape.dimension;
    data.layers = shape.dimension == TextureDimension::Cube ? kCubeFaces : 1;
    std::vector<std::byte> level;
    const std::vector<std::byte> texel = float_bytes(one_texel(*image));
    for (uint32_t layer = 0; layer < data.layers; ++layer) level.insert(level.end(), texel.begin(), texel.end());
    data.levels.push_back(std::move(level));
    return data;
  }
  if (shape.dimension == TextureDimension::Cube) {
    if (lut_file)
      return fail(ErrorKind::UserInput,
                  "a .cube file is a 3D LUT, not a cube map: the shader must declare a Texture3D");
    if (texture.source == TextureOrigin::Faces) {
      std::array<FloatImage, kCubeFaces> faces;
      for (uint32_t f = 0; f < kCubeFaces; ++f) {
        auto face = read_image(texture.faces[f], texture.srgb);
        if (!face) return fail(face.error());
        faces[f] = std::move(*face);
      }
      return cube_from_faces(faces);
    }
    auto equirect = read_image(texture.file, texture.srgb);
    if (!equirect) return fail(equirect.error());
    if (equirect->width != 2 * equirect->height || equirect->width < 4)
      return fail(ErrorKind::UserInput,
                  "a cube map from one image takes an equirect image, twice as wide as high; this one is " +
                      std::to_string(equirect->width) + "x" + std::to_string(equirect->height) +
                      " (or give faces = [6 images])");
    return cube_from_equirect(*equirect, equirect->width / 4);
  }
  // Texture3D.
  if (texture.source == TextureOrigin::Faces)
    return fail(ErrorKind::UserInput, "six faces make a cube map: the shader declares a Texture3D");
  if (lut_file) return read_cube_lut(texture.file);
  auto strip = read_image(texture.file, texture.srgb);
  if (!strip) return fail(strip.error());
  return lut_from_strip(*strip);
}

}  // namespace xshade::harness
