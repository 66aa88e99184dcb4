#include "harness/render/renderer_inputs.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

glm::vec4 vec4_of(const std::vector<float>& v) { return {v.at(0), v.at(1), v.at(2), v.at(3)}; }

glm::mat4 matrix_of(const std::vector<float>& hlsl) {  // row by row, as hlsl_components wrote it
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m[c][r] = hlsl.at(size_t(r) * 4 + c);
  return m;
}

Scene test_scene() {
  Scene scene;
  scene.width = 320;
  scene.height = 200;
  scene.camera = {{1.0f, 2.0f, 6.0f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}, 40.0f, 0.3f, 50.0f};
  scene.time_seconds = 2.0f;
  return scene;
}

// Unity's ShadeSH9 as UnityCG.cginc writes it (SHEvalLinearL0L1 + SHEvalLinearL2).
glm::vec3 shade_sh9(const std::array<glm::vec4, 7>& k, glm::vec3 n) {
  const glm::vec4 n1(n, 1.0f);
  const glm::vec4 b(n.x * n.y, n.y * n.z, n.z * n.z, n.z * n.x);
  const float c = n.x * n.x - n.y * n.y;
  return glm::vec3(glm::dot(k[0], n1), glm::dot(k[1], n1), glm::dot(k[2], n1)) +
         glm::vec3(glm::dot(k[3], b), glm::dot(k[4], b), glm::dot(k[5], b)) + glm::vec3(k[6]) * c;
}

TEST(RendererInputs, UnityShConstantsEvaluateToTheSameIrradiance) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> any(-1.0f, 1.0f);
  ShCoefficients sh;
  for (glm::vec3& c : sh) c = {any(random), any(random), any(random)};
  const auto constants = unity_sh_constants(sh);
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(any(random), any(random), any(random)) + glm::vec3(1e-3f));
    const glm::vec3 expected = sh_evaluate(sh, n), got = shade_sh9(constants, n);
    for (int channel = 0; channel < 3; ++channel) EXPECT_NEAR(got[channel], expected[channel], 1e-5f) << "normal " << i;
  }
}

// Linear01Depth and LinearEyeDepth (UnityCG.cginc) of the depth a point leaves in the depth
// buffer give back the point's distance along the view axis.
TEST(RendererInputs, ZBufferParamsLineariseTheDepthTheProjectionWrites) {
  const Scene scene = test_scene();
  const UniformValueMap values = frame_inputs(scene, {});
  const glm::vec4 z = vec4_of(values.at("_ZBufferParams"));
  const glm::mat4 projection = gpu_projection(scene.camera, 320.0f / 200.0f);
  for (float eye : {0.3f, 1.0f, 7.5f, 50.0f}) {
    const glm::vec4 clip = projection * glm::vec4(0.2f, -0.1f, -eye, 1.0f);
    const float depth = clip.z / clip.w;
    EXPECT_NEAR(1.0f / (z.z * depth + z.w), eye, eye * 1e-4f) << "LinearEyeDepth at " << eye;
    EXPECT_NEAR(1.0f / (z.x * depth + z.y), eye / 50.0f, 1e-4f) << "Linear01Depth at " << eye;
  }
}

TEST(RendererInputs, CameraSpaceLooksAlongPlusZAndCameraProjectionIsOpenGLs) {
  const Scene scene = test_scene();
  const UniformValueMap values = frame_inputs(scene, {});
  const glm::vec4 target = matrix_of(values.at("unity_WorldToCamera")) * glm::vec4(scene.camera.target, 1.0f);
  EXPECT_GT(target.z, 0.0f);
  EXPECT_NEAR(target.x, 0.0f, 1e-5f);
  const glm::vec4 origin = matrix_of(values.at("unity_CameraToWorld")) * glm::vec4(0, 0, 0, 1);
  EXPECT_NEAR(glm::distance(glm::vec3(origin), scene.camera.position), 0.0f, 1e-5f);
  const glm::mat4 camera_projection = matrix_of(values.at("unity_CameraProjection"));
  const glm::vec4 near = camera_projection * glm::vec4(0, 0, -0.3f, 1),
                  far = camera_projection * glm::vec4(0, 0, -50.0f, 1);
  EXPECT_NEAR(near.z / near.w, -1.0f, 1e-5f);
  EXPECT_NEAR(far.z / far.w, 1.0f, 1e-4f);
  const glm::mat4 round_trip = matrix_of(values.at("unity_CameraInvProjection")) * camera_projection;
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(round_trip[i][i], 1.0f, 1e-5f);
}

TEST(RendererInputs, TimeAndScreenAreUnitysLayout) {
  const UniformValueMap values = frame_inputs(test_scene(), {});
  EXPECT_EQ(vec4_of(values.at("_Time")), glm::vec4(0.1f, 2.0f, 4.0f, 6.0f));
  EXPECT_FLOAT_EQ(values.at("_SinTime")[3], std::sin(2.0f));
  EXPECT_FLOAT_EQ(values.at("_CosTime")[0], std::cos(0.25f));
  EXPECT_EQ(vec4_of(values.at("_ScreenParams")), glm::vec4(320.0f, 200.0f, 1.0f + 1.0f / 320.0f, 1.005f));
  EXPECT_EQ(vec4_of(values.at("_ProjectionParams")), glm::vec4(1.0f, 0.3f, 50.0f, 0.02f));
}

