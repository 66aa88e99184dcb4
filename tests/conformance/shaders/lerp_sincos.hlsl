// lerp extrapolates outside [0, 1]; sincos writes both out parameters.
#pragma fragment frag
static const float kS[8] = { -1.0, 0.0, 0.25, 0.5, 1.0, 2.0, -0.5, 0.75 };
float4 frag(float4 position : SV_Position) : SV_Target {
  float s = kS[int(position.x)];
  float sine, cosine;
  sincos(s * 3.0, sine, cosine);
  return float4(lerp(2.0, 6.0, s), lerp(float2(1, -1), float2(3, 5), s).y, sine, cosine);
}
