// The seed's depth of field as a Unity author writes it: an image effect whose five passes a C#
// script blits in order (Graphics.Blit(source, destination, material, pass)), as Post Processing
// v2's depth of field does (SHADERS.md section 3): the circle of confusion from the camera's depth,
// a half-resolution prefilter weighted by it, the bokeh gathered over PPv2's small disk kernel
// (16 samples) with background and foreground apart, a tent postfilter, and the combine over the
// sharp image. The script sets _FocusDistance, _FocusRange and _BokehRadius (pixels).
Shader "xshade/DepthOfField" {
  Properties {
    _MainTex ("Source", 2D) = "white" {}
  }

  CGINCLUDE
  #include "UnityCG.cginc"

  Texture2D _MainTex;
  SamplerState sampler_MainTex;
  Texture2D _CoCTex;
  SamplerState sampler_CoCTex;
  Texture2D _DoFTex;
  SamplerState sampler_DoFTex;
  UNITY_DECLARE_DEPTH_TEXTURE(_CameraDepthTexture);
  float4 _MainTex_TexelSize;
  float4 _CoCTex_TexelSize;
  half _FocusDistance, _FocusRange, _BokehRadius;

  // A CoC below this (in pixels) is in focus: the combine shows the source there.
  static const half kInFocusCoC = 0.1;

  // PPv2's small disk kernel: the centre, a ring of 5 and a ring of 10 on the unit disk.
  static const int kSampleCount = 16;
  static const float2 kDiskKernel[kSampleCount] = {
    float2(0, 0),
    float2(0.54545456, 0), float2(0.16855472, 0.5187581), float2(-0.44128203, 0.3206101),
    float2(-0.44128197, -0.3206102), float2(0.1685548, -0.5187581),
    float2(1, 0), float2(0.809017, 0.58778524), float2(0.30901697, 0.95105654), float2(-0.30901703, 0.9510565),
    float2(-0.80901706, 0.5877852), float2(-1, 0), float2(-0.80901694, -0.58778536), float2(-0.30901664, -0.9510566),
    float2(0.30901712, -0.9510565), float2(0.80901694, -0.5877853),
  };

  struct Interpolators {
    float4 pos : SV_POSITION;
    float2 uv : TEXCOORD0;
  };

  Interpolators VertexProgram(appdata_img v) {
    Interpolators i;
    i.pos = UnityObjectToClipPos(v.vertex);
    i.uv = v.texcoord;
    return i;
  }

  half max3(half3 c) { return max(c.r, max(c.g, c.b)); }

  // How much a sample at `radius` pixels with circle of confusion `coc` covers this pixel.
  half Weigh(half coc, half radius) { return saturate((coc - radius + 2) / 2); }
  ENDCG

  SubShader {
    Cull Off ZTest Always ZWrite Off

    Pass {  // 0: the circle of confusion in pixels, negative in front of the focus
      Name "CoC"
      CGPROGRAM
      #pragma vertex VertexProgram
      #pragma fragment FragmentProgram
      half4 FragmentProgram(Interpolators i) : SV_Target {
        float depth = LinearEyeDepth(SAMPLE_DEPTH_TEXTURE(_CameraDepthTexture, i.uv));
        half coc = clamp((depth - _FocusDistance) / _FocusRange, -1, 1) * _BokehRadius;
        return half4(coc, coc, coc, 1);
      }
      ENDCG
    }

    Pass {  // 1: down to half resolution, weighted by the CoC and against bright flicker
      Name "Prefilter"
      CGPROGRAM
      #pragma vertex VertexProgram
      #pragma fragment FragmentProgram
      half4 FragmentProgram(Interpolators i) : SV_Target {
        // The four source texels under this pixel (i.pos: its position in pixels), read exactly.
        int2 texel = int2(i.pos.xy) * 2;
        int2 colorLast = int2(_MainTex_TexelSize.zw) - 1;
        int2 cocLast = int2(_CoCTex_TexelSize.zw) - 1;
        int2 c0 = min(texel, colorLast), c1 = min(texel + 1, colorLast);
        int2 k0 = min(texel, cocLast), k1 = min(texel + 1, cocLast);
        half3 s0 = _MainTex.Load(int3(c0.x, c0.y, 0)).rgb;
        half3 s1 = _MainTex.Load(int3(c1.x, c0.y, 0)).rgb;
        half3 s2 = _MainTex.Load(int3(c0.x, c1.y, 0)).rgb;
        half3 s3 = _MainTex.Load(int3(c1.x, c1.y, 0)).rgb;
        half coc0 = _CoCTex.Load(int3(k0.x, k0.y, 0)).r;
        half coc1 = _CoCTex.Load(int3(k1.x, k0.y, 0)).r;
        half coc2 = _CoCTex.Load(int3(k0.x, k1.y, 0)).r;
        half coc3 = _CoCTex.Load(int3(k1.x, k1.y, 0)).r;
        half w0 = abs(coc0) / (max3(s0) + 1);
        half w1 = abs(coc1) / (max3(s1) + 1);
        half w2 = abs(coc2) / (max3(s2) + 1);
        half w3 = abs(coc3) / (max3(s3) + 1);
        half3 color = (s0 * w0 + s1 * w1 + s2 * w2 + s3 * w3) / (w0 + w1 + w2 + w3);
        half cocMin = min(min(coc0, coc1), min(coc2, coc3));
        half cocMax = max(max(coc0, coc1), max(coc2, coc3));
        half coc = cocMax >= -cocMin ? cocMax : cocMin;
        return half4(color, coc);
      }
      ENDCG
    }

    Pass {  // 2: the bokeh, background and foreground gathered apart
      Name "Bokeh"
      CGPROGRAM
      #pragma vertex VertexProgram
      #pragma fragment FragmentProgram
      half4 FragmentProgram(Interpolators i) : SV_Target {
        half coc = _MainTex.SampleLevel(sampler_MainTex, i.uv, 0).a;
        half3 bgColor = 0, fgColor = 0;
        half bgWeight = 0, fgWeight = 0;
        for (int k = 0; k < kSampleCount; k++) {
          float2 o = kDiskKernel[k] * _BokehRadius;
          half radius = length(o);
          o *= _MainTex_TexelSize.xy;
          half4 s = _MainTex.SampleLevel(sampler_MainTex, i.uv + o, 0);
          half bgw = Weigh(max(0, min(s.a, coc)), radius);
          bgColor += s.rgb * bgw;
          bgWeight += bgw;
          half fgw = Weigh(-s.a, radius);
          fgColor += s.rgb * fgw;
          fgWeight += fgw;
        }
        bgColor *= 1 / (bgWeight + (bgWeight == 0));
        fgColor *= 1 / (fgWeight + (fgWeight == 0));
        half bgfg = min(1, fgWeight * UNITY_PI / kSampleCount);
        return half4(lerp(bgColor, fgColor, bgfg), bgfg);
      }
      ENDCG
    }

    Pass {  // 3: a tent filter over the bokeh
      Name "Postfilter"
      CGPROGRAM
      #pragma vertex VertexProgram
      #pragma fragment FragmentProgram
      half4 FragmentProgram(Interpolators i) : SV_Target {
        float4 o = _MainTex_TexelSize.xyxy * float2(-0.5, 0.5).xxyy;
        half4 s = _MainTex.SampleLevel(sampler_MainTex, i.uv + o.xy, 0) + _MainTex.SampleLevel(sampler_MainTex, i.uv + o.zy, 0) +
                  _MainTex.SampleLevel(sampler_MainTex, i.uv + o.xw, 0) + _MainTex.SampleLevel(sampler_MainTex, i.uv + o.zw, 0);
        return s * 0.25;
      }
      ENDCG
    }

    Pass {  // 4: back over the sharp image
      Name "Combine"
      CGPROGRAM
      #pragma vertex VertexProgram
      #pragma fragment FragmentProgram
      half4 FragmentProgram(Interpolators i) : SV_Target {
        half4 source = _MainTex.SampleLevel(sampler_MainTex, i.uv, 0);
        half coc = _CoCTex.SampleLevel(sampler_CoCTex, i.uv, 0).r;
        half4 dof = _DoFTex.SampleLevel(sampler_DoFTex, i.uv, 0);
        half strength = smoothstep(kInFocusCoC, 1, abs(coc));
        half3 color = lerp(source.rgb, dof.rgb, strength + dof.a - strength * dof.a);
        return half4(color, source.a);
      }
      ENDCG
    }
  }
}