// Unity's D3D11 and Vulkan draw into a render target with depth reversed and y flipped, and say so
// in _ProjectionParams.x; _ZBufferParams still linearises the stored depth.
TEST(RendererInputs, Direct3DConventionsReverseDepthFlipYAndSaySo) {
  Scene scene = test_scene();
  const UniformValueMap glcore = frame_inputs(scene, {});
  scene.unity_platform = shaderlab::UnityPlatform::D3D11;
  const UniformValueMap d3d11 = frame_inputs(scene, {});
  EXPECT_EQ(vec4_of(d3d11.at("_ProjectionParams")), glm::vec4(-1.0f, 0.3f, 50.0f, 0.02f));
  const glm::mat4 projection = matrix_of(d3d11.at("glstate_matrix_projection"));
  const glm::mat4 forward = matrix_of(glcore.at("glstate_matrix_projection"));
  for (float distance : {0.3f, 1.0f, 7.0f, 50.0f}) {
    const glm::vec4 point(0.1f, 0.2f, -distance, 1.0f);
    const glm::vec4 clip = projection * point, unflipped = forward * point;
    EXPECT_NEAR(clip.y / clip.w, -unflipped.y / unflipped.w, 1e-6f) << "y flipped at " << distance;
    const float depth = clip.z / clip.w;
    EXPECT_NEAR(depth, 1.0f - unflipped.z / unflipped.w, 1e-6f) << "reversed at " << distance;
    // UnityCG's Linear01Depth: 1 / (x z + y) = distance / far on either platform.
    for (const UniformValueMap* values : {&glcore, &d3d11}) {
      const glm::vec4 z = vec4_of(values->at("_ZBufferParams"));
      const float stored = values == &glcore ? unflipped.z / unflipped.w : depth;
      EXPECT_NEAR(1.0f / (z.x * stored + z.y), distance / 50.0f, 1e-4f) << distance;
      EXPECT_NEAR(1.0f / (z.z * stored + z.w), distance, 2e-3f * distance) << "LinearEyeDepth at " << distance;
    }
  }
  EXPECT_EQ(matrix_of(d3d11.at("unity_CameraProjection")), matrix_of(glcore.at("unity_CameraProjection")))
      << "Camera.projectionMatrix is OpenGL's on every platform";

  UniformValueMap blit = d3d11;
  add_blit_inputs(blit, scene.unity_platform);
  EXPECT_EQ(matrix_of(blit.at("glstate_matrix_projection")), render_target_convention(scene.unity_platform));
  EXPECT_EQ(render_target_convention(shaderlab::UnityPlatform::GLCore), glm::mat4(1.0f));
}

// unity_FogParams through UnityCG.cginc's UNITY_CALC_FOG_FACTOR_RAW for each mode gives the fog
// factor Unity's manual defines: (end - z) / (end - start), exp(-density z), exp(-(density z)^2).
TEST(RendererInputs, FogParamsGiveUnitysFogFactorsForEachMode) {
  Scene scene = test_scene();
  scene.fog = FogSpec{FogMode::Linear, {0.2f, 0.3f, 0.4f, 1.0f}, 0.05f, 2.0f, 12.0f};
  const UniformValueMap values = frame_inputs(scene, {});
  EXPECT_EQ(vec4_of(values.at("unity_FogColor")), glm::vec4(0.2f, 0.3f, 0.4f, 1.0f));
  const glm::vec4 p = vec4_of(values.at("unity_FogParams"));
  for (float z : {2.0f, 5.0f, 12.0f}) {
    EXPECT_NEAR(z * p.z + p.w, (12.0f - z) / 10.0f, 1e-6f) << "linear at " << z;
    EXPECT_NEAR(std::exp2(-p.y * z), std::exp(-0.05f * z), 1e-6f) << "exponential at " << z;
    EXPECT_NEAR(std::exp2(-(p.x * z) * (p.x * z)), std::exp(-(0.05f * z) * (0.05f * z)), 1e-6f) << "squared at " << z;
  }
  // Without fog, Unity's defaults (grey, density 0.01, 0 to 300), read only with a fog keyword.
  const glm::vec4 defaults = vec4_of(frame_inputs(test_scene(), {}).at("unity_FogParams"));
  EXPECT_NEAR(std::exp2(-defaults.y * 100.0f), std::exp(-1.0f), 1e-6f);
  EXPECT_NEAR(150.0f * defaults.z + defaults.w, 0.5f, 1e-6f);
}

TEST(RendererInputs, ObjectInputsInvertAndFlagAMirroringTransform) {
  UniformValueMap values;
  const glm::mat4 mirrored = model_matrix({1, 2, 3}, {10, 20, 30}, {-1, 2, 1});
  add_object_inputs(mirrored, values);
  const glm::mat4 product = matrix_of(values.at("unity_WorldToObject")) * matrix_of(values.at("unity_ObjectToWorld"));
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(product[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
  EXPECT_EQ(values.at("unity_WorldTransformParams")[3], -1.0f);
  add_object_inputs(model_matrix({0, 0, 0}, {0, 0, 0}, {1, 1, 1}), values);
  EXPECT_EQ(values.at("unity_WorldTransformParams")[3], 1.0f);
}

}  // namespace
}  // namespace xshade::harness
