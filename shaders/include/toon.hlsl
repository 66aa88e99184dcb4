// The toon (cel) lighting terms of SHADERS.md section 2, each a function so that the stability
// suite can call it. The seed computes in fixed (half) precision; so does this.
#ifndef XSHADE_TOON_HLSL
#define XSHADE_TOON_HLSL

// The smallest smoothing width the guarded form passes to smoothstep: smoothstep with
// edge0 >= edge1 is undefined in GLSL (SHADERS.md hazard 5). 1e-4 is far below one 8-bit step
// of any ramp, so a guarded hard edge looks like the seed's. In fp16 both edges must stay
// distinct numbers wherever the threshold lies in [0, 1]: 2e-3 is 4 fp16 ulps just below 1
// (1e-4 vanishes there, and the edges meet again).
#if defined(XSHADE_PRECISION_HALF)
static const float kMinSmooth = 2e-3;
#else
static const float kMinSmooth = 1e-4;
#endif

// smoothstep over a band of width `band` centred on `threshold`, as the seed writes it.
fixed toon_step_seed(fixed threshold, fixed band, fixed x) {
  return smoothstep(threshold - band * 0.5, threshold + band * 0.5, x);
}

fixed toon_step_guarded(fixed threshold, fixed band, fixed x) {
  fixed half_band = max(band, kMinSmooth) * 0.5;
  return smoothstep(threshold - half_band, threshold + half_band, x);
}

fixed toon_step(fixed threshold, fixed band, fixed x) {
#if defined(_GUARDED)
  return toon_step_guarded(threshold, band, x);
#else
  return toon_step_seed(threshold, band, x);
#endif
}

// Half-Lambert (our choice: the seed does not show it) through the ramp, times attenuation.
fixed toon_ramp(fixed NoL, fixed atten, fixed threshold, fixed band) {
  fixed nd = NoL * 0.5 + 0.5;
  return toon_step(threshold, band, nd) * atten;
}

// Stepped Blinn-Phong (our choice). The seed form raises NoH, which can be negative, to a
// power that can be 0 (hazard 6); the guarded form saturates the base and floors the exponent.
fixed toon_specular(fixed NoH, fixed shininess, fixed gloss, fixed band) {
#if defined(_GUARDED)
  fixed s = pow(saturate(NoH), max(shininess * 128.0, kMinSmooth)) * gloss;
#else
  fixed s = pow(NoH, shininess * 128.0) * gloss;
#endif
  return toon_step(0.5, band, s);
}

// Rim light: strongest where the surface turns away from the viewer but faces the light. With
// NoV or NoL negative the seed's product leaves [0, 1] (hazard 7); the guarded form saturates both.
fixed toon_rim(fixed NoV, fixed NoL, fixed atten, fixed threshold, fixed band) {
#if defined(_GUARDED)
  fixed rim = (1.0 - saturate(NoV)) * saturate(NoL) * atten;
#else
  fixed rim = (1.0 - NoV) * NoL * atten;
#endif
  return toon_step(threshold, band, rim);
}

#endif
