#pragma fragment frag
struct FxaaTex { SamplerState smpl; Texture2D tex; };
Texture2D _MainTex; SamplerState sampler_MainTex;
float4 fetch(FxaaTex t, float2 uv) { return t.tex.SampleLevel(t.smpl, uv, 0.0) + t.tex.GatherGreen(t.smpl, uv, int2(1, 0)); }
float4 frag(float2 uv : TEXCOORD0) : SV_Target {
  FxaaTex mainTex;
  mainTex.tex = _MainTex;
  mainTex.smpl = sampler_MainTex;
  Texture2D alias = mainTex.tex;
  return fetch(mainTex, uv) + alias.Sample(mainTex.smpl, uv);
}
