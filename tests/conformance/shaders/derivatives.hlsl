// ddx and ddy follow the screen: x grows to the right and y downwards, as uv does.
#pragma fragment frag
float4 frag(float2 uv : TEXCOORD0, float4 position : SV_Position) : SV_Target {
  return float4(ddx(uv.x), ddy(uv.y), ddy(position.y), ddx(position.y));
}
