// Depth of field with a bokeh gather, in five full-screen passes (SHADERS.md section 3, after
// Unity Post Processing v2 and the catlikecoding tutorial). The seed computes in half precision;
// so does this. _GUARDED turns on the guards of SHADERS.md section 4 (hazards 9 and 10).
//
// Each `#pragma pass` line declares a pass: its name, its fragment entry point, the size of its
// target (full or half the scene's resolution) and, for each texture it samples, where that
// texture comes from: scene.color, scene.depth, or an earlier pass's name. The last pass's output
// is the effect's output. docs/shader_library.md describes the syntax.
#pragma pass coc        frag_coc        scale=full _CameraDepthTexture=scene.depth
#pragma pass prefilter  frag_prefilter  scale=half _MainTex=scene.color _CoCTex=coc
#pragma pass bokeh      frag_bokeh      scale=half _MainTex=prefilter
#pragma pass postfilter frag_postfilter scale=half _MainTex=bokeh
#pragma pass combine    frag_combine    scale=full _MainTex=scene.color _CoCTex=coc _DoFTex=postfilter
#pragma multi_compile _KERNEL_SMALL _KERNEL_MEDIUM _KERNEL_LARGE _KERNEL_VERY_LARGE _KERNEL_DENSE
#pragma multi_compile _ _GUARDED

#include "include/common.hlsl"
#include "include/dof_kernels.hlsl"

// Filled by the renderer: the camera's planes, and for each texture X of the pass, X_TexelSize
// = (1 / width, 1 / height, width, height) as Unity has it.
cbuffer PostInputs : register(b0) {
  float4 _CameraNearFar;  // x: near plane, y: far plane (view-space distances)
  float4 _MainTex_TexelSize;
  float4 _CoCTex_TexelSize;
};

half _FocusDistance <string UIName = "Focus distance"; float UIMin = 0.1; float UIMax = 100.0;> = 10.0;
half _FocusRange <string UIName = "Focus range"; float UIMin = 0.1; float UIMax = 10.0;> = 3.0;
half _BokehRadius <string UIName = "Bokeh radius (pixels)"; float UIMin = 1.0; float UIMax = 10.0;> = 4.0;
// _KERNEL_DENSE only: the spacing of its samples in texels. 0.5 gathers four times as many,
// between the texels (bilinear): the check that the reference has converged.
half _DenseStep <string UIName = "Dense reference: sample spacing (texels)"; float UIMin = 0.25; float UIMax = 1.0;> = 1.0;

Texture2D _CameraDepthTexture;
SamplerState sampler_CameraDepthTexture;
Texture2D _MainTex;
SamplerState sampler_MainTex;
Texture2D _CoCTex;
SamplerState sampler_CoCTex;
Texture2D _DoFTex;
SamplerState sampler_DoFTex;

// Distance from the camera for a depth-buffer value of a Direct3D-style projection (0 at the
// near plane, 1 at the far plane).
float linear_eye_depth(float depth) {
  float n = _CameraNearFar.x;
  float f = _CameraNearFar.y;
  return n * f / (f - depth * (f - n));
}

// The smallest focus range the guarded form divides by (hazard 10): 1e-4 scene units is
// sharper than any pixel at the fixed scenes' distances.
static const half kMinFocusRange = 1e-4;
// The smallest weight sum the guarded form divides by (hazard 10).
static const half kMinWeightSum = 1e-5;
// A CoC below this (in pixels) is in focus: the combine pass shows the source there.
static const half kInFocusCoC = 0.1;

// 1. Circle of confusion in pixels, signed: negative in front of the focus, positive behind.
half4 frag_coc(float2 uv : TEXCOORD0) : SV_Target {
  float depth = _CameraDepthTexture.SampleLevel(sampler_CameraDepthTexture, uv, 0.0).r;
#if defined(_GUARDED)
  // The sky (depth 1, hazard 9) is as far as blur goes, whatever rounding did to its distance.
  half coc = depth >= 1.0 ? 1.0
                          : clamp((linear_eye_depth(depth) - _FocusDistance) / max(_FocusRange, kMinFocusRange), -1.0, 1.0);
#else
  half coc = clamp((linear_eye_depth(depth) - _FocusDistance) / _FocusRange, -1.0, 1.0);
#endif
  coc *= _BokehRadius;
  return half4(coc, coc, coc, 1.0);
}

