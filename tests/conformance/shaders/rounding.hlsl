// round() takes halves to the even neighbour; trunc, floor and ceil as usual.
#pragma fragment frag
static const float kX[8] = { -2.5, -1.5, -0.5, 0.5, 1.5, 2.5, 2.4, -2.6 };
float4 frag(float4 position : SV_Position) : SV_Target {
  float x = kX[int(position.x)];
  return float4(round(x), trunc(x), floor(x), ceil(x));
}
