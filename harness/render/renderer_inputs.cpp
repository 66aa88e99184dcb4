#include "harness/render/renderer_inputs.h"

#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "harness/render/forward_lights.h"

namespace xshade::harness {
namespace {

std::vector<float> components(glm::vec4 v) { return {v.x, v.y, v.z, v.w}; }
std::vector<float> components(glm::vec3 v) { return {v.x, v.y, v.z}; }

// Unity's camera space: its camera transform's local axes, +x right, +y up, +z forward (the view
// matrix's -z).
const glm::mat4 kViewToCamera = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, -1.0f));

// A probe's box that nothing leaves: box projection is off (ProbePosition.w = 0), and the
// w of BoxMin, Unity's blend weight of the first probe, is 1.
constexpr float kUnboundedProbe = 1e30f;

}  // namespace

std::vector<float> hlsl_components(const glm::mat4& m) {
  std::vector<float> out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.push_back(m[c][r]);
  return out;
}

glm::mat4 view_matrix(const Camera& camera) { return glm::lookAtRH(camera.position, camera.target, camera.up); }

glm::mat4 gpu_projection(const Camera& camera, float aspect) {
  return glm::perspectiveRH_ZO(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane, camera.far_plane);
}

glm::mat4 render_target_convention(shaderlab::UnityPlatform platform) {
  if (!shaderlab::direct3d_conventions(platform)) return glm::mat4(1.0f);
  glm::mat4 convention(1.0f);  // column-major: [column][row]
  convention[1][1] = -1.0f;    // y' = -y
  convention[2][2] = -1.0f;    // z' = w - z
  convention[3][2] = 1.0f;
  return convention;
}

std::vector<float> texel_size(glm::uvec2 size) {
  return {1.0f / float(size.x), 1.0f / float(size.y), float(size.x), float(size.y)};
}

std::array<glm::vec4, 7> unity_sh_constants(const ShCoefficients& sh) {
  // The basis constants of spherical_harmonics.h, folded into Unity's polynomial in n:
  // band 0 and the constant part of Y6 = 0.315392 (3 z^2 - 1) go to SHA.w, z^2 to SHB.z.
  constexpr float k0 = 0.282095f, k1 = 0.488603f, kxy = 1.092548f, k6 = 0.315392f, k8 = 0.546274f;
  std::array<glm::vec4, 7> out{};
  for (int channel = 0; channel < 3; ++channel) {
    const auto c = [&](int i) { return sh[i][channel]; };
    out[channel] = {k1 * c(3), k1 * c(1), k1 * c(2), k0 * c(0) - k6 * c(6)};
    out[3 + channel] = {kxy * c(4), kxy * c(5), 3.0f * k6 * c(6), kxy * c(7)};
    out[6][channel] = k8 * c(8);
  }
  out[6].w = 1.0f;  // as Unity sets it; ShadeSH9 reads SHC.rgb only
  return out;
}

