// A one-component vector (float1, what Unity's UNITY_FOG_COORDS declares) is a vector: its .x is
// an l-value and its swizzles are vectors of its one value.
#pragma fragment frag
float4 frag(float4 position : SV_Position) : SV_Target {
  float1 v;
  v.x = position.x - 0.5;
  v.x += 1.0;
  float2 twice = v.xx;
  return float4(v, twice, v.x * 2.0);
}
