// HLSL packing of loose globals ($Globals), as of a cbuffer: a float3 after a float shares its
// register, a float2 after a float sits at 20; the host writes exactly those bytes.
#pragma fragment frag
float first;
float3 packed;  // offset 4: std140 (and glslang's layout of the globals) would put it at 16
float scalar;
float2 pair;    // offset 20
float4 frag(float4 position : SV_Position) : SV_Target {
  if (int(position.x) == 0) return float4(first, packed);
  return float4(scalar, pair, 0);
}
