#include "harness/image/flip.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace xshade::harness {

namespace {

// FLIP.h's constants: the colour and feature exponents qc and qf, the error redistribution's pc
// and pt, the feature filters' width w (in degrees), and the contrast sensitivity functions'
// Gaussians (a1, b1, a2, b2) for the achromatic, red-green and blue-yellow channels.
constexpr float kQc = 0.7f;
constexpr float kQf = 0.5f;
constexpr float kPc = 0.4f;
constexpr float kPt = 0.95f;
constexpr float kW = 0.082f;
constexpr glm::vec3 kA1{1.0f, 1.0f, 34.1f};
constexpr glm::vec3 kB1{0.0047f, 0.0053f, 0.04f};
constexpr glm::vec3 kA2{0.0f, 0.0f, 13.5f};
constexpr glm::vec3 kB2{1.0e-5f, 1.0e-5f, 0.025f};
constexpr glm::vec3 kIlluminant{0.950428545f, 1.000000000f, 1.088900371f};  // D65 white, XYZ
constexpr glm::vec3 kInverseIlluminant{1.052156925f, 1.000000000f, 0.918357670f};
constexpr float kPi = 3.14159265358979f;

glm::vec3 xyz_from_linear(glm::vec3 c) {
  return {(10135552.0f / 24577794.0f) * c.r + (8788810.0f / 24577794.0f) * c.g + (4435075.0f / 24577794.0f) * c.b,
          (2613072.0f / 12288897.0f) * c.r + (8788810.0f / 12288897.0f) * c.g + (887015.0f / 12288897.0f) * c.b,
          (1425312.0f / 73733382.0f) * c.r + (8788810.0f / 73733382.0f) * c.g + (70074185.0f / 73733382.0f) * c.b};
}

glm::vec3 linear_from_xyz(glm::vec3 c) {
  return {3.241003275f * c.x - 1.537398934f * c.y - 0.498615861f * c.z,
          -0.969224334f * c.x + 1.875930071f * c.y + 0.041554224f * c.z,
          0.055639423f * c.x - 0.204011202f * c.y + 1.057148933f * c.z};
}

// YCxCz: CIELAB without its cube root, the opponent space the filters run in.
glm::vec3 ycxcz_from_xyz(glm::vec3 xyz) {
  const glm::vec3 n = xyz * kInverseIlluminant;
  return {116.0f * n.y - 16.0f, 500.0f * (n.x - n.y), 200.0f * (n.y - n.z)};
}

glm::vec3 xyz_from_ycxcz(glm::vec3 c) {
  const float y = (c.x + 16.0f) / 116.0f;
  return glm::vec3(c.y / 500.0f + y, y, y - c.z / 200.0f) * kIlluminant;
}

// CIELAB with the Hunt effect (chroma shrinks as lightness falls): a' = L a / 100, b' = L b / 100.
glm::vec3 hunt_lab_from_linear(glm::vec3 linear) {
  const glm::vec3 n = xyz_from_linear(linear) * kInverseIlluminant;
  constexpr float delta = 6.0f / 29.0f;
  const auto f = [](float t) {
    return t > delta * delta * delta ? std::cbrt(t) : t / (3.0f * delta * delta) + 4.0f / 29.0f;
  };
  const float l = 116.0f * f(n.y) - 16.0f;
  const float a = 500.0f * (f(n.x) - f(n.y));
  const float b = 200.0f * (f(n.y) - f(n.z));
  return {l, 0.01f * l * a, 0.01f * l * b};
}

// HyAB: the lightness difference's magnitude plus the chroma plane's Euclidean distance.
float hyab(glm::vec3 p, glm::vec3 q) { return std::fabs(p.x - q.x) + std::hypot(p.y - q.y, p.z - q.z); }

// The largest colour difference, green against blue, raised to qc.
float max_colour_difference() {
  static const float largest =
      std::pow(hyab(hunt_lab_from_linear({0.0f, 1.0f, 0.0f}), hunt_lab_from_linear({0.0f, 0.0f, 1.0f})), kQc);
  return largest;
}

// A plane of values, row-major.
template <class T>
struct Plane {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<T> values;
};

// One pass of a separable filter along x (`along_x`) or y, clamped at the edges, each output the
// taps' sum in tap order. Along y whole rows are weighed and added, which reads memory in order.
template <class T, class Weight>
Plane<T> convolve(const Plane<T>& in, const std::vector<Weight>& kernel, bool along_x) {
  Plane<T> out{in.width, in.height, std::vector<T>(in.values.size())};
  const int64_t radius = int64_t(kernel.size() / 2);
  const int64_t width = in.width, height = in.height;
  if (along_x) {
    for (int64_t y = 0; y < height; ++y) {
      const T* row = &in.values[size_t(y * width)];
      T* to = &out.values[size_t(y * width)];
      for (int64_t x = 0; x < width; ++x) {
        T sum{};
        if (x >= radius && x + radius < width) {
          const T* first = row + (x - radius);
          for (size_t k = 0; k < kernel.size(); ++k) sum += kernel[k] * first[k];
        } else {
          for (int64_t k = -radius; k <= radius; ++k)
            sum += kernel[size_t(k + radius)] * row[std::clamp<int64_t>(x + k, 0, width - 1)];
        }
        to[x] = sum;
      }
    }
    return out;
  }
  for (int64_t y = 0; y < height; ++y) {
    T* to = &out.values[size_t(y * width)];
    for (int64_t k = -radius; k <= radius; ++k) {
      const T* row = &in.values[size_t(std::clamp<int64_t>(y + k, 0, height - 1) * width)];
      const Weight weight = kernel[size_t(k + radius)];
      for (int64_t x = 0; x < width; ++x) to[x] += weight * row[x];
    }
  }
  return out;
}

// The contrast sensitivity filters at `ppd`, one 1D kernel per channel and a second for
// blue-yellow, whose filter is the sum of two Gaussians: each 2D filter is the outer product of
// its 1D kernel with itself, with a gain of 1 for a constant image.
struct SpatialKernels {
  std::vector<glm::vec3> first;  // achromatic, red-green, blue-yellow's first Gaussian
  std::vector<float> second;     // blue-yellow's second Gaussian
};

SpatialKernels spatial_kernels(double ppd) {
  const float widest = std::max({kB1.x, kB1.y, kB1.z, kB2.x, kB2.y, kB2.z});
  const int radius = int(std::ceil(3.0f * std::sqrt(widest / (2.0f * kPi * kPi)) * float(ppd)));
  const auto gaussian = [](float x2, float a, float b) {
    return a * std::sqrt(kPi / b) * std::exp(-kPi * kPi * x2 / b);
  };
  const auto gaussian_root = [](float x2, float a, float b) {
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-kPi * kPi * x2 / b);
  };
  SpatialKernels kernels;
  glm::vec3 sum(0.0f);
  float second_sum = 0.0f;
  for (int i = -radius; i <= radius; ++i) {
    const float x = float(i) / float(ppd);
    const float x2 = x * x;
    const glm::vec3 tap{gaussian(x2, kA1.x, kB1.x), gaussian(x2, kA1.y, kB1.y), gaussian_root(x2, kA1.z, kB1.z)};
    const float second = gaussian_root(x2, kA2.z, kB2.z);
    kernels.first.push_back(tap);
    kernels.second.push_back(second);
    sum += tap;
    second_sum += second;
  }
  const float blue_yellow = std::sqrt(sum.z * sum.z + second_sum * second_sum);
  for (glm::vec3& tap : kernels.first) tap /= glm::vec3(sum.x, sum.y, blue_yellow);
  for (float& tap : kernels.second) tap /= blue_yellow;
  return kernels;
}

