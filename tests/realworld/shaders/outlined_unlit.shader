// A two-pass outline as Unity authors write it (a pass with Cull Front draws the mesh pushed out
// along its normals, so that its inside shows as a rim around the silhouette; then the body), on
// Unity's UnityCG.cginc from the corpus beside the project. Written for xshade's tests.
Shader "xshade/Outlined Unlit" {
  Properties {
    _MainTex ("Texture", 2D) = "white" {}
    _OutlineColor ("Outline colour", Color) = (1, 0.5, 0, 1)
    _OutlineWidth ("Outline width", Range(0, 0.2)) = 0.06
  }
  SubShader {
    Tags { "RenderType" = "Opaque" }
    CGINCLUDE
    #include "UnityCG.cginc"
    ENDCG

    Pass {
      Name "OUTLINE"
      Cull Front
      CGPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      float _OutlineWidth;
      fixed4 _OutlineColor;
      float4 vert(float4 vertex : POSITION, float3 normal : NORMAL) : SV_POSITION {
        return UnityObjectToClipPos(vertex.xyz + normal * _OutlineWidth);
      }
      fixed4 frag() : SV_Target { return _OutlineColor; }
      ENDCG
    }

    Pass {
      Name "BODY"
      CGPROGRAM
      #pragma vertex vert
      #pragma fragment frag
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
