// The values the renderer gives a shader's constant-buffer members by name: xshade's own inputs
// (_WorldToClip, _CameraPosition, ...) and Unity's built-in shader variables (_Time,
// _ScreenParams, unity_ObjectToWorld, unity_SHAr, ...) as Unity's built-in render pipeline sets
// them on a Direct3D-like platform, without reversed Z. docs/shader_library.md tables every name
// with its convention.
//
// The world is right-handed with +y up (the scene's), the view matrix looks down -z, clip space is
// Direct3D's (z in [0, w], 0 at the near plane, +y up). Matrices are in HLSL component order (row
// by row), so that mul(M, v) in a shader is the host's M * v.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "harness/assets/spherical_harmonics.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

using UniformValueMap = std::map<std::string, std::vector<float>>;

// Unity's frame time, in seconds, for unity_DeltaTime: the scene is a still of a 60 Hz frame.
inline constexpr float kFrameSeconds = 1.0f / 60.0f;

// The camera's matrices: the view (world to view space, looking down -z) and the projection the
// shaders use (Direct3D clip space: glm::perspectiveRH_ZO), for a target of `aspect` = width / height.
glm::mat4 view_matrix(const Camera& camera);
glm::mat4 gpu_projection(const Camera& camera, float aspect);

// What a platform of Direct3D's conventions (shaderlab::direct3d_conventions) does after the
// projection, as Unity's GL.GetGPUProjectionMatrix does for a render target: depth reversed (z' =
// w - z: 1 at the near plane, 0 at the far) and y flipped, so that the target's row 0 holds the
// bottom of the picture; the identity for GLCore.
glm::mat4 render_target_convention(shaderlab::UnityPlatform platform);

// Every per-frame value: xshade's and Unity's. `screen` is the scene's target size (what
// _ScreenParams describes in every pass, post passes at half size included, as Unity's camera
// target does), `sh` the environment's irradiance / pi (spherical_harmonics.h).
UniformValueMap frame_inputs(const Scene& scene, const ShCoefficients& sh);

// The per-object values of an instance with model matrix `model`, added to (or replaced in) `values`.
void add_object_inputs(const glm::mat4& model, UniformValueMap& values);

// Graphics.Blit's view and projection, added to (or replaced in) `values`: the identity for both
// (the projection then flipped as the platform's render targets are, render_target_convention),
// which puts the full-screen triangle's corners where they are in clip space, as Blit's
// orthographic projection of its unit quad does (the camera's own matrices, unity_CameraProjection
// and the rest, stay as they are).
void add_blit_inputs(UniformValueMap& values, shaderlab::UnityPlatform platform);

// Whether the renderer gives the uniform `name` itself (frame_inputs, add_object_inputs, and
// X_TexelSize of every texture): a scene cannot set such a name, and it needs no default.
bool renderer_uniform(const std::string& name);

// Whether the renderer binds the texture `name` itself: the environment (_EnvironmentSpecular),
// Unity's reflection probes (unity_SpecCube0, unity_SpecCube1) and a light's attenuation textures
// (_LightTexture0, _LightTextureB0; forward_lights.h).
bool renderer_texture(const std::string& name);

// A texture Unity's renderer binds that xshade's scenes have no data for, and the built-in the
// renderer binds in its place (the light probe proxy volume's unity_ProbeVolumeSH, which nothing
// reads while unity_ProbeVolumeParams.x is 0); nullopt for any other name.
std::optional<TextureOrigin> renderer_default_texture(const std::string& name);

// X_TexelSize of a texture of `size` texels: (1 / width, 1 / height, width, height).
std::vector<float> texel_size(glm::uvec2 size);

// Unity's seven SH constants (unity_SHAr, SHAg, SHAb, SHBr, SHBg, SHBb, SHC) for the same
// irradiance / pi as `sh`: ShadeSH9(n) = (dot(SHA, (n, 1)), ...) + (dot(SHB, n.xyzz * n.yzzx), ...)
// + SHC.rgb * (n.x^2 - n.y^2) equals sh_evaluate(sh, n) for every unit n.
std::array<glm::vec4, 7> unity_sh_constants(const ShCoefficients& sh);

// The HLSL components of a matrix (row by row).
std::vector<float> hlsl_components(const glm::mat4& m);

}  // namespace xshade::harness
