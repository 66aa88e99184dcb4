// Small helpers every shader of the library shares.
#ifndef XSHADE_COMMON_HLSL
#define XSHADE_COMMON_HLSL

static const float kPi = 3.14159265359;

// The precision the lighting terms compute in, as Unity's `real`: float, or half when the
// harness runs with half emulation (--precision half defines XSHADE_PRECISION_HALF), so that a
// term's own arithmetic is rounded to fp16 as on a GPU that prefers half. kRealMax is its
// largest finite value.
#if defined(XSHADE_PRECISION_HALF)
#define real half
#define real3 half3
static const float kRealMax = 65504.0;
#else
#define real float
#define real3 float3
static const float kRealMax = 3.402823e38;
#endif

// x^5 by multiplication: pow(x, 5) is undefined for x < 0 in GLSL (SHADERS.md hazard 4), and a
// product is defined everywhere and cheaper.
float pow5(float x) {
  float x2 = x * x;
  return x2 * x2 * x;
}

float pow4(float x) {
  float x2 = x * x;
  return x2 * x2;
}

float max3(float3 v) { return max(v.x, max(v.y, v.z)); }

// normalize() of a zero vector is 0/0. Light and view on opposite horizons make l + v = 0
// (hazard 3); the floor of 1e-3 on the squared length keeps such a vector finite and short.
float3 safe_normalize(float3 v) { return v * rsqrt(max(dot(v, v), 1e-3)); }

#endif
