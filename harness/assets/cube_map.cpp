#include "harness/assets/cube_map.h"

#include <fmt/format.h>

#include "harness/assets/equirect.h"
#include "harness/assets/scene_textures.h"
#include "harness/assets/specular_prefilter.h"

namespace xshade::harness {
namespace {

// One face of a cube level, each texel read along its centre's direction.
FloatImage face_from_equirect(const FloatImage& equirect, uint32_t face, uint32_t size) {
  FloatImage image(size, size);
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) {
      const glm::vec2 st{(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)};
      image.set(x, y, sample_equirect(equirect, equirect_uv(glm::normalize(cube_face_direction(face, st)))));
    }
  return image;
}

void append(std::vector<std::byte>& level, const FloatImage& face) {
  const std::vector<std::byte> bytes = float_bytes(face);
  level.insert(level.end(), bytes.begin(), bytes.end());
}

TextureData empty_cube(uint32_t size) {
  TextureData cube{TextureFormat::Rgba32Float, size, size, {}};
  cube.dimension = TextureDimension::Cube;
  cube.layers = kCubeFaces;
  return cube;
}

}  // namespace

glm::vec3 cube_face_direction(uint32_t face, glm::vec2 st) {
  const float sc = 2.0f * st.x - 1.0f, tc = 2.0f * st.y - 1.0f;
  switch (face) {
    case 0: return {1.0f, -tc, -sc};
    case 1: return {-1.0f, -tc, sc};
    case 2: return {sc, 1.0f, tc};
    case 3: return {sc, -1.0f, -tc};
    case 4: return {sc, -tc, 1.0f};
    default: return {-sc, -tc, -1.0f};
  }
}

Result<TextureData> cube_from_faces(const std::array<FloatImage, kCubeFaces>& faces) {
  static constexpr const char* kNames[kCubeFaces] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  const uint32_t size = faces[0].width;
  for (uint32_t f = 0; f < kCubeFaces; ++f) {
    if (faces[f].width != faces[f].height)
      return fail(ErrorKind::UserInput, fmt::format("cube face {} is {}x{}: a face must be square", kNames[f],
                                                    faces[f].width, faces[f].height));
    if (faces[f].width != size)
      return fail(ErrorKind::UserInput,
                  fmt::format("cube face {} is {}x{}, face +x {}x{}: every face must be the same size", kNames[f],
                              faces[f].width, faces[f].height, size, size));
  }
  TextureData cube = empty_cube(size);
  std::array<FloatImage, kCubeFaces> level = faces;
  while (true) {
    std::vector<std::byte>& bytes = cube.levels.emplace_back();
    for (const FloatImage& face : level) append(bytes, face);
    if (level[0].width == 1) break;
    for (FloatImage& face : level) face = half_size(face);
  }
  return cube;
}

TextureData cube_from_equirect(const FloatImage& equirect, uint32_t face_size) {
  const FloatImage source = resample_equirect(equirect, 4 * face_size, 2 * face_size);
  std::array<FloatImage, kCubeFaces> faces;
  for (uint32_t f = 0; f < kCubeFaces; ++f) faces[f] = face_from_equirect(source, f, face_size);
  return *cube_from_faces(faces);  // six square faces of one size
}

TextureData cube_from_prefiltered(const TextureData& prefiltered_equirect) {
  const uint32_t size = std::max(1u, prefiltered_equirect.width / 4);
  TextureData cube = empty_cube(size);
  for (uint32_t level = 0; level < prefiltered_equirect.levels.size(); ++level) {
    const FloatImage equirect = prefiltered_level(prefiltered_equirect, level);
    std::vector<std::byte>& bytes = cube.levels.emplace_back();
    for (uint32_t f = 0; f < kCubeFaces; ++f)
      append(bytes, face_from_equirect(equirect, f, std::max(1u, size >> level)));
  }
  return cube;
}

}  // namespace xshade::harness