UniformValueMap frame_inputs(const Scene& scene, const ShCoefficients& sh) {
  const Camera& camera = scene.camera;
  const float width = float(scene.width), height = float(scene.height);
  const bool direct3d = shaderlab::direct3d_conventions(scene.unity_platform);
  const glm::mat4 projection = render_target_convention(scene.unity_platform) * gpu_projection(camera, width / height);
  const glm::mat4 view = view_matrix(camera);
  // The main light: the brightest directional one (Unity's ForwardBase light; xshade's own
  // materials take it too); a scene without one is lit by its other lights and its environment.
  const Light light = main_light(scene);
  const float near = camera.near_plane, far = camera.far_plane;

  UniformValueMap values;
  // xshade's own.
  values["_WorldToClip"] = hlsl_components(projection * view);
  values["_CameraPosition"] = components(glm::vec4(camera.position, 1.0f));
  values["_LightDirection"] = components(glm::vec4(light.direction, 0.0f));
  values["_LightColor"] = components(glm::vec4(light.color * light.intensity, 0.0f));
  std::vector<float>& environment_sh = values["_EnvironmentSH"];
  for (const glm::vec3& c : sh) environment_sh.insert(environment_sh.end(), {c.r, c.g, c.b, 0.0f});
  values["_CameraNearFar"] = {near, far, 0.0f, 0.0f};

  // Unity's: time.
  const float t = scene.time_seconds;
  values["_Time"] = {t / 20.0f, t, 2.0f * t, 3.0f * t};
  values["_SinTime"] = {std::sin(t / 8.0f), std::sin(t / 4.0f), std::sin(t / 2.0f), std::sin(t)};
  values["_CosTime"] = {std::cos(t / 8.0f), std::cos(t / 4.0f), std::cos(t / 2.0f), std::cos(t)};
  values["unity_DeltaTime"] = {kFrameSeconds, 1.0f / kFrameSeconds, kFrameSeconds, 1.0f / kFrameSeconds};

  // The camera and the screen. Depth is 0 at the near plane, or 1 where the platform reverses it;
  // x = -1 says the projection is flipped (render_target_convention).
  values["_WorldSpaceCameraPos"] = components(camera.position);
  values["_ProjectionParams"] = {direct3d ? -1.0f : 1.0f, near, far, 1.0f / far};
  values["_ScreenParams"] = {width, height, 1.0f + 1.0f / width, 1.0f + 1.0f / height};
  // So that Linear01Depth(z) = 1 / (x z + y) is the view distance / far either way.
  const float zx = direct3d ? far / near - 1.0f : 1.0f - far / near, zy = direct3d ? 1.0f : far / near;
  values["_ZBufferParams"] = {zx, zy, zx / far, zy / far};
  values["unity_OrthoParams"] = {0.0f, 0.0f, 0.0f, 0.0f};  // w = 0: a perspective camera
  const glm::mat4 camera_projection =                      // Camera.projectionMatrix: OpenGL's clip space, z in [-w, w]
      glm::perspectiveRH_NO(glm::radians(camera.fov_y_degrees), width / height, near, far);
  values["unity_CameraProjection"] = hlsl_components(camera_projection);
  values["unity_CameraInvProjection"] = hlsl_components(glm::inverse(camera_projection));
  values["unity_WorldToCamera"] = hlsl_components(kViewToCamera * view);
  values["unity_CameraToWorld"] = hlsl_components(glm::inverse(kViewToCamera * view));
  values["unity_MatrixV"] = hlsl_components(view);
  values["unity_MatrixInvV"] = hlsl_components(glm::inverse(view));
  values["glstate_matrix_projection"] = hlsl_components(projection);
  values["unity_MatrixVP"] = hlsl_components(projection * view);
  // One view, not stereo: the left eye's index, which single-pass stereo code reads anyway.
  values["unity_StereoEyeIndex"] = {0.0f};
  // Linear colour space: Unity's luminance weights for linear RGB, w = 1.
  values["unity_ColorSpaceLuminance"] = {0.0396819152f, 0.458021790f, 0.00609653955f, 1.0f};

  // Fog as Unity sets it from its RenderSettings (the scene's, else Unity's defaults, which a
  // shader reads only with a fog keyword on): x = density / sqrt(ln 2), y = density / ln 2,
  // z = -1 / (end - start), w = end / (end - start) (UnityShaderVariables.cginc).
  const FogSpec fog = scene.fog.value_or(FogSpec{});
  const float ln2 = std::log(2.0f);
  values["unity_FogColor"] = components(fog.color);
  const float span = fog.end - fog.start;  // the scene refuses linear fog without one; kept finite for the others
  values["unity_FogParams"] = {fog.density / std::sqrt(ln2), fog.density / ln2, span > 0.0f ? -1.0f / span : 0.0f,
                               span > 0.0f ? fog.end / span : 0.0f};

  // The main light: a directional one is its direction toward the light with w = 0; its colour
  // is Unity's Color (alpha 1) times the intensity, alpha included. An additive pass's light
  // replaces these (forward_lights.h).
  add_light_inputs(light, values);

  // The environment: ambient light as SH, and the reflection probe (unity_SpecCube0, the
  // environment as a cube map of linear HDR texels, decoded by DecodeHDR with (1, 1, 0, 0)).
  const std::array<glm::vec4, 7> unity_sh = unity_sh_constants(sh);
  const char* sh_names[] = {"unity_SHAr", "unity_SHAg", "unity_SHAb", "unity_SHBr",
                            "unity_SHBg", "unity_SHBb", "unity_SHC"};
  for (size_t i = 0; i < unity_sh.size(); ++i) values[sh_names[i]] = components(unity_sh[i]);
  // The legacy flat ambient (UNITY_LIGHTMODEL_AMBIENT is twice it, as Unity stores half): the
  // environment's ambient averaged over every direction, ShadeSH9's band 0 (0.282095 * c0).
  const glm::vec3 mean_ambient = 0.282095f * sh[0];
  values["glstate_lightmodel_ambient"] = components(glm::vec4(0.5f * mean_ambient, 0.5f));
  for (const std::string probe : {"unity_SpecCube0", "unity_SpecCube1"}) {
    values[probe + "_HDR"] = {1.0f, 1.0f, 0.0f, 0.0f};
    values[probe + "_BoxMin"] = {-kUnboundedProbe, -kUnboundedProbe, -kUnboundedProbe, 1.0f};
    values[probe + "_BoxMax"] = {kUnboundedProbe, kUnboundedProbe, kUnboundedProbe, 1.0f};
    values[probe + "_ProbePosition"] = {0.0f, 0.0f, 0.0f, 0.0f};
  }
  // What a light without shadows, and an object lit by the environment's harmonics rather than a
  // light probe proxy volume, have in Unity: a shadow of strength 0 (x = 1 - strength) that
  // never fades in (z = w = 0), the fade centred on the camera; the main light's shadowmask
  // channel, red; the proxy volume off (x = 0), so that ShadeSHPerPixel reads unity_SHA*.
  values["_LightShadowData"] = {1.0f, 0.0f, 0.0f, 0.0f};
  values["unity_ShadowFadeCenterAndType"] = components(glm::vec4(camera.position, 0.0f));
  values["unity_OcclusionMaskSelector"] = {1.0f, 0.0f, 0.0f, 0.0f};
  values["unity_ProbeVolumeParams"] = {0.0f, 0.0f, 0.0f, 0.0f};
  values["unity_ProbeVolumeWorldToObject"] = hlsl_components(glm::mat4(1.0f));
  values["unity_ProbeVolumeSizeInv"] = {1.0f, 1.0f, 1.0f};
  values["unity_ProbeVolumeMin"] = {0.0f, 0.0f, 0.0f};

  // ForwardBase's four per-vertex lights (forward_lights.h; an unused slot has no colour, no
  // attenuation), and the vertex-lit path's eight, each unused slot as Unity's manual describes
  // one: no colour, view-space position (0, 0, 1, 0), attenuation (-1, 1, 0, 0) (not a spot light,
  // no range), spot direction (0, 0, 1, 0).
  add_vertex_light_inputs(scene, forward_lights(scene).vertex, values);
  const auto eight = [](glm::vec4 v) {
    std::vector<float> out;
    for (int i = 0; i < 8; ++i) out.insert(out.end(), {v.x, v.y, v.z, v.w});
    return out;
  };
  values["unity_LightPosition"] = eight({0.0f, 0.0f, 1.0f, 0.0f});
  values["unity_LightAtten"] = eight({-1.0f, 1.0f, 0.0f, 0.0f});
  values["unity_SpotDirection"] = eight({0.0f, 0.0f, 1.0f, 0.0f});
  // A light without shadows sets none of the shadow map's values, and an object without a
  // lightmap has the scale-offset of none.
  values["_LightPositionRange"] = values["_LightProjectionParams"] = {0.0f, 0.0f, 0.0f, 0.0f};
  values["unity_LightShadowBias"] = values["_LightSplitsNear"] = values["_LightSplitsFar"] = {0.0f, 0.0f, 0.0f, 0.0f};
  values["unity_ShadowSplitSqRadii"] = {0.0f, 0.0f, 0.0f, 0.0f};
  values["unity_ShadowSplitSpheres"] = std::vector<float>(16, 0.0f);
  values["unity_WorldToShadow"] = std::vector<float>(64, 0.0f);
  values["unity_LightmapST"] = values["unity_DynamicLightmapST"] = {1.0f, 1.0f, 0.0f, 0.0f};

  // The camera's frustum in world space, as Unity's manual orders it (left, right, bottom, top,
  // near, far): each plane (n, d) with n a unit normal into the frustum, dot(n, p) + d >= 0 inside
  // (the rows of the projection x view, Gribb and Hartmann's way, for depth 0 to 1).
  const glm::mat4 clip = gpu_projection(camera, width / height) * view;
  const auto row = [&](int r) { return glm::vec4(clip[0][r], clip[1][r], clip[2][r], clip[3][r]); };
  std::vector<float>& planes = values["unity_CameraWorldClipPlanes"];
  for (const glm::vec4 plane :
       {row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1), row(2), row(3) - row(2)}) {
    const glm::vec4 unit = plane / glm::length(glm::vec3(plane));
    planes.insert(planes.end(), {unit.x, unit.y, unit.z, unit.w});
  }
  return values;
}

