
#pragma vertex vert
#pragma fragment frag
Texture1D t1; Texture1DArray t1a; Texture2D t2; Texture2DArray t2a; Texture3D t3;
TextureCube tc; TextureCubeArray tca; Texture2DMS<float4, 4> tms; Texture2DMSArray<float4> tmsa;
Texture2D<float> depth; TextureCube<float> depth_cube; Texture2DArray<float> depth_array;
Texture2D<uint4> ids; Texture2D<int2> offsets; Texture3D<half3> lut;
SamplerState s; SamplerComparisonState cmp;
static const int2 kOffset = int2(1, -1);

float4 explicit_levels(float3 p) {
  float4 r = t1.SampleLevel(s, p.x, 0) + t1a.SampleLevel(s, p.xy, 1) + t2.SampleLevel(s, p.xy, 0, int2(1, 0));
  r += t2a.SampleLevel(s, p, 0, kOffset) + t3.SampleLevel(s, p, 0, int3(0, 1, 0)) + tc.SampleLevel(s, p, 2);
  r += tca.SampleLevel(s, float4(p, 1), 0) + t2.SampleGrad(s, p.xy, p.xy, p.yx, int2(-1, 0));
  r += tc.SampleGrad(s, p, p, p) + lut.SampleLevel(s, p, 0).rgbb;
  r += t1.Load(int2(3, 0)) + t1a.Load(int3(1, 2, 0), 1) + t2.Load(int3(1, 2, 0)) + t2.Load(int3(1, 2, 0), int2(1, 1));
  r += t2a.Load(int4(1, 2, 3, 0)) + t3.Load(int4(1, 2, 3, 0), int3(1, 0, 0));
  r += tms.Load(int2(1, 2), 3) + tms.Load(int2(1, 2), 0, int2(1, 0)) + tmsa.Load(int3(1, 2, 1), 2);
  r += float4(ids.Load(int3(0, 0, 0))) + float4(offsets.Load(int3(0, 0, 0)), 0, 0) + t2[uint2(4, 5)];
  r += t2.Gather(s, p.xy) + t2.GatherRed(s, p.xy, int2(1, 1)) + t2.GatherGreen(s, p.xy) + t2.GatherBlue(s, p.xy);
  r += t2.GatherAlpha(s, p.xy) + t2a.Gather(s, p) + tc.GatherRed(s, p) + tca.GatherAlpha(s, float4(p, 0));
  r += float4(ids.GatherRed(s, p.xy)) + depth.GatherCmp(cmp, p.xy, 0.5) + depth.GatherCmpRed(cmp, p.xy, 0.5, int2(0, 1));
  r += depth.SampleCmpLevelZero(cmp, p.xy, 0.5) + depth.SampleCmpLevelZero(cmp, p.xy, 0.5, int2(1, 0));
  r += depth_cube.SampleCmpLevelZero(cmp, p, 0.5) + depth_array.SampleCmpLevelZero(cmp, p, 0.5);
  uint w, h, e, l, n;
  float fw, fh, fe, fl;
  t1.GetDimensions(w); t1.GetDimensions(1, w, l); t1a.GetDimensions(w, e); t2.GetDimensions(w, h);
  t2.GetDimensions(0, fw, fh, fl); t2a.GetDimensions(w, h, e); t2a.GetDimensions(1, w, h, e, l);
  t3.GetDimensions(w, h, e); t3.GetDimensions(0, fw, fh, fe, fl); tc.GetDimensions(w, h); tca.GetDimensions(w, h, e);
  tms.GetDimensions(w, h, n); tmsa.GetDimensions(w, h, e, n);
  return r + float4(w + h + e + l + n, fw + fh + fe + fl, 0, 0);
}

float4 vert(float3 p : POSITION) : SV_Position { return explicit_levels(p); }

float4 frag(float4 position : SV_Position) : SV_Target {
  const float3 p = position.xyz;
  float4 r = explicit_levels(p) + t1.Sample(s, p.x) + t2.Sample(s, p.xy, int2(0, 1)) + t2a.Sample(s, p);
  r += t3.Sample(s, p) + tc.Sample(s, p) + tca.Sample(s, float4(p, 2)) + t2.SampleBias(s, p.xy, -1, int2(1, 1));
  r += tc.SampleBias(s, p, 0.5) + depth.SampleCmp(cmp, p.xy, 0.5) + depth.SampleCmp(cmp, p.xy, 0.5, int2(1, 0));
  r += depth_cube.SampleCmp(cmp, p, 0.5) + depth_array.SampleCmp(cmp, p, 0.5);
  r += t2.CalculateLevelOfDetail(s, p.xy) + t3.CalculateLevelOfDetailUnclamped(s, p) + tc.CalculateLevelOfDetail(s, p);
  return r;
}
