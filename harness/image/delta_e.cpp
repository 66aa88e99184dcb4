#include "harness/image/delta_e.h"

#include <algorithm>
#include <cmath>

namespace xshade::harness {

namespace {

constexpr double kPi = 3.14159265358979323846;
double degrees(double radians) { return radians * (180.0 / kPi); }
double radians(double degrees) { return degrees * (kPi / 180.0); }

// CIELAB's f(t): the cube root, with a straight segment near black.
double lab_f(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

// Black against white: the largest difference a finite pair of displayable colours has, which a
// non-finite pixel is given.
double largest_difference() {
  static const double largest = ciede2000(lab_from_linear_srgb(glm::vec3(0.0f)), lab_from_linear_srgb(glm::vec3(1.0f)));
  return largest;
}

}  // namespace

Lab lab_from_linear_srgb(glm::vec3 linear) {
  const double r = std::clamp(double(linear.r), 0.0, 1.0);
  const double g = std::clamp(double(linear.g), 0.0, 1.0);
  const double b = std::clamp(double(linear.b), 0.0, 1.0);
  // IEC 61966-2-1's sRGB to XYZ, each row divided by the white it gives (its sum), so that white
  // is L 100 with no chroma however the published digits round.
  const auto row = [&](double kr, double kg, double kb) { return (kr * r + kg * g + kb * b) / (kr + kg + kb); };
  const double x = row(0.4124564, 0.3575761, 0.1804375);
  const double y = row(0.2126729, 0.7151522, 0.0721750);
  const double z = row(0.0193339, 0.1191920, 0.9503041);
  return {116.0 * lab_f(y) - 16.0, 500.0 * (lab_f(x) - lab_f(y)), 200.0 * (lab_f(y) - lab_f(z))};
}

double ciede2000(const Lab& first, const Lab& second) {
  const double c1 = std::hypot(first.a, first.b);
  const double c2 = std::hypot(second.a, second.b);
  const double c_mean7 = std::pow((c1 + c2) / 2.0, 7.0);
  const double g = 0.5 * (1.0 - std::sqrt(c_mean7 / (c_mean7 + std::pow(25.0, 7.0))));
  const double a1 = (1.0 + g) * first.a;
  const double a2 = (1.0 + g) * second.a;
  const double cp1 = std::hypot(a1, first.b);
  const double cp2 = std::hypot(a2, second.b);
  const auto hue = [](double b, double a) {
    if (a == 0.0 && b == 0.0) return 0.0;
    const double h = degrees(std::atan2(b, a));
    return h < 0.0 ? h + 360.0 : h;
  };
  const double hp1 = hue(first.b, a1);
  const double hp2 = hue(second.b, a2);

  const double dl = second.L - first.L;
  const double dc = cp2 - cp1;
  double dh = 0.0;
  if (cp1 * cp2 != 0.0) {
    dh = hp2 - hp1;
    if (dh > 180.0) dh -= 360.0;
    if (dh < -180.0) dh += 360.0;
  }
  const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(radians(dh / 2.0));

  const double l_mean = (first.L + second.L) / 2.0;
  const double cp_mean = (cp1 + cp2) / 2.0;
  double hp_mean = hp1 + hp2;
  if (cp1 * cp2 != 0.0) {
    if (std::fabs(hp1 - hp2) <= 180.0)
      hp_mean /= 2.0;
    else
      hp_mean = hp_mean < 360.0 ? (hp_mean + 360.0) / 2.0 : (hp_mean - 360.0) / 2.0;
  }
  const double t = 1.0 - 0.17 * std::cos(radians(hp_mean - 30.0)) + 0.24 * std::cos(radians(2.0 * hp_mean)) +
                   0.32 * std::cos(radians(3.0 * hp_mean + 6.0)) - 0.20 * std::cos(radians(4.0 * hp_mean - 63.0));
  const double d_theta = 30.0 * std::exp(-std::pow((hp_mean - 275.0) / 25.0, 2.0));
  const double cp_mean7 = std::pow(cp_mean, 7.0);
  const double rc = 2.0 * std::sqrt(cp_mean7 / (cp_mean7 + std::pow(25.0, 7.0)));
  const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
  const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sc = 1.0 + 0.045 * cp_mean;
  const double sh = 1.0 + 0.015 * cp_mean * t;
  const double rt = -std::sin(radians(2.0 * d_theta)) * rc;
  const double l = dl / sl;
  const double c = dc / sc;
  const double h = dH / sh;
  return std::sqrt(l * l + c * c + h * h + rt * c * h);
}

DeltaEMeasure measure_delta_e(const FloatImage& test, const FloatImage& reference, double per_pixel_threshold) {
  DeltaEMeasure measure;
  const size_t pixels = size_t(test.width) * test.height;
  measure.per_pixel.resize(pixels);
  double sum = 0.0;
  double excess = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    const float* t = &test.rgba[p * 4];
    const float* r = &reference.rgba[p * 4];
    const bool finite = std::isfinite(t[0]) && std::isfinite(t[1]) && std::isfinite(t[2]) && std::isfinite(r[0]) &&
                        std::isfinite(r[1]) && std::isfinite(r[2]);
    const double difference =
        finite ? ciede2000(lab_from_linear_srgb({t[0], t[1], t[2]}), lab_from_linear_srgb({r[0], r[1], r[2]}))
               : largest_difference();
    measure.per_pixel[p] = float(difference);
    sum += difference;
    if (difference > measure.max) {
      measure.max = difference;
      measure.max_x = uint32_t(p % test.width);
      measure.max_y = uint32_t(p / test.width);
    }
    if (difference > per_pixel_threshold) {
      excess += difference - per_pixel_threshold;
      ++measure.incorrect_pixels;
    }
  }
  if (pixels) {
    measure.mean = sum / double(pixels);
    measure.average_excess = excess / double(pixels);
    measure.incorrect_fraction = double(measure.incorrect_pixels) / double(pixels);
  }
  return measure;
}

}  // namespace xshade::harness
