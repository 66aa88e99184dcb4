// An unlit textured material drawn only where the stencil buffer compares as its properties say
// (Unity's UnityEngine.Rendering.CompareFunction numbers: Equal 3, NotEqual 6), so that one
// object shows only through a stencil window and another only outside it. Written for xshade's
// tests.
Shader "xshade/Stencil Masked Unlit" {
  Properties {
    _MainTex ("Texture", 2D) = "white" {}
    _StencilRef ("Stencil reference", Int) = 1
    [Enum(UnityEngine.Rendering.CompareFunction)] _StencilComp ("Stencil comparison", Int) = 3
  }
  SubShader {
    Tags { "RenderType" = "Opaque" }
    Pass {
      Stencil {
        Ref [_StencilRef]
        Comp [_StencilComp]
      }
      CGPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #include "UnityCG.cginc"
      sampler2D _MainTex;
      float4 _MainTex_ST;
      struct v2f {
        float4 pos : SV_POSITION;
        float2 uv : TEXCOORD0;
      };
      v2f vert(appdata_base v) {
        v2f o;
        o.pos = UnityObjectToClipPos(v.vertex);
        o.uv = TRANSFORM_TEX(v.texcoord, _MainTex);
        return o;
      }
      fixed4 frag(v2f i) : SV_Target { return tex2D(_MainTex, i.uv); }
      ENDCG
    }
  }
}
