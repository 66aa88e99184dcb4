// The seed's physically based material as a Unity author writes it: a vertex/fragment ForwardBase
// pass whose direct light is the seed's Cook-Torrance (GGX D, the V-cavity G, Schlick's F; the
// seed's formulas, hazards and all: SHADERS.md section 1) and whose indirect light comes from
// Unity's GI functions (ShadeSH9's ambient, Unity_GlossyEnvironment's reflection probe, FresnelLerp),
// times the main light's attenuation and shadow. It casts with its Fallback's ShadowCaster.
Shader "xshade/StandardPBR" {
  Properties {
    _Color ("Color", Color) = (1, 1, 1, 1)
    _MainTex ("Albedo", 2D) = "white" {}
    _Metallic ("Metallic", Range(0, 1)) = 0
    _Smoothness ("Smoothness", Range(0, 1)) = 0.5
  }
  SubShader {
    Tags { "RenderType" = "Opaque" }
    Pass {
      Tags { "LightMode" = "ForwardBase" }
      CGPROGRAM
      #pragma vertex vert
      #pragma fragment frag
      #pragma target 3.0
      #pragma multi_compile_fwdbase
      #include "UnityCG.cginc"
      #include "Lighting.cginc"
      #include "AutoLight.cginc"
      #include "UnityStandardUtils.cginc"
      #include "UnityImageBasedLighting.cginc"

      sampler2D _MainTex;
      float4 _MainTex_ST;
      fixed4 _Color;
      half _Metallic;
      half _Smoothness;

      struct v2f {
        float4 pos : SV_POSITION;
        float2 uv : TEXCOORD0;
        float3 worldNormal : TEXCOORD1;
        float3 worldPos : TEXCOORD2;
        UNITY_SHADOW_COORDS(3)
      };

      v2f vert(appdata_full v) {
        v2f o;
        UNITY_INITIALIZE_OUTPUT(v2f, o);
        o.pos = UnityObjectToClipPos(v.vertex);
        o.uv = TRANSFORM_TEX(v.texcoord, _MainTex);
        o.worldNormal = UnityObjectToWorldNormal(v.normal);
        o.worldPos = mul(unity_ObjectToWorld, v.vertex).xyz;
        UNITY_TRANSFER_SHADOW(o, v.texcoord1.xy);
        return o;
      }

      float4 frag(v2f i) : SV_Target {
        float3 n = normalize(i.worldNormal);
        float3 v = normalize(UnityWorldSpaceViewDir(i.worldPos));
        float3 l = normalize(UnityWorldSpaceLightDir(i.worldPos));
        float4 base = tex2D(_MainTex, i.uv) * _Color;
        half oneMinusReflectivity;
        half3 specColor;
        half3 diffColor = DiffuseAndSpecularFromMetallic(base.rgb, _Metallic, specColor, oneMinusReflectivity);
        // The seed uses roughness itself as GGX's alpha.
        float roughness = 1.0 - _Smoothness;

        float3 h = normalize(l + v);
        float NdotL = dot(n, l);
        float NdotV = dot(n, v);
        float NdotH = dot(n, h);
        float VdotH = dot(v, h);
        float LdotH = dot(l, h);
        float a2 = roughness * roughness;
        float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
        float D = a2 / (UNITY_PI * d * d);
        float G = min(1.0, min(2.0 * NdotH * NdotV / VdotH, 2.0 * NdotH * NdotL / VdotH));
        float3 F = specColor + (1.0 - specColor) * pow(1.0 - LdotH, 5.0);
        float3 directSpecular = (D * F * G) * UNITY_PI / (4.0 * (NdotL * NdotV));
        UNITY_LIGHT_ATTENUATION(atten, i, i.worldPos)
        float3 direct = (diffColor + directSpecular) * _LightColor0.rgb * saturate(NdotL) * atten;

        // Unity's indirect light: the ambient SH, and the reflection probe blurred for the
        // roughness, reduced for rough surfaces and brightened toward grazing.
        float3 indirectDiffuse = diffColor * ShadeSH9(float4(n, 1.0));
        Unity_GlossyEnvironmentData glossy;
        glossy.roughness = roughness;
        glossy.reflUVW = reflect(-v, n);
        float3 environment = Unity_GlossyEnvironment(UNITY_PASS_TEXCUBE(unity_SpecCube0), unity_SpecCube0_HDR, glossy);
        float surfaceReduction = 1.0 / (roughness * roughness + 1.0);
        half grazing = saturate(_Smoothness + 1.0 - oneMinusReflectivity);
        float3 indirectSpecular = surfaceReduction * environment * FresnelLerp(specColor, grazing, saturate(NdotV));
        return float4(direct + indirectDiffuse + indirectSpecular, base.a);
      }
      ENDCG
    }
  }
  Fallback "Legacy Shaders/VertexLit"
}
