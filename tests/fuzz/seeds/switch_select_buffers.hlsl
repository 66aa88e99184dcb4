// Seed for the fuzzer: switch, select, ConstantBuffer<S>, the buffer resources (unreached),
// overloads that DXC ranks, string attributes.
#pragma fragment frag
struct Scene { float4 tint; float strength; };
ConstantBuffer<Scene> scene : register(b1);
StructuredBuffer<Scene> scenes;
RWTexture2D<float4> output;
float pick(float a, float b) { return a; }
float3 pick(float3 a, float3 b) { return b; }
float3 unused(uint i) { output[uint2(i, 0)] = scenes[i].tint; return scenes.Load(i).tint.rgb; }
[RootSignature("RootFlags(0), " "CBV(b0)")]
float4 frag(float2 uv : TEXCOORD0, float4 position : SV_Position) : SV_Target {
  float4 c = scene.tint;
  switch (int(position.x) % 3) {
    case 0: c.r = pick(c.r, 1); break;
    case 1:
    case -1: c.rgb = pick(c.rgb, 0.5); break;
    default: c = select(c > 0.5, c, 1 - c);
  }
  return c * scene.strength;
}
