// Signed integer / and % on vectors: each component truncates toward zero on its own, with the
// remainder taking the dividend's sign (xshade's GLSL builds these per component, not as scalars).
#pragma fragment frag
static const int kA[8] = { -7, -7, 7, 7, -8, 0, 5, -1 };
static const int kB[8] = { 2, -2, 2, -2, 3, 3, -5, 1 };
float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x);
  int2 a = int2(kA[i], -kA[i]);
  int2 b = int2(kB[i], kB[i]);
  int2 q = a / b;
  int2 r = a % b;
  return float4(q.x, r.x, q.y, r.y);
}
