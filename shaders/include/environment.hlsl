// Indirect light from the scene's environment, computed on the CPU by the harness
// (harness/environment.h): 9 spherical-harmonic coefficients for irradiance, and an
// equirectangular image whose mip levels are prefiltered for rising roughness.
#ifndef XSHADE_ENVIRONMENT_HLSL
#define XSHADE_ENVIRONMENT_HLSL

#include "brdf.hlsl"
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

// The specular light from the environment as the integral of L(l) f(v, l) (n.l) over the
// hemisphere, estimated with `count` half vectors from GGX's own distribution (Hammersley points,
// importance sampling): the reference the prefiltered lookup is judged against (SHADERS.md
// section 6). f is the variant's V and F; D cancels against the sampling density, so the estimate
// is L (V F (n.l) 4 (v.h) / (n.h)) averaged. Level 0 is the environment itself.
float3 sampled_environment_specular(float3 n, float3 v, float a, float3 spec_color, int count) {
  // An orthonormal frame around n (Duff et al. 2017).
  float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
  float p = -1.0 / (sign_z + n.z);
  float q = n.x * n.y * p;
  float3 t = float3(1.0 + sign_z * n.x * n.x * p, sign_z * q, -sign_z * n.x);
  float3 b = float3(q, sign_z + n.y * n.y * p, -n.y);
  float a2 = a * a;
  float3 sum = float3(0.0, 0.0, 0.0);
  for (int i = 0; i < count; i++) {
    float u = (float(i) + 0.5) / float(count);
    float phi = 2.0 * kPi * float(reversebits(uint(i))) * 2.3283064365386963e-10;
    // The inverse of GGX's cumulative distribution of cos^2(theta_h), for pdf(h) = D(h) (n.h).
    float cos_theta = sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
    float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    float3 h = t * (sin_theta * cos(phi)) + b * (sin_theta * sin(phi)) + n * cos_theta;
    float VoH = dot(v, h);
    float3 l = 2.0 * VoH * h - v;
    float NoL = dot(n, l);
    if (NoL <= 0.0 || VoH <= 0.0) continue;
    BrdfInputs s = brdf_inputs(n, v, l, a);
    float3 radiance = _EnvironmentSpecular.SampleLevel(sampler_EnvironmentSpecular, equirect_uv(l), 0.0).rgb;
    sum += radiance * fresnel(spec_color, s.LoH) * (visibility(s) * NoL * 4.0 * VoH / cos_theta);
  }
  return sum / float(count);
}

#endif
