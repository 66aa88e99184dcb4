// What the renderer supplies to every material draw. The renderer fills these buffers by member
// name (docs/shader_library.md lists the names); a material declares its own properties as
// globals with annotations.
#ifndef XSHADE_SCENE_INPUTS_HLSL
#define XSHADE_SCENE_INPUTS_HLSL

cbuffer PerFrame {
  float4x4 _WorldToClip;
  float4 _CameraPosition;   // xyz: the camera in world space
  float4 _LightDirection;   // xyz: unit vector from the surface toward the (directional) light
  float4 _LightColor;       // rgb: the light's colour times its intensity
  // rgb: the environment's irradiance / pi as 9 spherical-harmonic coefficients, with the
  // cosine convolution folded in (see sh_irradiance).
  float4 _EnvironmentSH[9];
};

cbuffer PerObject {
  float4x4 _ObjectToWorld;
  float4x4 _NormalToWorld;  // inverse transpose of _ObjectToWorld, so that scaled normals stay normal
};

// The one vertex format of the harness's meshes.
struct MeshVertex {
  float3 position : POSITION;
  float3 normal : NORMAL;
  float4 tangent : TANGENT;
  float2 uv : TEXCOORD0;
};

// What the library's material vertex shader hands to its fragment shaders.
struct SurfaceVaryings {
  float4 clip_position : SV_Position;
  float3 world_position : TEXCOORD0;
  float3 world_normal : TEXCOORD1;
  float2 uv : TEXCOORD2;
};

SurfaceVaryings surface_vertex(MeshVertex input) {
  SurfaceVaryings output;
  float4 world = mul(_ObjectToWorld, float4(input.position, 1.0));
  output.clip_position = mul(_WorldToClip, world);
  output.world_position = world.xyz;
  output.world_normal = mul((float3x3)_NormalToWorld, input.normal);
  output.uv = input.uv;
  return output;
}

#endif
