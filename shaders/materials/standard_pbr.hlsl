// The seed's standard material: Cook-Torrance direct light plus Unity-style indirect light from
// the environment (SHADERS.md section 1). Keywords choose the form of each term (section 6) and
// whether the guards of section 4 are on; with no keyword this is the seed exactly.
#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _D_GGX_SEED _D_GGX_LAGRANGE
#pragma multi_compile _G_COOK_TORRANCE _G_SMITH_CORRELATED _G_SMITH_FAST
#pragma multi_compile _F_SCHLICK _F_SPHERICAL_GAUSSIAN _F_EXACT
#pragma multi_compile _ _GUARDED
#pragma multi_compile _ _INDIRECT_SAMPLED

#include "include/brdf.hlsl"
#include "include/environment.hlsl"
#include "include/scene_inputs.hlsl"

float4 _Color <string UIName = "Color";> = float4(1.0, 1.0, 1.0, 1.0);
Texture2D _MainTex <string UIName = "Albedo"; string Default = "white";>;
SamplerState sampler_MainTex;
float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.0;
float _Smoothness <string UIName = "Smoothness"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
// _INDIRECT_SAMPLED only: how many GGX samples estimate the environment's specular light.
float _IndirectSamples <string UIName = "Indirect specular samples"; float UIMin = 1.0; float UIMax = 4096.0;> = 64.0;

SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }

float4 frag(SurfaceVaryings input) : SV_Target {
  float3 n = normalize(input.world_normal);
  float3 v = normalize(_CameraPosition.xyz - input.world_position);
  float3 l = _LightDirection.xyz;

  float4 base = _MainTex.Sample(sampler_MainTex, input.uv) * _Color;
  float3 diff_color, spec_color;
  float one_minus_reflectivity;
  diffuse_and_specular_from_metallic(base.rgb, _Metallic, diff_color, spec_color, one_minus_reflectivity);

  // The seed uses roughness itself as GGX's alpha.
  float roughness = 1.0 - _Smoothness;
  float3 direct = direct_light(n, v, l, roughness, diff_color, spec_color, _LightColor.rgb);

  // Unity's indirect terms: SH irradiance for diffuse; the prefiltered environment, reduced
  // for rough surfaces and brightened toward grazing, for specular.
  float NoV = saturate(dot(n, v));
  float surface_reduction = 1.0 / (roughness * roughness + 1.0);
  float grazing = saturate(_Smoothness + 1.0 - one_minus_reflectivity);
  float3 indirect_diffuse = diff_color * sh_irradiance(n);
#if defined(_INDIRECT_SAMPLED)
  // The integral itself, sampled: the reference for Unity's approximation below.
  float3 indirect_specular = sampled_environment_specular(n, v, roughness, spec_color, int(_IndirectSamples));
#else
  float3 indirect_specular = surface_reduction * prefiltered_environment(reflect(-v, n), roughness) *
                             lerp(spec_color, float3(grazing, grazing, grazing), pow4(1.0 - NoV));
#endif
  return float4(direct + indirect_diffuse + indirect_specular, base.a);
}