// The feature filters at `ppd`: a Gaussian and its first and second derivatives, each
// derivative's positive and negative taps scaled to sum to 1 and -1.
struct FeatureKernels {
  std::vector<float> gaussian, first, second;
};

FeatureKernels feature_kernels(double ppd) {
  const float sigma = 0.5f * kW * float(ppd);
  const int radius = int(std::ceil(3.0f * sigma));
  FeatureKernels kernels;
  for (int i = -radius; i <= radius; ++i) {
    const float x = float(i);
    const float g = std::exp(-x * x / (2.0f * sigma * sigma));
    kernels.gaussian.push_back(g);
    kernels.first.push_back(-x * g);
    kernels.second.push_back((x * x / (sigma * sigma) - 1.0f) * g);
  }
  const auto normalize_signs = [](std::vector<float>& taps) {
    float positive = 0.0f, negative = 0.0f;
    for (float tap : taps) (tap > 0.0f ? positive : negative) += std::fabs(tap);
    for (float& tap : taps) tap /= tap > 0.0f ? positive : negative;
  };
  float sum = 0.0f;
  for (float tap : kernels.gaussian) sum += tap;
  for (float& tap : kernels.gaussian) tap /= sum;
  normalize_signs(kernels.first);
  normalize_signs(kernels.second);
  return kernels;
}

