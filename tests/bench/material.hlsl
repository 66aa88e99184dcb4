// A Unity-style lit material, the benchmark's larger input.
#pragma vertex vert
#pragma fragment frag
#pragma multi_compile _ USE_RAMP

cbuffer PerObject : register(b1) {
  float4x4 _ObjectToWorld;
  float4x4 _WorldToClip;
  float3 _CameraPosition;
  float _Time;
};
float4 _Color <string UIName = "Colour";> = float4(1, 1, 1, 1);
float _Metallic <string UIName = "Metallic"; float UIMin = 0.0; float UIMax = 1.0;> = 0.0;
float _Smoothness <string UIName = "Smoothness"; float UIMin = 0.0; float UIMax = 1.0;> = 0.5;
float3 _LightDirection = float3(0, 1, 0);
float3 _LightColor = float3(1, 1, 1);
Texture2D _MainTex;
SamplerState sampler_MainTex;
sampler2D _Ramp;

struct appdata { float3 vertex : POSITION; float3 normal : NORMAL; float4 tangent : TANGENT; float2 uv : TEXCOORD0; };
struct v2f { float4 pos : SV_Position; float3 world : TEXCOORD0; float3 normal : TEXCOORD1; float2 uv : TEXCOORD2; };

static const float PI = 3.14159265;

float D_GGX(float NoH, float a) {
  float a2 = a * a;
  float d = NoH * NoH * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}
float3 F_Schlick(float3 f0, float LoH) {
  float f = pow(1.0 - LoH, 5.0);
  return f0 + (1.0 - f0) * f;
}
float G_CookTorrance(float NoH, float NoV, float NoL, float VoH) {
  return min(1.0, min(2.0 * NoH * NoV / VoH, 2.0 * NoH * NoL / VoH));
}
void split(float3 albedo, float metallic, out float3 diffuse, out float3 specular) {
  specular = lerp(float3(0.04, 0.04, 0.04), albedo, metallic);
  diffuse = albedo * 0.96 * (1.0 - metallic);
}

v2f vert(appdata v) {
  v2f o;
  float4 world = mul(_ObjectToWorld, float4(v.vertex, 1.0));
  o.pos = mul(_WorldToClip, world);
  o.world = world.xyz;
  o.normal = normalize(mul((float3x3)_ObjectToWorld, v.normal));
  o.uv = v.uv;
  return o;
}

float4 frag(v2f i) : SV_Target {
  float3 n = normalize(i.normal);
  float3 v = normalize(_CameraPosition - i.world);
  float3 l = normalize(_LightDirection);
  float3 h = normalize(l + v);
  float NoL = saturate(dot(n, l)), NoV = saturate(dot(n, v)), NoH = saturate(dot(n, h));
  float VoH = saturate(dot(v, h)), LoH = saturate(dot(l, h));
  float3 albedo = _MainTex.Sample(sampler_MainTex, i.uv).rgb * _Color.rgb;
  float3 diffuse, specular;
  split(albedo, _Metallic, diffuse, specular);
  float a = 1.0 - _Smoothness;
  float3 spec = D_GGX(NoH, a) * F_Schlick(specular, LoH) * G_CookTorrance(NoH, NoV, NoL, VoH) * PI / (4.0 * NoL * NoV + 1e-4);
  float3 color = (diffuse + spec) * _LightColor * NoL;
#ifdef USE_RAMP
  color *= tex2D(_Ramp, float2(NoL, 0.5)).rgb;
#endif
  for (int k = 0; k < 4; ++k) color += 0.01 * sin(_Time + k) * albedo;
  return float4(color, _Color.a);
}
