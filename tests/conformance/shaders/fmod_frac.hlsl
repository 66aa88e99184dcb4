// fmod and % on floats truncate (the result takes the dividend's sign); frac is x - floor(x).
#pragma fragment frag
static const float kX[8] = { -7.5, -3.0, -0.5, 0.0, 0.5, 3.0, 7.25, -1.75 };
float4 frag(float4 position : SV_Position) : SV_Target {
  float x = kX[int(position.x)];
  return float4(fmod(x, 2.0), fmod(x, -2.0), x % 2.0, frac(x));
}
