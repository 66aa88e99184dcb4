#include "harness/assets/environment.h"

#include <fstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "harness/assets/equirect.h"
#include "harness/assets/specular_prefilter.h"
#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

std::filesystem::path scratch_directory() {
  auto directory =
      std::filesystem::temp_directory_path() /
      ("xshade_environment_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  std::filesystem::create_directories(directory);
  return directory;
}

TEST(BuildEnvironment, ConstantEnvironmentLightsEveryNormalWithItsRadiance) {
  EnvironmentSpec desc;
  desc.kind = EnvironmentKind::Constant;
  desc.color = {0.2f, 0.4f, 0.8f};
  desc.intensity = 2.0f;
  Result<Environment> environment = build_environment(desc);
  ASSERT_TRUE(environment) << environment.error().to_string();
  const glm::vec3 expected = desc.color * desc.intensity;
  for (glm::vec3 n :
       {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -2, 3))}) {
    glm::vec3 irradiance = sh_evaluate(environment->sh, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(irradiance[c], expected[c], 2e-6f);  // float rounding
  }
  ASSERT_EQ(environment->prefiltered.levels.size(), kPrefilteredLevels);
  FloatImage roughest = prefiltered_level(environment->prefiltered, kPrefilteredLevels - 1);
  for (uint32_t y = 0; y < roughest.height; ++y)
    for (uint32_t x = 0; x < roughest.width; ++x)
      EXPECT_NEAR(roughest.at(x, y).z, expected.z, 2e-6f);  // float rounding
}

TEST(GradientRadiance, BlendsSkyHorizonAndGroundByHeight) {
  EnvironmentSpec desc;
  desc.kind = EnvironmentKind::Gradient;
  desc.sky = {0.2f, 0.4f, 1.0f};
  desc.horizon = {1.0f, 1.0f, 1.0f};
  desc.ground = {0.1f, 0.1f, 0.1f};
  auto at = [&](float y) { return gradient_radiance(desc, glm::normalize(glm::vec3(std::sqrt(1 - y * y), y, 0))); };
  EXPECT_EQ(at(1.0f), desc.sky);
  EXPECT_EQ(at(0.0f), desc.horizon);
  EXPECT_EQ(at(-1.0f), desc.ground);
  EXPECT_EQ(at(-0.5f), desc.ground);  // the ground is reached 0.15 below the horizon
  // Halfway up: 1 - (1 - 0.5)^3 = 7/8 of the way from horizon to sky.
  EXPECT_NEAR(at(0.5f).x, 1.0f + (0.2f - 1.0f) * 0.875f, 1e-6f);  // float rounding
  // Continuous across the horizon: within 1e-4 of it the colour moves by less than 1e-3.
  EXPECT_LT(glm::length(at(1e-4f) - at(-1e-4f)), 1e-3f);
}

TEST(BuildEnvironment, GradientSkyIsBrighterFromAboveAndKeepsItsColoursInTheImage) {
  EnvironmentSpec desc;
  desc.kind = EnvironmentKind::Gradient;
  desc.sky = {0.5f, 0.7f, 1.0f};
  desc.horizon = {1.0f, 1.0f, 1.0f};
  desc.ground = {0.1f, 0.1f, 0.1f};
  desc.intensity = 3.0f;
  Result<Environment> environment = build_environment(desc);
  ASSERT_TRUE(environment) << environment.error().to_string();
  // The top row is within 0.7 degrees of the zenith, the bottom row of the nadir.
  EXPECT_NEAR(environment->radiance.at(7, 0).z, 3.0f, 1e-4f);
  EXPECT_NEAR(environment->radiance.at(7, kPrefilteredHeight - 1).z, 0.3f, 1e-6f);
  EXPECT_GT(sh_evaluate(environment->sh, {0, 1, 0}).z, sh_evaluate(environment->sh, {0, -1, 0}).z);
  // Rotationally symmetric about y: every horizontal normal sees the same light.
  EXPECT_NEAR(sh_evaluate(environment->sh, {1, 0, 0}).z, sh_evaluate(environment->sh, {0, 0, 1}).z, 1e-4f);
}

TEST(BuildEnvironment, ReadsAnEquirectFileScaledByItsIntensityAndOrientedByTheConvention) {
  // The -x half of the sphere (u < 0.5) is bright, the +x half black.
  FloatImage file(64, 32);
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 64; ++x) file.set(x, y, glm::vec4(x < 32 ? 4.0f : 0.0f, 1.0f, 1.0f, 0.5f));
  const auto path = scratch_directory() / "half.exr";
  ASSERT_TRUE(write_exr(file, path));

  EnvironmentSpec desc;
  desc.kind = EnvironmentKind::Equirect;
  desc.file = path;
  desc.intensity = 0.5f;
  Result<Environment> environment = build_environment(desc);
  ASSERT_TRUE(environment) << environment.error().to_string();
  ASSERT_EQ(environment->radiance.width, kPrefilteredWidth);
  ASSERT_EQ(environment->radiance.height, kPrefilteredHeight);
  EXPECT_FLOAT_EQ(environment->radiance.at(64, 64).x, 2.0f);   // u = 0.25: -x
  EXPECT_FLOAT_EQ(environment->radiance.at(192, 64).x, 0.0f);  // u = 0.75: +x
  EXPECT_FLOAT_EQ(environment->radiance.at(192, 64).y, 0.5f);
  EXPECT_FLOAT_EQ(environment->radiance.at(192, 64).w, 1.0f);  // the file's alpha is not light
  // Radiance 2 on the -x hemisphere is 1 - sign(x). Its bands 0..2 are 1 - 1.5 x (sign(x) is
  // odd, so band 2 is empty), which the cosine lobe turns into 1 - x: 2 at -x and 0 at +x.
  // 0.1 allows for the texels that resampling blends at the two boundaries (u = 0 and 0.5).
  EXPECT_GT(sh_evaluate(environment->sh, {-1, 0, 0}).x, 1.9f);
  EXPECT_LT(sh_evaluate(environment->sh, {1, 0, 0}).x, 0.1f);
}

TEST(BuildEnvironment, MissingOrCorruptFilesAreErrorsNamingTheFile) {
  EnvironmentSpec desc;
  desc.kind = EnvironmentKind::Equirect;
  desc.file = scratch_directory() / "absent.hdr";
  Result<Environment> missing = build_environment(desc);
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find(desc.file.string()), std::string::npos) << missing.error().message;

  desc.file = scratch_directory() / "corrupt.hdr";
  std::ofstream(desc.file) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 8\nnot pixels";
  Result<Environment> corrupt = build_environment(desc);
  ASSERT_FALSE(corrupt);
  EXPECT_NE(corrupt.error().message.find(desc.file.string()), std::string::npos) << corrupt.error().message;
}

}  // namespace
}  // namespace xshade::harness
