// The accuracy measurement: its statistics and image helpers on hand-made data, and one study
// measured for real on the gl lane.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "accuracy/accuracy_report.h"
#include "accuracy/measure.h"

namespace xshade::accuracy {
namespace {

TEST(Summarize, GivesTheMedianAndQuartilesOfTheRepetitions) {
  const Timing t = summarize({5.0, 1.0, 4.0, 2.0, 3.0});
  EXPECT_EQ(t.repetitions, 5u);
  EXPECT_DOUBLE_EQ(t.median_ms, 3.0);
  EXPECT_DOUBLE_EQ(t.q1_ms, 2.0);
  EXPECT_DOUBLE_EQ(t.q3_ms, 4.0);
  // Between order statistics: linear interpolation.
  EXPECT_DOUBLE_EQ(summarize({1.0, 2.0}).median_ms, 1.5);
  EXPECT_EQ(summarize({}).repetitions, 0u);
}

TEST(BoxDownsample, AveragesEachBlock) {
  harness::FloatImage image(4, 2);
  for (uint32_t x = 0; x < 4; ++x)
    for (uint32_t y = 0; y < 2; ++y) image.set(x, y, glm::vec4(float(x + 4 * y)));
  const harness::FloatImage small = box_downsample(image, 2);
  ASSERT_EQ(small.width, 2u);
  ASSERT_EQ(small.height, 1u);
  EXPECT_FLOAT_EQ(small.at(0, 0).r, (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(small.at(1, 0).r, (2 + 3 + 6 + 7) / 4.0f);
}

// A result whose 8-bit RMSE (what the charts and the convergence check use) is `rmse` steps.
ConfigurationResult with_rmse(double rmse) {
  ConfigurationResult result;
  result.error.psnr = rmse == 0.0 ? INFINITY : 20.0 * std::log10(255.0 / rmse);
  return result;
}

TEST(Convergence, TheCheckMustDifferLessThanTheSmallestErrorJudged) {
  StudyResult result;
  result.configurations = {with_rmse(0.0), with_rmse(0.02), with_rmse(0.01)};
  EXPECT_FALSE(convergence(result).has_value());  // no check, nothing to say
  result.reference_check = with_rmse(0.004);
  auto c = convergence(result);
  ASSERT_TRUE(c.has_value());
  EXPECT_TRUE(c->converged);
  EXPECT_NEAR(c->smallest_error, 0.01, 1e-12);  // the reference itself (0) judges nothing
  result.reference_check = with_rmse(0.011);
  EXPECT_FALSE(convergence(result)->converged);
}

// The depth-of-field study on gl, end to end: each ring kernel is measurably off the dense
// reference, the reference converges, and the tables and chart name every configuration.
TEST(MeasureStudy, DepthOfFieldKernelsOnGl) {
  const std::filesystem::path source = XSHADE_SOURCE_DIR;
  Study study;
  for (const Study& s : all_studies())
    if (s.id == "dof_kernel") study = s;
  ASSERT_EQ(study.id, "dof_kernel");
  auto backend = harness::create_backend(harness::Lane::Gl);
  ASSERT_TRUE(backend) << backend.error().to_string();
  MeasureOptions options;
  options.scenes_dir = source / "scenes";
  options.shaders_dir = source / "shaders";
  options.rounds = 1;
  auto result = measure_study(study, harness::Lane::Gl, **backend, options);
  ASSERT_TRUE(result) << result.error().to_string();
  ASSERT_EQ(result->configurations.size(), 4u);
  for (const ConfigurationResult& c : result->configurations) {
    EXPECT_GT(chart_error(c), 0.0) << c.label;
    EXPECT_EQ(c.time.repetitions, 3u) << c.label;
    EXPECT_EQ(c.image.width, 320u) << c.label;
  }
  const auto converged = convergence(*result);
  ASSERT_TRUE(converged.has_value());
  EXPECT_TRUE(converged->converged) << converged->check_error << " vs " << converged->smallest_error;

  AccuracyRun run;
  run.studies = {study};
  run.results = {*result};
  run.drivers = {{harness::Lane::Gl, (*backend)->driver_info()}};
  run.command_line = "xshade accuracy dof_kernel --lane gl";
  const std::string md = accuracy_markdown(run, "accuracy");
  EXPECT_THAT(md, testing::HasSubstr("![dof_kernel](accuracy/dof_kernel.svg)"));
  EXPECT_THAT(md, testing::HasSubstr("| 71 samples | gl | "));
  EXPECT_THAT(md, testing::HasSubstr("dense gather, half-texel spacing against the reference"));
  const std::string svg = study_chart_svg(study, run);
  for (const char* label : {"16 samples", "22 samples", "43 samples", "71 samples"})
    EXPECT_THAT(svg, testing::HasSubstr(label));
  const std::string csv = accuracy_csv(run);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);  // header and four rows
}

// The shadow-map study on gl, where Unity's include files are: a larger map places the shadow's
// edge closer to the reference's, so the error falls with each doubling, and filtering the
// comparisons (soft) brings it closer still at every size.
TEST(MeasureStudy, ShadowMapResolutionOnGl) {
  const std::filesystem::path source = XSHADE_SOURCE_DIR;
  const std::filesystem::path unity =
      std::filesystem::path(XSHADE_REALWORLD_CORPUS) / "TwoTailsGames+Unity-Built-in-Shaders";
  if (!std::filesystem::is_directory(unity / "CGIncludes")) GTEST_SKIP() << "no Unity include files at " << unity;
  Study study;
  for (const Study& s : all_studies())
    if (s.id == "shadow_map") study = s;
  ASSERT_EQ(study.id, "shadow_map");
  EXPECT_TRUE(study.unity);  // run only when named, with its folders
  auto backend = harness::create_backend(harness::Lane::Gl);
  ASSERT_TRUE(backend) << backend.error().to_string();
  MeasureOptions options;
  options.scenes_dir = source / "tests" / "realworld" / "scenes";
  options.shaders_dir = source / "shaders";
  options.shader_folders = {source / "examples" / "unity", unity, unity / "CGIncludes"};
  options.rounds = 1;
  options.reference_check = false;
  auto result = measure_study(study, harness::Lane::Gl, **backend, options);
  ASSERT_TRUE(result) << result.error().to_string();
  // Four sizes hard, then the same four soft.
  ASSERT_EQ(result->configurations.size(), 8u);
  const auto& measured = result->configurations;
  for (size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(measured[i].label);
    if (i > 0) {
      EXPECT_LT(chart_error(measured[i]), chart_error(measured[i - 1]));
      EXPECT_LT(chart_error(measured[i + 4]), chart_error(measured[i + 3]));
    }
    // A ramp a texel wide is nearer the reference's edge than a step at the same size.
    EXPECT_LT(chart_error(measured[i + 4]), chart_error(measured[i]));
  }
  EXPECT_GT(chart_error(measured.back()), 0.0);
}

}  // namespace
}  // namespace xshade::accuracy
