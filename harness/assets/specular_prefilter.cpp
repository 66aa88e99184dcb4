#include "harness/assets/specular_prefilter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "harness/assets/equirect.h"

namespace xshade::harness {
namespace {

// GGX samples per output texel. With filtered importance sampling each sample already averages
// the source over its share of the lobe, so a few hundred leave no visible noise or banding.
constexpr uint32_t kSamples = 256;
// Colbert and Krivanek read one level coarser than the sample's footprint, which hides the
// pattern of a fixed sample set.
constexpr double kLodBias = 1.0;

// The source at successively halved resolution. Each texel averages the 2 x 2 texels under it
// weighted by their solid angles, so that every level keeps the mean over the sphere.
std::vector<FloatImage> solid_angle_mip_chain(const FloatImage& base) {
  std::vector<FloatImage> chain{base};
  while (chain.back().height > 1) {
    const FloatImage& fine = chain.back();
    FloatImage coarse(fine.width / 2, fine.height / 2);
    for (uint32_t y = 0; y < coarse.height; ++y) {
      auto top = float(equirect_texel_solid_angle(2 * y, fine.width, fine.height));
      auto bottom = float(equirect_texel_solid_angle(2 * y + 1, fine.width, fine.height));
      for (uint32_t x = 0; x < coarse.width; ++x) {
        glm::vec4 sum = top * (fine.at(2 * x, 2 * y) + fine.at(2 * x + 1, 2 * y)) +
                        bottom * (fine.at(2 * x, 2 * y + 1) + fine.at(2 * x + 1, 2 * y + 1));
        coarse.set(x, y, sum / (2.0f * (top + bottom)));
      }
    }
    chain.push_back(std::move(coarse));
  }
  return chain;
}

// Bilinear filtering of one level at uv with u >= 0, wrapping in u and clamping in v: the
// inner loop of the prefilter, so it avoids the general sample_equirect's care for any uv.
glm::vec3 bilinear(const FloatImage& image, float u, float v) {
  const float x = u * float(image.width) - 0.5f + float(image.width);  // >= 0 for u >= 0
  const float y = std::clamp(v * float(image.height) - 0.5f, 0.0f, float(image.height - 1));
  const auto x0 = uint32_t(x), y0 = uint32_t(y);
  const float fx = x - float(x0), fy = y - float(y0);
  const uint32_t left = x0 % image.width, right = (x0 + 1) % image.width;
  const uint32_t top = y0, bottom = std::min(y0 + 1, image.height - 1);
  auto texel = [&image](uint32_t tx, uint32_t ty) {
    const float* p = &image.rgba[(size_t(ty) * image.width + tx) * 4];
    return glm::vec3(p[0], p[1], p[2]);
  };
  return (texel(left, top) * (1.0f - fx) + texel(right, top) * fx) * (1.0f - fy) +
         (texel(left, bottom) * (1.0f - fx) + texel(right, bottom) * fx) * fy;
}

// The i-th point of the n-point Hammersley set in [0, 1)^2.
glm::dvec2 hammersley(uint32_t i, uint32_t n) {
  uint32_t bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {double(i) / n, double(bits) * 2.3283064365386963e-10};
}

// A light direction in the frame where n = v = +z, with its weight n.l and the source level to
// read it from. The set is the same for every texel of a level; only the frame turns.
struct LobeSample {
  glm::vec3 direction;
  float weight;
  uint32_t level;  // the finer of the two source levels read, blended by `blend`
  float blend;
};

std::vector<LobeSample> lobe_samples(double alpha, double source_texel_solid_angle, size_t source_levels) {
  const double a2 = alpha * alpha;
  std::vector<LobeSample> samples;
  samples.reserve(kSamples);
  for (uint32_t i = 0; i < kSamples; ++i) {
    glm::dvec2 xi = hammersley(i, kSamples);
    // Half vectors distributed as D(n.h) (n.h) (Walter et al. 2007).
    double cos_h = std::sqrt((1.0 - xi.x) / (1.0 + (a2 - 1.0) * xi.x));
    double sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
    double phi = 2.0 * std::numbers::pi * xi.y;
    glm::dvec3 h{sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h};
    glm::dvec3 l = 2.0 * cos_h * h - glm::dvec3(0.0, 0.0, 1.0);
    if (l.z <= 0.0) continue;
    // With v = n, the density of l per solid angle is D(n.h) (n.h) / (4 v.h) = D(n.h) / 4.
    double d = a2 / (std::numbers::pi * std::pow(cos_h * cos_h * (a2 - 1.0) + 1.0, 2.0));
    double sample_solid_angle = 1.0 / (kSamples * d / 4.0);
    double lod = 0.5 * std::log2(sample_solid_angle / source_texel_solid_angle) + kLodBias;
    lod = std::clamp(lod, 0.0, double(source_levels - 1));
    auto level = std::min(uint32_t(lod), uint32_t(source_levels - 2));
    samples.push_back({glm::vec3(glm::normalize(l)), float(l.z), level, float(lod - level)});
  }
  return samples;
}

FloatImage prefilter_level(const std::vector<FloatImage>& chain, uint32_t width, uint32_t height, double alpha) {
  // Texel footprints are judged by their extent in theta, pi / height, the larger side of an
  // equirect texel everywhere (the phi side shrinks toward the poles).
  const double texel_extent = std::numbers::pi / chain.front().height;
  const std::vector<LobeSample> samples = lobe_samples(alpha, texel_extent * texel_extent, chain.size());
  FloatImage level(width, height);
  std::vector<glm::vec2> sample_uv(samples.size());
  for (uint32_t y = 0; y < height; ++y) {
    // The texels of a row differ only by a turn about y, which moves every sample's u by the
    // same amount and leaves its v: the samples' uv are found once per row, for its first texel.
    const glm::vec3 n = equirect_texel_direction(0, y, width, height);
    const glm::vec3 up = std::abs(n.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 tangent = glm::normalize(glm::cross(up, n));
    const glm::vec3 bitangent = glm::cross(n, tangent);
    for (size_t k = 0; k < samples.size(); ++k) {
      const glm::vec3& d = samples[k].direction;
      sample_uv[k] = equirect_uv(tangent * d.x + bitangent * d.y + n * d.z);
    }
    for (uint32_t x = 0; x < width; ++x) {
      const float turn = float(x) / float(width);
      glm::vec3 sum(0.0f);
      float weight = 0.0f;
      for (size_t k = 0; k < samples.size(); ++k) {
        const LobeSample& sample = samples[k];
        const float u = sample_uv[k].x + turn, v = sample_uv[k].y;
        glm::vec3 value = bilinear(chain[sample.level], u, v);
        if (sample.blend > 0.0f) value += sample.blend * (bilinear(chain[sample.level + 1], u, v) - value);
        sum += sample.weight * value;
        weight += sample.weight;
      }
      level.set(x, y, glm::vec4(sum / weight, 1.0f));
    }
  }
  return level;
}

std::vector<std::byte> level_bytes(const FloatImage& image) {
  std::vector<std::byte> bytes(image.rgba.size() * sizeof(float));
  std::memcpy(bytes.data(), image.rgba.data(), bytes.size());
  return bytes;
}

}  // namespace

float prefiltered_mip_for_roughness(float roughness) { return roughness * (1.7f - 0.7f * roughness) * 6.0f; }

float prefiltered_roughness_for_mip(float level) {
  // The root in [0, 1] of 0.7 r^2 - 1.7 r + level / 6 = 0.
  double discriminant = std::max(0.0, 2.89 - 2.8 * double(level) / 6.0);
  return float((1.7 - std::sqrt(discriminant)) / 1.4);
}

TextureData prefilter_specular(const FloatImage& equirect_radiance) {
  FloatImage base = equirect_radiance.width == kPrefilteredWidth && equirect_radiance.height == kPrefilteredHeight
                        ? equirect_radiance
                        : resample_equirect(equirect_radiance, kPrefilteredWidth, kPrefilteredHeight);
  for (size_t i = 3; i < base.rgba.size(); i += 4) base.rgba[i] = 1.0f;
  const std::vector<FloatImage> chain = solid_angle_mip_chain(base);

  TextureData texture;
  texture.format = TextureFormat::Rgba32Float;
  texture.width = kPrefilteredWidth;
  texture.height = kPrefilteredHeight;
  texture.levels.push_back(level_bytes(base));
  for (uint32_t level = 1; level < kPrefilteredLevels; ++level) {
    double alpha = prefiltered_roughness_for_mip(float(level));
    texture.levels.push_back(
        level_bytes(prefilter_level(chain, kPrefilteredWidth >> level, kPrefilteredHeight >> level, alpha)));
  }
  return texture;
}

FloatImage prefiltered_level(const TextureData& texture, uint32_t level) {
  FloatImage image(std::max(1u, texture.width >> level), std::max(1u, texture.height >> level));
  std::memcpy(image.rgba.data(), texture.levels.at(level).data(),
              std::min(texture.levels.at(level).size(), image.rgba.size() * sizeof(float)));
  return image;
}

}  // namespace xshade::harness
