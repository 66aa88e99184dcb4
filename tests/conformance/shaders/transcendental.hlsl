// atan2(y, x) in every quadrant, rsqrt, log10, and saturate outside [0, 1].
#pragma fragment frag
static const float2 kYX[8] = { float2(1, 1), float2(1, -1), float2(-1, -1), float2(-1, 1),
                               float2(0, -1), float2(2, 0), float2(-3, 0.5), float2(0.25, 4) };
static const float kX[8] = { 0.25, 1.0, 4.0, 100.0, 1e-3, 0.5, 7.0, 1e4 };
float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x);
  float2 yx = kYX[i];
  float x = kX[i];
  return float4(atan2(yx.x, yx.y), rsqrt(x), log10(x), saturate(x - 2.0));
}
