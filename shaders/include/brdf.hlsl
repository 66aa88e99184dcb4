// The terms of the Cook-Torrance BRDF, each form written once (SHADERS.md sections 1, 4 and 6).
// The seed's forms are kept exactly as the seed writes them, hazards included: they are a test
// subject. Every form is an ordinary function, so that the stability suite can call each one
// whatever keywords a material was compiled with; distribution(), visibility() and fresnel()
// pick the forms the variant's keywords name. The terms compute in `real` (common.hlsl): float,
// or half under half emulation.
#ifndef XSHADE_BRDF_HLSL
#define XSHADE_BRDF_HLSL

#include "common.hlsl"

// ---- Normal distribution D ----------------------------------------------------------------

// The seed's GGX (Walter et al.), alpha = roughness. 0/0 at a = 0 and NoH = 1 (hazard 2); in
// fp16, a*a - 1 rounds to -1 below a ~ 0.0156 and the result overflows (hazard 8).
real D_GGX_seed(real NoH, real a) {
  real a2 = a * a;
  real d = NoH * NoH * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d);
}

// The same distribution written with 1 - NoH^2 = |n x h|^2, which keeps its precision where
// NoH is close to 1 (Filament's form): k = a / (|n x h|^2 + (NoH a)^2), D = k^2 / pi. For a unit
// h and a <= 1 the denominator is at least a^2 (D's peak); the floor holds that when h is not a
// unit vector (the safe half vector of l = -v is 0, hazard 3), and the clamp to the precision's
// largest value keeps k^2 finite in fp16 where a is below 0.0079.
real D_GGX_lagrange(float3 n, float3 h, real NoH, real a) {
  float3 nxh = cross(n, h);
  real k = a / max(dot(nxh, nxh) + (NoH * a) * (NoH * a), a * a);
  return min(k * k / kPi, kRealMax);
}

// ---- Geometry G, as the visibility term V = G / (4 NoL NoV) --------------------------------

// The seed's Cook-Torrance V-cavity G, as the seed writes it.
real G_cook_torrance(real NoL, real NoV, real VoH, real NoH) {
  real p2 = 2.0 * NoH * NoV / VoH;
  real p3 = 2.0 * NoH * NoL / VoH;
  return min(min(1.0, p2), p3);
}

// The seed's division: 0/0 at a silhouette (NoV = 0) or terminator (NoL = 0), hazard 1.
real V_cook_torrance(real NoL, real NoV, real VoH, real NoH) {
  return G_cook_torrance(NoL, NoV, VoH, NoH) / (4.0 * (NoL * NoV));
}

// Height-correlated Smith for GGX (Heitz 2014), already divided by 4 NoL NoV.
real V_smith_correlated(real NoL, real NoV, real a) {
  real a2 = a * a;
  real lambda_v = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
  real lambda_l = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
  return 0.5 / (lambda_v + lambda_l);
}

// Its linear approximation (Hammon 2017), cheaper by two square roots.
real V_smith_correlated_fast(real NoL, real NoV, real a) {
  return 0.5 / lerp(2.0 * NoL * NoV, NoL + NoV, a);
}

// ---- Fresnel F ----------------------------------------------------------------------------

// The seed's Schlick with Unity's specColor as R0, with the seed's half parameters. pow of a
// negative base is undefined in GLSL, and LoH can round to just above 1 (hazard 4).
float3 F_schlick(half3 R, half cosA) {
  return R + (1 - R) * pow((1 - cosA), 5);
}

// Schlick with the base saturated and the fifth power multiplied out: defined for every LoH.
real3 F_schlick_guarded(real3 f0, real LoH) {
  return f0 + (1.0 - f0) * pow5(saturate(1.0 - LoH));
}

// Schlick's factor through a spherical-Gaussian fit (Unreal 4): one exp2 instead of a power.
real3 F_spherical_gaussian(real3 f0, real LoH) {
  return f0 + (1.0 - f0) * exp2((-5.55473 * LoH - 6.98316) * LoH);
}

// The exact Fresnel reflectance of unpolarised light at a dielectric, per channel, with the
// index of refraction that gives R0 at normal incidence: eta = (1 + sqrt(R0)) / (1 - sqrt(R0)).
// R0 is capped below 1, where eta would be infinite (a metal's tinted R0 is not a dielectric's,
// so for metals this is a reference of the shape only).
real F_dielectric_exact_channel(real r0, real c) {
  real s = sqrt(clamp(r0, 0.0, 0.999));
  real eta = (1.0 + s) / (1.0 - s);
  real g = sqrt(eta * eta - 1.0 + c * c);
  real a = (g - c) / (g + c);
  real b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}

real3 F_dielectric_exact(real3 f0, real LoH) {
  real c = saturate(LoH);
  return real3(F_dielectric_exact_channel(f0.r, c), F_dielectric_exact_channel(f0.g, c),
                F_dielectric_exact_channel(f0.b, c));
}

// ---- The specular lobe --------------------------------------------------------------------