// An image's YCxCz, its linear colours clamped to [0, 1].
Plane<glm::vec3> ycxcz_plane(const FloatImage& image) {
  Plane<glm::vec3> plane{image.width, image.height, {}};
  plane.values.resize(size_t(image.width) * image.height);
  for (size_t p = 0; p < plane.values.size(); ++p) {
    const float* c = &image.rgba[p * 4];
    const auto clamped = [](float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : (v > 0 ? 1.0f : 0.0f); };
    plane.values[p] = ycxcz_from_xyz(xyz_from_linear({clamped(c[0]), clamped(c[1]), clamped(c[2])}));
  }
  return plane;
}

// The image as the eye sees it at `ppd`, in Hunt-adjusted CIELAB.
std::vector<glm::vec3> filtered_hunt_lab(const Plane<glm::vec3>& ycxcz, const SpatialKernels& kernels) {
  const Plane<glm::vec3> first = convolve(convolve(ycxcz, kernels.first, true), kernels.first, false);
  Plane<float> blue_yellow{ycxcz.width, ycxcz.height, std::vector<float>(ycxcz.values.size())};
  for (size_t p = 0; p < ycxcz.values.size(); ++p) blue_yellow.values[p] = ycxcz.values[p].z;
  const Plane<float> second = convolve(convolve(blue_yellow, kernels.second, true), kernels.second, false);
  std::vector<glm::vec3> lab(ycxcz.values.size());
  for (size_t p = 0; p < lab.size(); ++p) {
    const glm::vec3 filtered{first.values[p].x, first.values[p].y, first.values[p].z + second.values[p]};
    lab[p] = hunt_lab_from_linear(glm::clamp(linear_from_xyz(xyz_from_ycxcz(filtered)), 0.0f, 1.0f));
  }
  return lab;
}

// Edges (first derivatives) and points (second) of the achromatic channel, scaled to [0, 1].
struct Features {
  std::vector<float> edge, point;
};

Features features(const Plane<glm::vec3>& ycxcz, const FeatureKernels& kernels) {
  Plane<float> y{ycxcz.width, ycxcz.height, std::vector<float>(ycxcz.values.size())};
  for (size_t p = 0; p < y.values.size(); ++p) y.values[p] = (ycxcz.values[p].x + 16.0f) / 116.0f;
  const Plane<float> smooth_x = convolve(y, kernels.gaussian, true);
  const Plane<float> dx = convolve(convolve(y, kernels.first, true), kernels.gaussian, false);
  const Plane<float> ddx = convolve(convolve(y, kernels.second, true), kernels.gaussian, false);
  const Plane<float> dy = convolve(smooth_x, kernels.first, false);
  const Plane<float> ddy = convolve(smooth_x, kernels.second, false);
  Features out{std::vector<float>(y.values.size()), std::vector<float>(y.values.size())};
  for (size_t p = 0; p < y.values.size(); ++p) {
    out.edge[p] = std::hypot(dx.values[p], dy.values[p]);
    out.point[p] = std::hypot(ddx.values[p], ddy.values[p]);
  }
  return out;
}

// LDR-FLIP's values, per pixel.
std::vector<float> ldr_flip(const FloatImage& test, const FloatImage& reference, double ppd) {
  const SpatialKernels spatial = spatial_kernels(ppd);
  const FeatureKernels feature = feature_kernels(ppd);
  const Plane<glm::vec3> test_ycxcz = ycxcz_plane(test);
  const Plane<glm::vec3> reference_ycxcz = ycxcz_plane(reference);
  const std::vector<glm::vec3> test_lab = filtered_hunt_lab(test_ycxcz, spatial);
  const std::vector<glm::vec3> reference_lab = filtered_hunt_lab(reference_ycxcz, spatial);
  const Features test_features = features(test_ycxcz, feature);
  const Features reference_features = features(reference_ycxcz, feature);

  const float cmax = max_colour_difference();
  const float pccmax = kPc * cmax;
  std::vector<float> values(test_lab.size());
  for (size_t p = 0; p < values.size(); ++p) {
    // The colour difference, redistributed: the lower pc of its range onto [0, pt], the rest above.
    float colour = std::pow(hyab(reference_lab[p], test_lab[p]), kQc);
    colour = colour < pccmax ? colour * (kPt / pccmax) : kPt + (colour - pccmax) / (cmax - pccmax) * (1.0f - kPt);
    const float feature_difference = std::pow(
        float(1.0 / std::sqrt(2.0)) * std::max(std::fabs(reference_features.edge[p] - test_features.edge[p]),
                                               std::fabs(reference_features.point[p] - test_features.point[p])),
        kQf);
    values[p] = std::pow(colour, 1.0f - feature_difference);
  }
  return values;
}

