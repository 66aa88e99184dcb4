// Indirect light from the scene's environment, computed on the CPU by the harness
// (harness/environment.h): 9 spherical-harmonic coefficients for irradiance, and an
// equirectangular image whose mip levels are prefiltered for rising roughness.
#ifndef XSHADE_ENVIRONMENT_HLSL
#define XSHADE_ENVIRONMENT_HLSL

#include "common.hlsl"
#include "scene_inputs.hlsl"

Texture2D _EnvironmentSpecular;
SamplerState sampler_EnvironmentSpecular;

// Unity's mip count for reflection probes: roughness 1 reads level 6.
static const float kEnvironmentMipSteps = 6.0;

// irradiance(n) / pi from the coefficients (the real SH basis of degree 2, constants folded
// with the cosine lobe on the CPU), so that a constant environment of radiance L gives L.
float3 sh_irradiance(float3 n) {
  float3 result = _EnvironmentSH[0].rgb * 0.282095;
  result += _EnvironmentSH[1].rgb * (0.488603 * n.y);
  result += _EnvironmentSH[2].rgb * (0.488603 * n.z);
  result += _EnvironmentSH[3].rgb * (0.488603 * n.x);
  result += _EnvironmentSH[4].rgb * (1.092548 * n.x * n.y);
  result += _EnvironmentSH[5].rgb * (1.092548 * n.y * n.z);
  result += _EnvironmentSH[6].rgb * (0.315392 * (3.0 * n.z * n.z - 1.0));
  result += _EnvironmentSH[7].rgb * (1.092548 * n.x * n.z);
  result += _EnvironmentSH[8].rgb * (0.546274 * (n.x * n.x - n.y * n.y));
  // Degree-2 SH rings below zero opposite a bright sky; negative light is not light.
  return max(result, 0.0);
}

// Direction to equirectangular uv: v = 0 (the image's top row) is straight up, the u seam is
// at -z, behind the objects as the default camera sees them.
float2 equirect_uv(float3 direction) {
  float u = 0.5 + atan2(direction.x, direction.z) * (0.5 / kPi);
  float v = acos(clamp(direction.y, -1.0, 1.0)) / kPi;
  return float2(u, v);
}

// The environment seen along `direction`, blurred for perceptual roughness r, read from the
// level Unity's standard shader would pick (perceptualRoughnessToMipmapLevel).
float3 prefiltered_environment(float3 direction, float r) {
  float mip = r * (1.7 - 0.7 * r) * kEnvironmentMipSteps;
  return _EnvironmentSpecular.SampleLevel(sampler_EnvironmentSpecular, equirect_uv(direction), mip).rgb;
}

#endif
