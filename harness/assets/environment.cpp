#include "harness/assets/environment.h"

#include <algorithm>
#include <cmath>

#include "harness/assets/equirect.h"
#include "harness/assets/specular_prefilter.h"
#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

FloatImage radiance_image(const EnvironmentSpec& desc) {
  FloatImage image(kPrefilteredWidth, kPrefilteredHeight);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x) {
      glm::vec3 value = desc.kind == EnvironmentKind::Gradient
                            ? gradient_radiance(desc, equirect_texel_direction(x, y, image.width, image.height))
                            : desc.color;
      image.set(x, y, glm::vec4(value, 1.0f));
    }
  return image;
}

}  // namespace

glm::vec3 gradient_radiance(const EnvironmentSpec& desc, glm::vec3 direction) {
  const float y = std::clamp(direction.y, -1.0f, 1.0f);
  if (y >= 0.0f) {
    float t = 1.0f - std::pow(1.0f - y, 3.0f);
    return glm::mix(desc.horizon, desc.sky, t);
  }
  float s = std::clamp(-y / 0.15f, 0.0f, 1.0f);
  return glm::mix(desc.horizon, desc.ground, s * s * (3.0f - 2.0f * s));
}

Result<Environment> build_environment(const EnvironmentSpec& desc) {
  Environment environment;
  if (desc.kind == EnvironmentKind::Equirect) {
    Result<FloatImage> file = read_image(desc.file);
    if (!file) return fail(file.error().kind, "environment " + desc.file.string() + ": " + file.error().message);
    environment.radiance = file->width == kPrefilteredWidth && file->height == kPrefilteredHeight
                               ? std::move(*file)
                               : resample_equirect(*file, kPrefilteredWidth, kPrefilteredHeight);
  } else {
    environment.radiance = radiance_image(desc);
  }
  for (size_t i = 0; i < environment.radiance.rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) environment.radiance.rgba[i + c] *= desc.intensity;
    environment.radiance.rgba[i + 3] = 1.0f;
  }
  environment.sh = irradiance_sh(environment.radiance);
  environment.prefiltered = prefilter_specular(environment.radiance);
  return environment;
}

}  // namespace xshade::harness
