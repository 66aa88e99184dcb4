// HLSL matrices: constructors fill rows, M[i] is a row, mul(M, v) treats v as a column and
// mul(v, M) as a row, * is component-wise, _mRC and _RC name elements.
#pragma fragment frag
float4 frag(float4 position : SV_Position) : SV_Target {
  float2x3 m = float2x3(1, 2, 3, 4, 5, 6);
  float2x2 a = float2x2(1, 2, 3, 4);
  float2x2 b = float2x2(5, 6, 7, 8);
  int i = int(position.x);
  if (i == 0) return float4(mul(m, float3(1, 10, 100)), 0, 0);
  if (i == 1) return float4(mul(float2(1, 10), m), 0);
  if (i == 2) return float4(m[1], m[0][2]);
  if (i == 3) return float4(m._m01, m._m10, m._12, determinant(a));  // _12 is one-based: row 1, column 2
  float2x2 ab = mul(a, b);
  if (i == 4) return float4(ab[0], ab[1]);
  float2x2 c = a * b;
  if (i == 5) return float4(c[0], c[1]);
  float3x2 t = transpose(m);
  return float4(t[0], t[2]);
}
