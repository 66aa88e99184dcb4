// Stability probe: the library's toon terms (include/toon.hlsl) at the inputs the suite gives,
// one input per pixel column: (ramp, stepped specular, rim, 0). _GUARDED chooses the form.
#pragma fragment frag
#pragma multi_compile _ _GUARDED

#include "include/toon.hlsl"

static const int kMaxInputs = 512;

cbuffer ProbeInputs {
  // Per input: (NoL, NoV, NoH, attenuation), (threshold, smoothing, shininess, gloss).
  float4 _Inputs[kMaxInputs * 2];
};

float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x) * 2;
  float4 dots = _Inputs[i];
  float4 knobs = _Inputs[i + 1];
  return float4(toon_ramp(dots.x, dots.w, knobs.x, knobs.y), toon_specular(dots.z, knobs.z, knobs.w, knobs.y),
                toon_rim(dots.y, dots.x, dots.w, knobs.x, knobs.y), 0.0);
}
