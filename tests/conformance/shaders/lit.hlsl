// lit(n_dot_l, n_dot_h, m) as HLSL documents it, in each form HLSL takes its arguments: float,
// half, int and uint scalars (converted to float), one-component vectors, and literals. The
// arguments of pixel x are kArgs[x]; each form's row holds values it represents exactly.
#pragma fragment frag
static const float3 kArgs[8] = {
    float3(0.5, 0.25, 2.0),   // float
    float3(0.5, 0.75, 4.0),   // half
    float3(2.0, 3.0, 2.0),    // int
    float3(1.0, 2.0, 3.0),    // uint
    float3(0.25, 0.5, 3.0),   // float1
    float3(0.25, 0.5, 3.0),   // literals
    float3(-0.5, 0.5, 2.0),   // n.l < 0: no diffuse, no specular
    float3(0.5, -0.25, 2.0),  // n.h < 0: diffuse, no specular
};
float4 frag(float4 position : SV_Position) : SV_Target {
  const int i = int(position.x);
  const float3 a = kArgs[i];
  if (i == 1) return lit(half(a.x), half(a.y), half(a.z));
  if (i == 2) return lit(int(a.x), int(a.y), int(a.z));
  if (i == 3) return lit(uint(a.x), uint(a.y), uint(a.z));
  if (i == 4) {
    const float1 l = a.x, h = a.y, m = a.z;
    return lit(l, h, m);
  }
  if (i == 5) return lit(0.25h, 0.5, 3);
  return lit(a.x, a.y, a.z);
}
