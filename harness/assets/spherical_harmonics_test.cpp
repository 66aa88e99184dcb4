#include "harness/assets/spherical_harmonics.h"

#include <functional>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "harness/assets/equirect.h"

namespace xshade::harness {
namespace {

FloatImage equirect_of(const std::function<float(glm::vec3)>& radiance, uint32_t width = 256, uint32_t height = 128) {
  FloatImage image(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      image.set(x, y, glm::vec4(radiance(equirect_texel_direction(x, y, width, height)), 0.0f, 0.0f, 1.0f));
  return image;
}

std::vector<glm::vec3> test_directions() {
  std::vector<glm::vec3> directions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (float u = 0.05f; u < 1.0f; u += 0.15f)
    for (float v = 0.1f; v < 1.0f; v += 0.2f) directions.push_back(equirect_direction({u, v}));
  return directions;
}

TEST(ShBasis, MatchesTheListedConstants) {
  const glm::vec3 n = glm::normalize(glm::vec3(1, 2, 3));
  const float x = n.x, y = n.y, z = n.z;
  const float expected[9] = {0.282095f,
                             0.488603f * y,
                             0.488603f * z,
                             0.488603f * x,
                             1.092548f * x * y,
                             1.092548f * y * z,
                             0.315392f * (3 * z * z - 1),
                             1.092548f * x * z,
                             0.546274f * (x * x - y * y)};
  std::array<float, 9> basis = sh_basis(n);
  // The listed constants have six decimals.
  for (size_t i = 0; i < 9; ++i) EXPECT_NEAR(basis[i], expected[i], 1e-6f) << i;
}

TEST(IrradianceSh, ConstantRadianceGivesItselfInEveryDirection) {
  const float radiance = 2.5f;
  ShCoefficients sh = irradiance_sh(equirect_of([=](glm::vec3) { return radiance; }));
  // Every texel integral is exact, so only float rounding of the coefficients remains.
  for (glm::vec3 n : test_directions()) EXPECT_NEAR(sh_evaluate(sh, n).x, radiance, 2e-6f * radiance);
  EXPECT_EQ(sh_evaluate(sh, {0, 1, 0}).y, 0.0f);  // the other channels were black
}

// Texels hold the radiance at their centres: a midpoint rule whose error is of the order of
// (pi / 128)^2 / 8 ~ 1e-4 of the radiance's variation; 1e-3 leaves room for the sum of terms.
constexpr float kMidpointTolerance = 1e-3f;

TEST(IrradianceSh, LinearRadianceGivesTheCosineConvolution) {
  // For L(d) = a + b.d, irradiance(n) / pi = a + (2/3) b.n: the constant passes unchanged and the
  // integral of d (n.d) over the hemisphere around n is (2 pi / 3) n.
  const float a = 1.0f;
  const glm::vec3 b{0.5f, -0.25f, 0.75f};
  ShCoefficients sh = irradiance_sh(equirect_of([=](glm::vec3 d) { return a + glm::dot(b, d); }));
  for (glm::vec3 n : test_directions())
    EXPECT_NEAR(sh_evaluate(sh, n).x, a + (2.0f / 3.0f) * glm::dot(b, n), kMidpointTolerance) << n.x << n.y << n.z;
}

TEST(IrradianceSh, QuadraticRadianceIsScaledByAQuarterInBandTwo) {
  // L(d) = y^2 + x z = 1/3 + (y^2 - 1/3) + x z, where (y^2 - 1/3) and x z are pure band 2, which
  // the cosine lobe scales by A2 / pi = 1/4: irradiance / pi = 1/3 + (y^2 - 1/3) / 4 + x z / 4.
  ShCoefficients sh = irradiance_sh(equirect_of([](glm::vec3 d) { return d.y * d.y + d.x * d.z; }));
  for (glm::vec3 n : test_directions()) {
    float expected = 1.0f / 3.0f + (n.y * n.y - 1.0f / 3.0f) / 4.0f + n.x * n.z / 4.0f;
    EXPECT_NEAR(sh_evaluate(sh, n).x, expected, kMidpointTolerance) << n.x << " " << n.y << " " << n.z;
  }
}

}  // namespace
}  // namespace xshade::harness