// 2. Down to half resolution: colour weighted by CoC (and by brightness, against flicker), and
// the CoC of largest magnitude among the four taps so that near blur is not lost. The four taps
// are the four full-resolution texels under this pixel, read exactly: bilinear taps aimed at
// their centres pick up a trace of the neighbours from rounding in the interpolated uv, and
// where a near and a far CoC tie in magnitude that trace decides which one wins. The reads are
// clamped to the source's last texel, since a Load outside a texture is undefined: a source 1
// texel wide (or high) still gets a half-resolution target of 1, whose pixel has no second texel
// under it. For every other size the clamp changes nothing (half rounds down).
half4 frag_prefilter(float2 uv : TEXCOORD0, float4 position : SV_Position) : SV_Target {
  int2 texel = int2(position.xy) * 2;
  int2 color_last = int2(_MainTex_TexelSize.zw) - 1;
  int2 c_lo = min(texel, color_last);
  int2 c_hi = min(texel + 1, color_last);
  int2 coc_last = int2(_CoCTex_TexelSize.zw) - 1;
  int2 k_lo = min(texel, coc_last);
  int2 k_hi = min(texel + 1, coc_last);
  half3 c0 = _MainTex.Load(int3(c_lo.x, c_lo.y, 0)).rgb;
  half3 c1 = _MainTex.Load(int3(c_hi.x, c_lo.y, 0)).rgb;
  half3 c2 = _MainTex.Load(int3(c_lo.x, c_hi.y, 0)).rgb;
  half3 c3 = _MainTex.Load(int3(c_hi.x, c_hi.y, 0)).rgb;
  half coc0 = _CoCTex.Load(int3(k_lo.x, k_lo.y, 0)).r;
  half coc1 = _CoCTex.Load(int3(k_hi.x, k_lo.y, 0)).r;
  half coc2 = _CoCTex.Load(int3(k_lo.x, k_hi.y, 0)).r;
  half coc3 = _CoCTex.Load(int3(k_hi.x, k_hi.y, 0)).r;

  half w0 = abs(coc0) / (max3(c0) + 1.0);
  half w1 = abs(coc1) / (max3(c1) + 1.0);
  half w2 = abs(coc2) / (max3(c2) + 1.0);
  half w3 = abs(coc3) / (max3(c3) + 1.0);
  half3 color = c0 * w0 + c1 * w1 + c2 * w2 + c3 * w3;
#if defined(_GUARDED)
  color /= max(w0 + w1 + w2 + w3, kMinWeightSum);
#else
  color /= w0 + w1 + w2 + w3;
#endif

  half coc_min = min(min(coc0, coc1), min(coc2, coc3));
  half coc_max = max(max(coc0, coc1), max(coc2, coc3));
  half coc = coc_max >= -coc_min ? coc_max : coc_min;
  return half4(color, coc);
}

// How much a sample at `radius` pixels with circle of confusion `coc` covers this pixel.
half bokeh_weight(half coc, half radius) { return saturate((coc - radius + 2.0) / 2.0); }

// Adds to the bokeh's sums (background and foreground apart) the sample `o` texels of its source
// away from uv, for a pixel of CoC `coc`.
void gather_bokeh_sample(inout half3 bg_color, inout half bg_weight, inout half3 fg_color, inout half fg_weight,
                         float2 uv, half coc, float2 o) {
  half radius = length(o);
  o *= _MainTex_TexelSize.xy;
  half4 s = _MainTex.SampleLevel(sampler_MainTex, uv + o, 0.0);
  half bgw = bokeh_weight(max(0.0, min(s.a, coc)), radius);
  bg_color += s.rgb * bgw;
  bg_weight += bgw;
  half fgw = bokeh_weight(-s.a, radius);
#if defined(_GUARDED)
  // An in-focus sample is no foreground (as Unity PPv2 cuts it): counted as one, it gave an
  // in-focus pixel a foreground coverage of about 0.2, and the combine blended that much blur
  // over the sharp source (SHADERS.md case 13 wants the source there).
  fgw *= step(kInFocusCoC, -s.a);
#endif
  fg_color += s.rgb * fgw;
  fg_weight += fgw;
}

