// clip(x) discards the pixel when any component of x is negative.
#pragma fragment frag
float4 frag(float4 position : SV_Position) : SV_Target {
  clip(float2(1.0, position.x - 3.5));
  return float4(1, 2, 3, 4);
}
