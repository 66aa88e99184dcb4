// Car paint: a metallic base under a clear lacquer. The coat is a second, smooth GGX lobe with a
// dielectric's Fresnel (4 % head-on); the light it reflects never reaches the base. Written on
// xshade's shader library: include/ comes from wherever xshade is installed.
#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ _CLEAR_COAT

#include "include/brdf.hlsl"
#include "include/environment.hlsl"
#include "include/scene_inputs.hlsl"

float4 _BaseColor <string UIName = "Base color";> = float4(0.6, 0.05, 0.05, 1.0);
float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.8;
float _Smoothness <string UIName = "Base smoothness"; float UIMin = 0.0; float UIMax = 1.0;> = 0.45;
float _CoatSmoothness <string UIName = "Coat smoothness"; float UIMin = 0.0; float UIMax = 1.0;> = 0.95;
float _CoatStrength <string UIName = "Coat strength"; float UIMin = 0.0; float UIMax = 1.0;> = 1.0;

SurfaceVaryings vert(MeshVertex input) { return surface_vertex(input); }

// One GGX lobe in the library's guarded forms, so that neither a silhouette nor a mirror-smooth
// coat divides by zero.
float3 ggx_lobe(float3 n, float3 v, float3 l, float a, float3 f0) {
  BrdfInputs s = brdf_inputs_guarded(n, v, l, a);
  return D_GGX_lagrange(s.n, s.h, s.NoH, s.a) * V_smith_correlated(s.NoL, s.NoV, s.a) * F_schlick_guarded(f0, s.LoH) *
         kPi;
}

float4 frag(SurfaceVaryings input) : SV_Target {
  float3 n = normalize(input.world_normal);
  float3 v = normalize(_CameraPosition.xyz - input.world_position);
  float3 l = _LightDirection.xyz;
  float NoL = saturate(dot(n, l));
  float NoV = saturate(dot(n, v));

  float3 diff_color, spec_color;
  float one_minus_reflectivity;
  diffuse_and_specular_from_metallic(_BaseColor.rgb, _Metallic, diff_color, spec_color, one_minus_reflectivity);
  float roughness = 1.0 - _Smoothness;
  float3 color = (diff_color + ggx_lobe(n, v, l, roughness, spec_color)) * NoL * _LightColor.rgb;
  color += diff_color * sh_irradiance(n) + spec_color * prefiltered_environment(reflect(-v, n), roughness);

#if defined(_CLEAR_COAT)
  float coat_roughness = 1.0 - _CoatSmoothness;
  float3 coat_f0 = float3(0.04, 0.04, 0.04);
  float coat_reflects = F_schlick_guarded(coat_f0, NoV).x * _CoatStrength;
  float3 coat = ggx_lobe(n, v, l, coat_roughness, coat_f0) * NoL * _LightColor.rgb +
                prefiltered_environment(reflect(-v, n), coat_roughness) * coat_reflects;
  color = color * (1.0 - coat_reflects) + coat * _CoatStrength;
#endif
  return float4(color, _BaseColor.a);
}
