// ?: with a vector condition picks per component; scalars splat to vectors; truncation.
#pragma fragment frag
float4 frag(float4 position : SV_Position) : SV_Target {
  float x = position.x - 3.5;  // -3.5 .. 3.5 across 8 pixels
  float4 v = float4(x, -x, x * 2.0, 1.0);
  float4 picked = v > 0.0 ? v : 10.0;   // component-wise, with a splat of 10
  float3 splat = 2.0;
  splat *= 0.5 + x;
  float2 truncated = (float2)v;
  return float4(picked.x + picked.y, picked.z, splat.y, truncated.y);
}
