// HLSL packing: a float3 after a float shares its register, a float2 after a float sits at 4,
// and a matrix is stored by columns; the host writes exactly those bytes.
#pragma fragment frag
cbuffer Params {
  float first;
  float3 packed;     // offset 4: std140 cannot place it there
  float scalar;
  float2 pair;       // offset 20
  float4x4 matrix_;  // column_major
};
float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x);
  if (i == 0) return float4(first, packed);
  if (i == 1) return float4(scalar, pair, 0);
  return mul(matrix_, float4(1, 2, 3, 4));
}
