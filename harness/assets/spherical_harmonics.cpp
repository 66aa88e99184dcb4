#include "harness/assets/spherical_harmonics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace xshade::harness {
namespace {

// The normalisation constants, exact; they round to the six-digit values in the header.
const double kBand0 = 0.5 * std::sqrt(1.0 / std::numbers::pi);         // 0.282095
const double kBand1 = std::sqrt(3.0 / (4.0 * std::numbers::pi));       // 0.488603
const double kProduct = 0.5 * std::sqrt(15.0 / std::numbers::pi);      // 1.092548
const double kZonal = 0.25 * std::sqrt(5.0 / std::numbers::pi);        // 0.315392
const double kDifference = 0.25 * std::sqrt(15.0 / std::numbers::pi);  // 0.546274

// The cosine lobe's transfer per band divided by pi: A0 / pi, A1 / pi, A2 / pi.
constexpr std::array<double, 9> kConvolution = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};

// Integrals over one row of texels of the theta-dependent factors, with t = cos(theta) and the
// solid-angle weight sin(theta) dtheta = -dt: the integrals run over t from the row's bottom
// edge to its top edge.
struct RowIntegrals {
  double one, t, sine, sine_t, sine2, t2;  // 1, t, sin, sin*t, sin^2, t^2
};

RowIntegrals row_integrals(uint32_t y, uint32_t height) {
  double t0 = std::cos(std::numbers::pi * y / height);        // top edge
  double t1 = std::cos(std::numbers::pi * (y + 1) / height);  // bottom edge
  auto sine_antiderivative = [](double t) { return 0.5 * (t * std::sqrt(std::max(0.0, 1.0 - t * t)) + std::asin(t)); };
  auto sine_t_antiderivative = [](double t) { return -std::pow(std::max(0.0, 1.0 - t * t), 1.5) / 3.0; };
  RowIntegrals r{};
  r.one = t0 - t1;
  r.t = 0.5 * (t0 * t0 - t1 * t1);
  r.sine = sine_antiderivative(t0) - sine_antiderivative(t1);
  r.sine_t = sine_t_antiderivative(t0) - sine_t_antiderivative(t1);
  r.t2 = (t0 * t0 * t0 - t1 * t1 * t1) / 3.0;
  r.sine2 = r.one - r.t2;
  return r;
}

// Integrals over one column of texels of the phi-dependent factors, phi = (u - 0.5) * 2 pi.
struct ColumnIntegrals {
  double one, cosine, sine, cosine2, sine2, sine_cosine;
};

ColumnIntegrals column_integrals(uint32_t x, uint32_t width) {
  double p0 = (double(x) / width - 0.5) * 2.0 * std::numbers::pi;
  double p1 = (double(x + 1) / width - 0.5) * 2.0 * std::numbers::pi;
  ColumnIntegrals c{};
  c.one = p1 - p0;
  c.cosine = std::sin(p1) - std::sin(p0);
  c.sine = std::cos(p0) - std::cos(p1);
  c.cosine2 = 0.5 * c.one + 0.25 * (std::sin(2.0 * p1) - std::sin(2.0 * p0));
  c.sine2 = c.one - c.cosine2;
  c.sine_cosine = 0.5 * (std::sin(p1) * std::sin(p1) - std::sin(p0) * std::sin(p0));
  return c;
}

// The integral of each basis function over one texel, each written as a theta factor times a phi
// factor through x = sin(theta) sin(phi), y = cos(theta), z = sin(theta) cos(phi).
std::array<double, 9> texel_integrals(const RowIntegrals& r, const ColumnIntegrals& c) {
  return {
      kBand0 * r.one * c.one,
      kBand1 * r.t * c.one,
      kBand1 * r.sine * c.cosine,
      kBand1 * r.sine * c.sine,
      kProduct * r.sine_t * c.sine,
      kProduct * r.sine_t * c.cosine,
      kZonal * (3.0 * r.sine2 * c.cosine2 - r.one * c.one),
      kProduct * r.sine2 * c.sine_cosine,
      kDifference * (r.sine2 * c.sine2 - r.t2 * c.one),
  };
}

}  // namespace

std::array<float, 9> sh_basis(glm::vec3 n) {
  const double x = n.x, y = n.y, z = n.z;
  return {float(kBand0),
          float(kBand1 * y),
          float(kBand1 * z),
          float(kBand1 * x),
          float(kProduct * x * y),
          float(kProduct * y * z),
          float(kZonal * (3.0 * z * z - 1.0)),
          float(kProduct * x * z),
          float(kDifference * (x * x - y * y))};
}

glm::vec3 sh_evaluate(const ShCoefficients& coefficients, glm::vec3 n) {
  std::array<float, 9> basis = sh_basis(n);
  glm::vec3 sum(0.0f);
  for (size_t i = 0; i < 9; ++i) sum += coefficients[i] * basis[i];
  return sum;
}

ShCoefficients irradiance_sh(const FloatImage& equirect_radiance) {
  const uint32_t width = equirect_radiance.width, height = equirect_radiance.height;
  std::vector<ColumnIntegrals> columns(width);
  for (uint32_t x = 0; x < width; ++x) columns[x] = column_integrals(x, width);

  std::array<std::array<double, 3>, 9> sums{};
  for (uint32_t y = 0; y < height; ++y) {
    const RowIntegrals row = row_integrals(y, height);
    for (uint32_t x = 0; x < width; ++x) {
      const float* texel = &equirect_radiance.rgba[(size_t(y) * width + x) * 4];
      std::array<double, 9> weights = texel_integrals(row, columns[x]);
      for (size_t i = 0; i < 9; ++i)
        for (size_t c = 0; c < 3; ++c) sums[i][c] += weights[i] * texel[c];
    }
  }
  ShCoefficients coefficients{};
  for (size_t i = 0; i < 9; ++i)
    coefficients[i] = glm::vec3(float(kConvolution[i] * sums[i][0]), float(kConvolution[i] * sums[i][1]),
                                float(kConvolution[i] * sums[i][2]));
  return coefficients;
}

}  // namespace xshade::harness
