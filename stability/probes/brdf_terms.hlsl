// Stability probe: the library's Cook-Torrance terms (include/brdf.hlsl) at the inputs the suite
// gives, one input per pixel column. The keywords choose the forms, as they do for a material.
//   row 0: (D, V, F at the given LoH, specular D F V pi)
//   row 1: (direct light of a grey material under a white light, specular times saturate(NoL),
//           diffuse colour of a white albedo at the given metallic, 0)
#pragma fragment frag
#pragma multi_compile _D_GGX_SEED _D_GGX_LAGRANGE
#pragma multi_compile _G_COOK_TORRANCE _G_SMITH_CORRELATED _G_SMITH_FAST
#pragma multi_compile _F_SCHLICK _F_SPHERICAL_GAUSSIAN _F_EXACT
#pragma multi_compile _ _GUARDED

#include "include/brdf.hlsl"

static const int kMaxInputs = 128;

cbuffer ProbeInputs {
  // Per input, four vectors: (n, alpha), (v, R0), (l, LoH for fresnel()), (metallic, 0, 0, 0).
  float4 _Inputs[kMaxInputs * 4];
};

float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x) * 4;
  float3 n = _Inputs[i].xyz;
  float a = _Inputs[i].w;
  float3 v = _Inputs[i + 1].xyz;
  float3 spec_color = _Inputs[i + 1].www;
  float3 l = _Inputs[i + 2].xyz;
  float LoH = _Inputs[i + 2].w;
  float metallic = _Inputs[i + 3].x;

  BrdfInputs s = brdf_inputs(n, v, l, a);
  float3 specular = cook_torrance_specular(s, spec_color);
  if (int(position.y) == 0) return float4(distribution(s), visibility(s), fresnel(spec_color, LoH).r, specular.r);

  float3 grey = float3(0.5, 0.5, 0.5);
  float3 direct = direct_light(n, v, l, a, grey, spec_color, float3(1.0, 1.0, 1.0));
  float3 diff_color, metal_spec_color;
  float one_minus_reflectivity;
  diffuse_and_specular_from_metallic(float3(1.0, 1.0, 1.0), metallic, diff_color, metal_spec_color, one_minus_reflectivity);
  return float4(direct.r, specular.r * saturate(dot(n, l)), diff_color.r, 0.0);
}
