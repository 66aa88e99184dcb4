// Stability probe: integrals of the library's BRDF terms over the hemisphere, one per pixel
// column, by a midpoint rule over M x M points of a warped square.
//   mode 0: the directional albedo E(v) = integral of D V 4 (n.l) ... with F = 1, i.e. the
//           integral of f cos over the hemisphere without the seed's extra pi. The points are
//           the GGX distribution's own (importance sampling with stratified points), so the
//           rule converges quickly however sharp the lobe.
//   mode 1: the GGX normalisation, integral of D(m) (n.m) over the hemisphere (it must be 1),
//           with theta = atan(alpha tan psi) over psi in [0, pi/2) so that the points crowd
//           into the peak at small alpha.
#pragma fragment frag
#pragma multi_compile _D_GGX_SEED _D_GGX_LAGRANGE
#pragma multi_compile _G_COOK_TORRANCE _G_SMITH_CORRELATED _G_SMITH_FAST
#pragma multi_compile _F_SCHLICK _F_SPHERICAL_GAUSSIAN _F_EXACT
#pragma multi_compile _ _GUARDED

#include "include/brdf.hlsl"

static const int kMaxInputs = 64;

cbuffer ProbeInputs {
  float4 _Inputs[kMaxInputs];  // per input: (NoV, alpha, M, mode)
};

float directional_albedo(float NoV, float a, int m_count) {
  float3 n = float3(0.0, 0.0, 1.0);
  float3 v = float3(sqrt(1.0 - NoV * NoV), 0.0, NoV);
  float sum = 0.0;
  for (int j = 0; j < m_count; j++) {
    // u = 1 - (1 - t)^2 crowds the points toward u = 1, the lobe's grazing tail, where G falls
    // below 1 at small alpha; du/dt = 2 (1 - t) weighs them back.
    float t = (float(j) + 0.5) / float(m_count);
    float u = 1.0 - (1.0 - t) * (1.0 - t);
    float weight = 2.0 * (1.0 - t);
    // The inverse of GGX's cumulative distribution of cos^2(theta_m), for pdf(m) = D(m) (n.m).
    float cos_theta = sqrt((1.0 - u) / (1.0 + (a * a - 1.0) * u));
    float sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    for (int k = 0; k < m_count; k++) {
      float phi = 2.0 * kPi * (float(k) + 0.5) / float(m_count);
      float3 m = float3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
      float VoM = dot(v, m);
      float3 l = 2.0 * VoM * m - v;
      float NoL = dot(n, l);
      if (NoL <= 0.0 || VoM <= 0.0) continue;
      BrdfInputs s = brdf_inputs(n, v, l, a);
      // f cos / pdf(l), where pdf(l) = D(m) (n.m) / (4 v.m) and the sampled D is GGX's.
      float pdf_d = D_GGX_lagrange(n, m, cos_theta, a);
      sum += weight * distribution(s) * visibility(s) * NoL * 4.0 * VoM / (pdf_d * cos_theta);
    }
  }
  return sum / float(m_count * m_count);
}

float ggx_normalisation(float a, int m_count) {
  float3 n = float3(0.0, 0.0, 1.0);
  float sum = 0.0;
  for (int j = 0; j < m_count; j++) {
    float psi = 0.5 * kPi * (float(j) + 0.5) / float(m_count);
    float t = tan(psi);
    float theta = atan(a * t);
    float dtheta_dpsi = a * (1.0 + t * t) / (1.0 + a * a * t * t);
    float3 m = float3(sin(theta), 0.0, cos(theta));
    // v = l = m: the half vector is m itself.
    BrdfInputs s = brdf_inputs(n, m, m, a);
    sum += 2.0 * kPi * distribution(s) * cos(theta) * sin(theta) * dtheta_dpsi;
  }
  return sum * 0.5 * kPi / float(m_count);
}

float4 frag(float4 position : SV_Position) : SV_Target {
  float4 input = _Inputs[int(position.x)];
  int m_count = int(input.z);
  // if, not ?:, which in HLSL evaluates both operands (and each is a long loop).
  if (input.w == 0.0) return float4(directional_albedo(input.x, input.y, m_count), 0.0, 0.0, 0.0);
  return float4(ggx_normalisation(input.y, m_count), 0.0, 0.0, 0.0);
}