// The reference tool's pooling: mean, weighted percentiles, min and max.
FlipMeasure pooled(std::vector<float> values, uint32_t width) {
  FlipMeasure measure;
  measure.per_pixel = values;
  if (values.empty()) return measure;
  double sum = 0.0;
  measure.min = values[0];
  for (size_t p = 0; p < values.size(); ++p) {
    sum += values[p];
    measure.min = std::min(measure.min, double(values[p]));
    if (values[p] > measure.max || p == 0) {
      measure.max = values[p];
      measure.max_x = uint32_t(p % width);
      measure.max_y = uint32_t(p / width);
    }
  }
  measure.mean = sum / double(values.size());
  std::sort(values.begin(), values.end());
  const auto weighted_percentile = [&](double fraction) {
    double running = 0.0;
    for (float value : values) {
      running += value;
      if (running > fraction * sum) return double(value);
    }
    return double(values.back());
  };
  measure.weighted_first_quartile = weighted_percentile(0.25);
  measure.weighted_median = weighted_percentile(0.5);
  measure.weighted_third_quartile = weighted_percentile(0.75);
  return measure;
}

}  // namespace

double flip_default_pixels_per_degree() { return 0.7 * (3840.0 / 0.7) * (3.14159265358979 / 180.0); }

FlipMeasure measure_flip(const FloatImage& test, const FloatImage& reference, double pixels_per_degree) {
  return pooled(ldr_flip(test, reference, pixels_per_degree), test.width);
}

FlipMeasure measure_hdr_flip(const FloatImage& test, const FloatImage& reference, double pixels_per_degree) {
  // ACES, the reference tool's default tone mapper: y = (c0 x^2 + c1 x + c2) / (c3 x^2 + c4 x + c5).
  constexpr double c[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
  // The input the tone mapper maps to 0.85: the larger root of (c0 - t c3) x^2 + (c1 - t c4) x + (c2 - t c5).
  constexpr double t = 0.85;
  const double qa = c[0] - t * c[3], qb = c[1] - t * c[4], qc = c[2] - t * c[5];
  const double x_max = (-qb + std::sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa);

  std::vector<double> luminance;
  luminance.reserve(size_t(reference.width) * reference.height);
  for (size_t p = 0; p < size_t(reference.width) * reference.height; ++p) {
    const float* rgb = &reference.rgba[p * 4];
    const double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    if (std::isfinite(y) && y > 0.0) luminance.push_back(y);  // black has no exposure of its own
  }
  double start = 0.0, stop = 0.0;
  if (!luminance.empty()) {
    const double brightest = *std::max_element(luminance.begin(), luminance.end());
    std::nth_element(luminance.begin(), luminance.begin() + std::ptrdiff_t(luminance.size() / 2), luminance.end());
    start = std::log2(x_max / brightest);
    stop = std::log2(x_max / luminance[luminance.size() / 2]);
  }
  const uint32_t exposures = std::max(2u, uint32_t(std::ceil(stop - start)));
  const double step = (stop - start) / double(exposures - 1);

  std::vector<float> worst(size_t(test.width) * test.height, 0.0f);
  for (uint32_t i = 0; i < exposures; ++i) {
    const float scale = float(std::exp2(start + step * double(i)));
    const auto tone_mapped = [&](const FloatImage& image) {
      FloatImage out = image;
      for (size_t v = 0; v < out.rgba.size(); ++v) {
        if (v % 4 == 3) continue;
        const double x = double(out.rgba[v]) * scale;
        out.rgba[v] = float((c[0] * x * x + c[1] * x + c[2]) / (c[3] * x * x + c[4] * x + c[5]));
      }
      return out;
    };
    const std::vector<float> values = ldr_flip(tone_mapped(test), tone_mapped(reference), pixels_per_degree);
    for (size_t p = 0; p < worst.size(); ++p) worst[p] = std::max(worst[p], values[p]);
  }
  FlipMeasure measure = pooled(std::move(worst), test.width);
  measure.hdr = true;
  measure.start_exposure = start;
  measure.stop_exposure = stop;
  measure.exposures = exposures;
  return measure;
}

}  // namespace xshade::harness
