// Signed integer / and % truncate toward zero; unsigned ones are plain.
#pragma fragment frag
static const int kA[8] = { -7, -7, 7, 7, -8, 0, 5, -1 };
static const int kB[8] = { 2, -2, 2, -2, 3, 3, -5, 1 };
float4 frag(float4 position : SV_Position) : SV_Target {
  int i = int(position.x);
  int a = kA[i];
  int b = kB[i];
  uint ua = uint(abs(a)) + 10u;
  return float4(a / b, a % b, ua / 3u, ua % 3u);
}