// The dot products the terms read. The seed does not show how it computes them; the seed form
// takes them as they come (our choice), so that it breaks exactly where SHADERS.md section 4
// says: 0/0 where NoL or NoV is exactly 0, pow of a negative base when LoH rounds above 1.
// (Clamping them to [0, 1] first, as Unity's DotClamped does, would turn the whole unlit half
// of every surface into 0/0.) The guarded form keeps every denominator away from zero
// (hazards 1, 2, 3).
struct BrdfInputs {
  float3 n;
  float3 h;
  float NoL;
  float NoV;
  float NoH;
  float VoH;
  float LoH;
  float a;  // GGX alpha
};

BrdfInputs brdf_inputs_seed(float3 n, float3 v, float3 l, float a) {
  BrdfInputs s;
  s.n = n;
  s.h = normalize(l + v);
  s.NoL = dot(n, l);
  s.NoV = dot(n, v);
  s.NoH = dot(n, s.h);
  s.VoH = dot(v, s.h);
  s.LoH = dot(l, s.h);
  s.a = a;
  return s;
}

#if defined(XSHADE_PRECISION_HALF)
// In fp16 (SHADERS.md hazards 2 and 8): alpha from 0.0079 keeps the peak of D below fp16's
// largest value, and cosines from 2^-8 keep 4 NoL NoV a normal fp16 number (>= 6.1e-5), so
// that no visibility term divides by a product that rounded to 0.
static const float kMinAlpha = 0.0079;
static const float kMinCosine = 0.0039;
#else
// Smallest alpha the guarded form lets through: D stays finite in fp32 (SHADERS.md hazard 2).
static const float kMinAlpha = 0.002;
// Smallest NoV, NoL and VoH a denominator sees: 1e-4 keeps D*F*G/(4 NoL NoV) finite at a
// silhouette while changing no visible pixel (hazard 1).
static const float kMinCosine = 1e-4;
#endif

BrdfInputs brdf_inputs_guarded(float3 n, float3 v, float3 l, float a) {
  BrdfInputs s;
  s.n = n;
  s.h = safe_normalize(l + v);
  s.NoL = max(dot(n, l), kMinCosine);
  s.NoV = max(dot(n, v), kMinCosine);
  s.NoH = saturate(dot(n, s.h));
  s.VoH = max(dot(v, s.h), kMinCosine);
  s.LoH = saturate(dot(l, s.h));
  s.a = max(a, kMinAlpha);
  return s;
}

BrdfInputs brdf_inputs(float3 n, float3 v, float3 l, float a) {
#if defined(_GUARDED)
  return brdf_inputs_guarded(n, v, l, a);
#else
  return brdf_inputs_seed(n, v, l, a);
#endif
}

// The forms of D, V and F the variant's keywords select (SHADERS.md section 6).
real distribution(BrdfInputs s) {
#if defined(_D_GGX_LAGRANGE)
  return D_GGX_lagrange(s.n, s.h, s.NoH, s.a);
#else
  return D_GGX_seed(s.NoH, s.a);
#endif
}

real visibility(BrdfInputs s) {
#if defined(_G_SMITH_CORRELATED)
  return V_smith_correlated(s.NoL, s.NoV, s.a);
#elif defined(_G_SMITH_FAST)
  return V_smith_correlated_fast(s.NoL, s.NoV, s.a);
#else
  return V_cook_torrance(s.NoL, s.NoV, s.VoH, s.NoH);
#endif
}

float3 fresnel(float3 spec_color, float LoH) {
#if defined(_F_SPHERICAL_GAUSSIAN)
  return F_spherical_gaussian(spec_color, LoH);
#elif defined(_F_EXACT)
  return F_dielectric_exact(spec_color, LoH);
#elif defined(_GUARDED)
  return F_schlick_guarded(spec_color, LoH);
#else
  return F_schlick(spec_color, LoH);
#endif
}

// D * F * G * pi / (4 NoL NoV), the seed's direct specular with Unity's extra pi.
float3 cook_torrance_specular(BrdfInputs s, float3 spec_color) {
  float D = distribution(s);
  float V = visibility(s);
  float3 F = fresnel(spec_color, s.LoH);
  return D * F * V * kPi;
}

// The direct light of one light: diffuse plus specular, times the light and the cosine at the
// surface, which is saturated whatever the form (a light below the horizon adds nothing).
float3 direct_light(float3 n, float3 v, float3 l, float a, float3 diff_color, float3 spec_color, float3 light_color) {
  BrdfInputs s = brdf_inputs(n, v, l, a);
  return (diff_color + cook_torrance_specular(s, spec_color)) * light_color * saturate(dot(n, l));
}

// ---- Metallic workflow --------------------------------------------------------------------

// Unity's DiffuseAndSpecularFromMetallic in linear space: dielectrics reflect 4 %.
void diffuse_and_specular_from_metallic(float3 albedo, float metallic, out float3 diff_color,
                                        out float3 spec_color, out float one_minus_reflectivity) {
  spec_color = lerp(float3(0.04, 0.04, 0.04), albedo, metallic);
  one_minus_reflectivity = 0.96 * (1.0 - metallic);
  diff_color = albedo * one_minus_reflectivity;
}

#endif
