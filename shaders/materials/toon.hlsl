// The seed's toon (cel) material: a two-tone ramp, a stepped highlight and a rim light
// (SHADERS.md section 2). _SHADOW_TEX darkens through a texture instead of a flat colour;
// _GUARDED turns on the guards of SHADERS.md section 4 (hazards 5 to 7).
#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _SHADOW_TEX
#pragma multi_compile _ _GUARDED

#include "include/scene_inputs.hlsl"
#include "include/toon.hlsl"

fixed4 _Color <string UIName = "Color";> = fixed4(1.0, 1.0, 1.0, 1.0);
Texture2D _MainTex <string UIName = "Albedo (alpha = gloss)"; string Default = "white";>;
SamplerState sampler_MainTex;
#if defined(_SHADOW_TEX)
Texture2D _ShadowTex <string UIName = "Shadow texture"; string Default = "white";>;
SamplerState sampler_ShadowTex;
#endif
fixed4 _HColor <string UIName = "Highlight color";> = fixed4(0.785, 0.785, 0.785, 1.0);
fixed4 _SColor <string UIName = "Shadow color (alpha = blend toward highlight)";> = fixed4(0.195, 0.195, 0.195, 1.0);
fixed _RampThreshold <string UIName = "Ramp threshold"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
fixed _RampSmooth <string UIName = "Ramp smoothing"; float UIMin = 0.0; float UIMax = 1.0;> = 0.1;
fixed4 _SpecColor <string UIName = "Specular color";> = fixed4(0.5, 0.5, 0.5, 1.0);
fixed _SpecSmooth <string UIName = "Specular smoothing"; float UIMin = 0.0; float UIMax = 1.0;> = 0.1;
fixed _Shininess <string UIName = "Shininess"; float UIMin = 0.0; float UIMax = 1.0;> = 0.2;
fixed4 _RimColor <string UIName = "Rim color (alpha = strength)";> = fixed4(0.8, 0.8, 0.8, 0.6);
fixed _RimThreshold <string UIName = "Rim threshold"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
fixed _RimSmooth <string UIName = "Rim smoothing"; float UIMin = 0.0; float UIMax = 1.0;> = 0.1;

SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }

fixed4 frag(SurfaceVaryings input) : SV_Target {
  float3 n = normalize(input.world_normal);
  float3 v = normalize(_CameraPosition.xyz - input.world_position);
  float3 l = _LightDirection.xyz;
  float3 h = normalize(l + v);
  fixed NoL = dot(n, l);
  fixed NoV = dot(n, v);
  fixed NoH = dot(n, h);
  // A directional light without shadows: nothing attenuates it.
  fixed atten = 1.0;
  fixed3 light_color = _LightColor.rgb;

  fixed4 main_tex = _MainTex.Sample(sampler_MainTex, input.uv);
  fixed4 albedo = main_tex * _Color;
  fixed gloss = main_tex.a;

  fixed ramp = toon_ramp(NoL, atten, _RampThreshold, _RampSmooth);
#if defined(_SHADOW_TEX)
  albedo.rgb = lerp(_ShadowTex.Sample(sampler_ShadowTex, input.uv).rgb, albedo.rgb, ramp);
#endif
  fixed4 s_color = lerp(_HColor, _SColor, _SColor.a);
  fixed3 ramp_color = lerp(s_color.rgb, _HColor.rgb, ramp);
  fixed3 diffuse = albedo.rgb * light_color * ramp_color;

  fixed3 specular = _SpecColor.rgb * light_color * toon_specular(NoH, _Shininess, gloss, _SpecSmooth);
  fixed3 rim = _RimColor.rgb * light_color * _RimColor.a * toon_rim(NoV, NoL, atten, _RimThreshold, _RimSmooth);
  return fixed4(diffuse + specular + rim, albedo.a);
}
