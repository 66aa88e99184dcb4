// The seed's toon with its shadow texture, as the seed's author writes it: Toon.shader with a
// custom output struct, SurfaceOutputCustom, whose Shadow field holds a texture's colour that
// replaces the albedo where the ramp falls to shadow (SHADERS.md section 2, the _SHADOW_TEX form).
Shader "xshade/Toon Shadow Texture" {
  Properties {
    _Color ("Color", Color) = (1, 1, 1, 1)
    _MainTex ("Albedo (alpha = gloss)", 2D) = "white" {}
    _ShadowTex ("Shadow texture", 2D) = "white" {}
    _HColor ("Highlight color", Color) = (0.785, 0.785, 0.785, 1)
    _SColor ("Shadow color (alpha = blend toward highlight)", Color) = (0.195, 0.195, 0.195, 1)
    _RampThreshold ("Ramp threshold", Range(0, 1)) = 0.5
    _RampSmooth ("Ramp smoothing", Range(0, 1)) = 0.1
    _SpecColor ("Specular color", Color) = (0.5, 0.5, 0.5, 1)
    _SpecSmooth ("Specular smoothing", Range(0, 1)) = 0.1
    _Shininess ("Shininess", Range(0.01, 1)) = 0.2
    _RimColor ("Rim color (alpha = strength)", Color) = (0.8, 0.8, 0.8, 0.6)
    _RimThreshold ("Rim threshold", Range(0, 1)) = 0.5
    _RimSmooth ("Rim smoothing", Range(0, 1)) = 0.1
  }
  SubShader {
    Tags { "RenderType" = "Opaque" }

    CGPROGRAM
    #pragma surface surf Toon fullforwardshadows addshadow
    #pragma target 3.0

    sampler2D _MainTex;
    sampler2D _ShadowTex;
    fixed4 _Color;
    fixed4 _HColor;
    fixed4 _SColor;
    fixed _RampThreshold;
    fixed _RampSmooth;
    fixed _SpecSmooth;
    fixed _Shininess;
    fixed4 _RimColor;
    fixed _RimThreshold;
    fixed _RimSmooth;

    struct Input {
      float2 uv_MainTex;
    };

    struct SurfaceOutputCustom {
      fixed3 Albedo;
      fixed3 Normal;
      fixed3 Emission;
      half Specular;
      fixed Gloss;
      fixed Alpha;
      fixed3 Shadow;
    };

    void surf(Input IN, inout SurfaceOutputCustom o) {
      fixed4 mainTex = tex2D(_MainTex, IN.uv_MainTex);
      o.Shadow = tex2D(_ShadowTex, IN.uv_MainTex).rgb;
      o.Albedo = mainTex.rgb * _Color.rgb;
      o.Alpha = mainTex.a * _Color.a;
      o.Specular = _Shininess;
      o.Gloss = mainTex.a;
    }

    inline fixed4 LightingToon(SurfaceOutputCustom s, half3 lightDir, half3 viewDir, half atten) {
      half3 normalDir = normalize(s.Normal);
      half3 halfDir = normalize(lightDir + viewDir);
      fixed ndl = dot(normalDir, lightDir);
      fixed ndv = dot(normalDir, viewDir);
      fixed ndh = dot(normalDir, halfDir);
      fixed3 lightColor = _LightColor0.rgb;

      // Half-Lambert through the ramp.
      fixed nd1 = ndl * 0.5 + 0.5;
      fixed ramp = smoothstep(_RampThreshold - _RampSmooth * 0.5, _RampThreshold + _RampSmooth * 0.5, nd1);
      ramp *= atten;
      s.Albedo = lerp(s.Shadow, s.Albedo, ramp);
      fixed4 sColor = lerp(_HColor, _SColor, _SColor.a);
      fixed3 rampColor = lerp(sColor.rgb, _HColor.rgb, ramp);
      fixed3 diffuse = s.Albedo * lightColor * rampColor;

      // A stepped Blinn-Phong highlight, its strength the texture's gloss.
      fixed spec = pow(ndh, s.Specular * 128.0) * s.Gloss;
      spec = smoothstep(0.5 - _SpecSmooth * 0.5, 0.5 + _SpecSmooth * 0.5, spec) * atten;
      fixed3 specular = _SpecColor.rgb * lightColor * spec;

      // The rim: where the surface turns from the viewer but faces the light.
      fixed rim = (1.0 - ndv) * ndl;
      rim *= atten;
      rim = smoothstep(_RimThreshold - _RimSmooth * 0.5, _RimThreshold + _RimSmooth * 0.5, rim);
      fixed3 rimColor = _RimColor.rgb * lightColor * _RimColor.a * rim;

      fixed4 color;
      color.rgb = diffuse + specular + rimColor;
      color.a = s.Alpha;
      return color;
    }
    ENDCG
  }
  Fallback "Diffuse"
}