void add_blit_inputs(UniformValueMap& values, shaderlab::UnityPlatform platform) {
  const std::vector<float> identity = hlsl_components(glm::mat4(1.0f));
  for (const char* name : {"_WorldToClip", "unity_MatrixV", "unity_MatrixInvV"}) values[name] = identity;
  const std::vector<float> projection = hlsl_components(render_target_convention(platform));
  for (const char* name : {"glstate_matrix_projection", "unity_MatrixVP"}) values[name] = projection;
}

void add_object_inputs(const glm::mat4& model, UniformValueMap& values) {
  values["_ObjectToWorld"] = hlsl_components(model);
  values["_NormalToWorld"] = hlsl_components(glm::transpose(glm::inverse(model)));
  values["unity_ObjectToWorld"] = hlsl_components(model);
  values["unity_WorldToObject"] = hlsl_components(glm::inverse(model));
  // w = -1 where the transform mirrors (odd negative scale), which turns the bitangent around.
  values["unity_WorldTransformParams"] = {0.0f, 0.0f, 0.0f, glm::determinant(glm::mat3(model)) < 0.0f ? -1.0f : 1.0f};
}

bool renderer_uniform(const std::string& name) {
  static const std::set<std::string> names = [] {
    // Any sane scene: only the names are kept.
    Scene scene;
    scene.width = scene.height = 1;
    scene.camera = {glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 60.0f, 0.1f, 10.0f};
    UniformValueMap values = frame_inputs(scene, ShCoefficients{});
    add_object_inputs(glm::mat4(1.0f), values);
    std::set<std::string> keys;
    for (const auto& [key, value] : values) keys.insert(key);
    return keys;
  }();
  return names.count(name) || name.ends_with("_TexelSize") || name.ends_with("_HDR");
}

bool renderer_texture(const std::string& name) {
  return name == "_EnvironmentSpecular" || name == "unity_SpecCube0" || name == "unity_SpecCube1" ||
         name == "_LightTexture0" || name == "_LightTextureB0";
}

std::optional<TextureOrigin> renderer_default_texture(const std::string& name) {
  // The light probe proxy volume's coefficients, read only where unity_ProbeVolumeParams.x is 1.
  if (name == "unity_ProbeVolumeSH") return TextureOrigin::Clear;
  return std::nullopt;
}

}  // namespace xshade::harness
