// A stencil window as Unity authors write one (a portal or a mask): drawn before the opaque
// objects (Queue Geometry-1), it writes no colour and no depth, only its reference into the
// stencil buffer wherever it covers. Written for xshade's tests.
Shader "xshade/Stencil Window" {
  Properties {
    _StencilRef ("Stencil reference", Int) = 1
  }
  SubShader {
    Tags { "Queue" = "Geometry-1" "RenderType" = "Opaque" }
    Pass {
      ColorMask 0
      ZWrite Off
      Stencil {
        Ref [_StencilRef]
        Comp Always
        Pass Replace
      }
      CGPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #include "UnityCG.cginc"
      float4 vert(float4 vertex : POSITION) : SV_POSITION { return UnityObjectToClipPos(vertex); }
      fixed4 frag() : SV_Target { return 0; }
      ENDCG
    }
  }
}
