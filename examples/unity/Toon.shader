// The seed's toon (cel) material as a Unity author writes it: a surface shader whose lighting
// model, LightingToon, turns the light into a two-tone ramp, a stepped highlight and a rim light
// (SHADERS.md section 2), each times the light's attenuation, so that shadows fall across the
// ramp. xshade generates the passes Unity generates from `#pragma surface` (docs/unity.md).
Shader "xshade/Toon" {
  Properties {
    _Color ("Color", Color) = (1, 1, 1, 1)
    _MainTex ("Albedo (alpha = gloss)", 2D) = "white" {}
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

    void surf(Input IN, inout SurfaceOutput o) {
      fixed4 mainTex = tex2D(_MainTex, IN.uv_MainTex);
      o.Albedo = mainTex.rgb * _Color.rgb;
      o.Alpha = mainTex.a * _Color.a;
      o.Specular = _Shininess;
      o.Gloss = mainTex.a;
    }

    inline fixed4 LightingToon(SurfaceOutput s, half3 lightDir, half3 viewDir, half atten) {
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