// 3. The bokeh: gather over the disk kernel, background and foreground apart; the foreground's
// coverage decides how much of it lies over the background. Each sample stands for an equal
// share of the unit disk (pi / samples), so the coverage is the foreground's weight times that.
// _KERNEL_DENSE, the reference the ring kernels are judged against, gathers every texel within
// _BokehRadius instead of the rings.
half4 frag_bokeh(float2 uv : TEXCOORD0) : SV_Target {
  half coc = _MainTex.SampleLevel(sampler_MainTex, uv, 0.0).a;
  half3 bg_color = 0.0;
  half3 fg_color = 0.0;
  half bg_weight = 0.0;
  half fg_weight = 0.0;
#if defined(_KERNEL_DENSE)
  int reach = int(ceil(_BokehRadius / _DenseStep));
  float radius_squared = _BokehRadius * _BokehRadius;
  int sample_count = 0;
  for (int y = -reach; y <= reach; y++) {
    for (int x = -reach; x <= reach; x++) {
      float2 o = float2(x, y) * _DenseStep;
      if (dot(o, o) <= radius_squared) {
        gather_bokeh_sample(bg_color, bg_weight, fg_color, fg_weight, uv, coc, o);
        sample_count++;
      }
    }
  }
#else
  int sample_count = kBokehSampleCount;
  for (int k = 0; k < kBokehSampleCount; k++)
    gather_bokeh_sample(bg_color, bg_weight, fg_color, fg_weight, uv, coc, kBokehKernel[k] * _BokehRadius);
#endif
  // A zero sum leaves its colour at zero instead of dividing 0 by 0.
  bg_color *= 1.0 / (bg_weight + (bg_weight == 0.0 ? 1.0 : 0.0));
  fg_color *= 1.0 / (fg_weight + (fg_weight == 0.0 ? 1.0 : 0.0));
  half bgfg = min(1.0, fg_weight * kPi / sample_count);
  half3 color = lerp(bg_color, fg_color, bgfg);
  return half4(color, bgfg);
}

// 4. A tent filter over the half-resolution bokeh: four bilinear taps half a texel away.
half4 frag_postfilter(float2 uv : TEXCOORD0) : SV_Target {
  float4 o = _MainTex_TexelSize.xyxy * float2(-0.5, 0.5).xxyy;
  half4 s = _MainTex.SampleLevel(sampler_MainTex, uv + o.xy, 0.0) + _MainTex.SampleLevel(sampler_MainTex, uv + o.zy, 0.0) +
            _MainTex.SampleLevel(sampler_MainTex, uv + o.xw, 0.0) + _MainTex.SampleLevel(sampler_MainTex, uv + o.zw, 0.0);
  return s * 0.25;
}

// 5. Back over the sharp image: in focus (|coc| < 0.1 pixel) the source shows through unchanged;
// the foreground's coverage (dof.a) blends over it wherever it reaches.
half4 frag_combine(float2 uv : TEXCOORD0) : SV_Target {
  half4 source = _MainTex.SampleLevel(sampler_MainTex, uv, 0.0);
  half coc = _CoCTex.SampleLevel(sampler_CoCTex, uv, 0.0).r;
  half4 dof = _DoFTex.SampleLevel(sampler_DoFTex, uv, 0.0);
  half strength = smoothstep(kInFocusCoC, 1.0, abs(coc));
  half3 color = lerp(source.rgb, dof.rgb, strength + dof.a - strength * dof.a);
  return half4(color, source.a);
}
