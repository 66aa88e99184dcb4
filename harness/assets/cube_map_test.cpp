#include "harness/assets/cube_map.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "harness/assets/equirect.h"

namespace xshade::harness {
namespace {

// The face and (s, t) a direction selects, written from the major-axis table the APIs publish
// (OpenGL 4.5 section 8.13, Direct3D's cube addressing): the inverse cube_face_direction must be.
struct FaceTexel {
  uint32_t face;
  glm::vec2 st;
};
FaceTexel select_face(glm::vec3 r) {
  const glm::vec3 a = glm::abs(r);
  float sc, tc, ma;
  uint32_t face;
  if (a.x >= a.y && a.x >= a.z) {
    face = r.x > 0 ? 0 : 1, ma = a.x, sc = r.x > 0 ? -r.z : r.z, tc = -r.y;
  } else if (a.y >= a.z) {
    face = r.y > 0 ? 2 : 3, ma = a.y, sc = r.x, tc = r.y > 0 ? r.z : -r.z;
  } else {
    face = r.z > 0 ? 4 : 5, ma = a.z, sc = r.z > 0 ? r.x : -r.x, tc = -r.y;
  }
  return {face, {0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)}};
}

TEST(CubeMap, FaceDirectionsAreTheInverseOfTheApisFaceSelection) {
  for (uint32_t face = 0; face < kCubeFaces; ++face)
    for (glm::vec2 st : {glm::vec2(0.5f), glm::vec2(0.1f, 0.2f), glm::vec2(0.9f, 0.3f), glm::vec2(0.25f, 0.8f)}) {
      const FaceTexel selected = select_face(cube_face_direction(face, st));
      EXPECT_EQ(selected.face, face) << "st " << st.x << ", " << st.y;
      EXPECT_NEAR(selected.st.x, st.x, 1e-6f) << "face " << face;
      EXPECT_NEAR(selected.st.y, st.y, 1e-6f) << "face " << face;
    }
}

TEST(CubeMap, FacesCentresLookAlongTheirAxes) {
  const glm::vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (uint32_t face = 0; face < kCubeFaces; ++face) EXPECT_EQ(cube_face_direction(face, glm::vec2(0.5f)), axes[face]);
  // The first row of +z is its top (+y), its first column its left (-x), as a viewer inside
  // the cube looking along +z with +y up sees it in Direct3D's left-handed frame.
  EXPECT_EQ(cube_face_direction(4, {0.0f, 0.0f}), glm::vec3(-1, 1, 1));
}

glm::vec4 texel(const TextureData& cube, uint32_t level, uint32_t face, uint32_t x, uint32_t y) {
  const uint32_t size = std::max(1u, cube.width >> level);
  glm::vec4 value;
  std::memcpy(&value, cube.levels[level].data() + ((size_t(face) * size + y) * size + x) * sizeof(glm::vec4),
              sizeof value);
  return value;
}

// An environment whose colour is its direction: every cube texel must hold its own direction.
TEST(CubeMap, FromAnEquirectEachTexelHoldsWhatLiesAlongIt) {
  FloatImage equirect(256, 128);
  for (uint32_t y = 0; y < 128; ++y)
    for (uint32_t x = 0; x < 256; ++x) equirect.set(x, y, glm::vec4(equirect_texel_direction(x, y, 256, 128), 1.0f));
  const TextureData cube = cube_from_equirect(equirect, 16);
  EXPECT_EQ(cube.dimension, TextureDimension::Cube);
  EXPECT_EQ(cube.layers, kCubeFaces);
  EXPECT_EQ(cube.levels.size(), 5u);  // 16, 8, 4, 2, 1
  EXPECT_TRUE(validate_texture(cube, 4096));
  for (uint32_t face = 0; face < kCubeFaces; ++face)
    for (uint32_t y = 0; y < 16; y += 5)
      for (uint32_t x = 0; x < 16; x += 3) {
        const glm::vec3 d =
            glm::normalize(cube_face_direction(face, {(float(x) + 0.5f) / 16.0f, (float(y) + 0.5f) / 16.0f}));
        const glm::vec4 value = texel(cube, 0, face, x, y);
        // Bilinear filtering of a smooth function at 4 texels a face texel: within 0.05.
        EXPECT_NEAR(glm::length(glm::vec3(value) - d), 0.0f, 0.05f) << "face " << face << " texel " << x << ", " << y;
      }
}

TEST(CubeMap, FromFacesRefusesFacesThatAreNotOneSquareSize) {
  std::array<FloatImage, kCubeFaces> faces;
  for (FloatImage& face : faces) face = FloatImage(4, 4);
  EXPECT_TRUE(cube_from_faces(faces));
  faces[3] = FloatImage(4, 2);
  auto not_square = cube_from_faces(faces);
  ASSERT_FALSE(not_square);
  EXPECT_EQ(not_square.error().message, "cube face -y is 4x2: a face must be square");
  faces[3] = FloatImage(2, 2);
  auto other_size = cube_from_faces(faces);
  ASSERT_FALSE(other_size);
  EXPECT_EQ(other_size.error().message, "cube face -y is 2x2, face +x 4x4: every face must be the same size");
}

TEST(CubeMap, FromFacesKeepsEachFaceInItsLayerAndMipsIt) {
  std::array<FloatImage, kCubeFaces> faces;
  for (uint32_t f = 0; f < kCubeFaces; ++f) {
    faces[f] = FloatImage(2, 2);
    for (uint32_t i = 0; i < 4; ++i) faces[f].set(i % 2, i / 2, glm::vec4(float(f), float(i), 0.0f, 1.0f));
  }
  auto cube = cube_from_faces(faces);
  ASSERT_TRUE(cube);
  ASSERT_EQ(cube->levels.size(), 2u);
  for (uint32_t f = 0; f < kCubeFaces; ++f) {
    EXPECT_EQ(texel(*cube, 0, f, 1, 0), glm::vec4(float(f), 1.0f, 0.0f, 1.0f));
    EXPECT_EQ(texel(*cube, 1, f, 0, 0), glm::vec4(float(f), 1.5f, 0.0f, 1.0f));  // the mean of 0..3
  }
}

}  // namespace
}  // namespace xshade::harness
