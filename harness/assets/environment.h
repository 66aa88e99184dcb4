// The light a scene's surroundings give: an environment's radiance, its diffuse irradiance as
// spherical harmonics and its GGX-prefiltered specular texture.
//
// Directions follow equirect.h (right-handed world, +y up, seam at -z); the SH convention is in
// spherical_harmonics.h and the prefiltered texture's in specular_prefilter.h.
#pragma once

#include <filesystem>

#include <glm/vec3.hpp>

#include "base/result.h"
#include "harness/assets/spherical_harmonics.h"
#include "harness/backend/backend.h"
#include "harness/image/image.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

struct Environment {
  FloatImage radiance;      // equirect, kPrefilteredWidth x kPrefilteredHeight, alpha 1
  ShCoefficients sh{};      // irradiance / pi, from `radiance`
  TextureData prefiltered;  // RGBA32F, level 0 = `radiance`
};

// The gradient sky's radiance in direction d (before `intensity`), a function of d.y alone:
//   above the horizon  mix(horizon, sky, 1 - (1 - y)^3)        (steep at the horizon, flat at the zenith)
//   below the horizon  mix(horizon, ground, smoothstep(0, 0.15, -y))  (ground from about 8.6 degrees down)
// Continuous everywhere, equal to `horizon` at y = 0, `sky` straight up, `ground` below.
glm::vec3 gradient_radiance(const EnvironmentSpec& desc, glm::vec3 direction);

// Builds everything a scene's [environment] (scene.h) needs. Fails, naming the file, when an Equirect image cannot be
// read. An equirect image of another size is resampled (see resample_equirect); its alpha is ignored.
Result<Environment> build_environment(const EnvironmentSpec& desc);

}  // namespace xshade::harness
