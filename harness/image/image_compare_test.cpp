#include "harness/image/image_compare.h"

#include <cmath>
#include <ctime>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

// A colour whose channels are exactly the linear values of 8-bit sRGB codes, so that a test can
// say "this pixel differs by N steps" and mean it.
glm::vec4 code_colour(int r, int g, int b, int a = 255) {
  return {srgb8_to_linear(uint8_t(r)), srgb8_to_linear(uint8_t(g)), srgb8_to_linear(uint8_t(b)), float(a) / 255.0f};
}

FloatImage filled(uint32_t width, uint32_t height, glm::vec4 colour) {
  FloatImage image(width, height);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) image.set(x, y, colour);
  return image;
}

CompareSettings settings(uint32_t tolerance, double fraction = 0.0, uint32_t radius = 0) {
  CompareSettings result;
  result.channel_tolerance = tolerance;
  result.max_failing_fraction = fraction;
  result.position_radius = radius;
  return result;
}

const LayerResult& layer(const Comparison& comparison, const std::string& name) {
  for (const LayerResult& each : comparison.layers)
    if (each.layer == name) return each;
  ADD_FAILURE() << "no layer " << name;
  static const LayerResult none;
  return none;
}

std::vector<std::string> layer_names(const Comparison& comparison) {
  std::vector<std::string> names;
  for (const LayerResult& each : comparison.layers) names.push_back(each.layer);
  return names;
}

bool is_black(glm::vec4 colour) { return colour.r == 0.0f && colour.g == 0.0f && colour.b == 0.0f; }

TEST(CompareImages, IdenticalImagesPassOnTheExactLayer) {
  FloatImage image = filled(4, 3, {0.2f, 0.4f, 0.6f, 1.0f});
  image.set(1, 2, {3.0f, 0.0f, 1e-6f, 0.5f});
  const Comparison comparison = compare_images(image, image, settings(0));
  EXPECT_EQ(comparison.verdict, Verdict::Pass);
  EXPECT_EQ(comparison.decided_by, "exact");
  EXPECT_EQ(layer_names(comparison),
            (std::vector<std::string>{"finite", "exact", "per_pixel", "position", "float", "summary"}));
  EXPECT_EQ(layer(comparison, "finite").verdict, Verdict::Pass);
  EXPECT_EQ(layer(comparison, "exact").verdict, Verdict::Pass);
  EXPECT_EQ(layer(comparison, "exact").detail, "bit-identical");
  EXPECT_EQ(layer(comparison, "per_pixel").verdict, Verdict::Skipped);
  EXPECT_EQ(layer(comparison, "position").verdict, Verdict::Skipped);
  EXPECT_EQ(comparison.metrics.max_difference, 0.0);
  EXPECT_EQ(comparison.metrics.mean, 0.0);
  EXPECT_EQ(comparison.metrics.rmse, 0.0);
  EXPECT_EQ(comparison.metrics.psnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(comparison.metrics.failing_pixels, 0u);
  ASSERT_EQ(comparison.heat_map.width, 4u);
  ASSERT_EQ(comparison.heat_map.height, 3u);
  for (uint32_t y = 0; y < 3; ++y)
    for (uint32_t x = 0; x < 4; ++x) EXPECT_EQ(comparison.heat_map.at(x, y), glm::vec4(0, 0, 0, 1)) << x << "," << y;
}

TEST(CompareImages, AScenesMetricDecidesInPlaceOfThePerPixelLayers) {
  // A 16x16 image whose one pixel moved by 3 steps: the per-pixel layer fails it, and a CIEDE2000
  // that ignores differences below 2 passes it.
  FloatImage reference = filled(16, 16, {0.2f, 0.4f, 0.6f, 1.0f});
  FloatImage test = reference;
  test.set(3, 4, {0.21f, 0.4f, 0.6f, 1.0f});
  CompareSettings with_metric = settings(1);
  with_metric.metric = MetricSettings{Metric::DeltaE, 0.0, 2.0, 0.0, 0.0};
  const Comparison comparison = compare_images(test, reference, with_metric);
  EXPECT_EQ(layer(comparison, "per_pixel").verdict, Verdict::Fail);  // still run, for the report
  EXPECT_EQ(comparison.decided_by, "deltae");
  EXPECT_EQ(comparison.verdict, Verdict::Pass);
  EXPECT_EQ(layer_names(comparison),
            (std::vector<std::string>{"finite", "exact", "per_pixel", "position", "float", "deltae", "summary"}));
  ASSERT_TRUE(comparison.metrics.metric);
  EXPECT_EQ(comparison.metrics.metric->name, "deltae");
  EXPECT_EQ(comparison.metrics.metric->value, 0.0);  // nothing above 2
  // A per-pixel threshold below the difference fails it.
  with_metric.metric->pixel_threshold = 0.1;
  const Comparison strict = compare_images(test, reference, with_metric);
  EXPECT_EQ(strict.verdict, Verdict::Fail);
  EXPECT_EQ(strict.decided_by, "deltae");
  EXPECT_GT(strict.metrics.metric->value, 0.0);
  // Identical images need no measuring; a NaN still fails on the finite layer first.
  EXPECT_EQ(compare_images(reference, reference, with_metric).decided_by, "exact");
  test.set(0, 0, {NAN, 0.0f, 0.0f, 1.0f});
  EXPECT_EQ(compare_images(test, reference, with_metric).decided_by, "finite");
}

TEST(CompareImages, OnePixelTwoStepsOffFailsWithoutBudgetAndPassesWithOnePixelOfBudget) {
  const FloatImage reference = filled(4, 4, code_colour(100, 100, 100));
  FloatImage test = reference;
  test.set(2, 1, code_colour(100, 102, 100));

  const Comparison strict = compare_images(test, reference, settings(1));
  EXPECT_EQ(strict.verdict, Verdict::Fail);
  EXPECT_EQ(strict.decided_by, "per_pixel");
  EXPECT_EQ(layer(strict, "exact").verdict, Verdict::Skipped);
  EXPECT_EQ(layer(strict, "per_pixel").verdict, Verdict::Fail);
  EXPECT_EQ(layer(strict, "per_pixel").detail,
            "1 of 16 pixels differ by more than 1 sRGB step (budget 0% = 0 pixels); worst 2 steps at (2, 1)");
  EXPECT_EQ(layer(strict, "position").verdict, Verdict::Skipped);
  EXPECT_EQ(layer(strict, "position").detail, "position_radius is 0");
  EXPECT_EQ(strict.metrics.failing_pixels, 1u);
  EXPECT_EQ(strict.metrics.failing_fraction, 1.0 / 16.0);

  // One pixel in sixteen is 6.25%.
  const Comparison budgeted = compare_images(test, reference, settings(1, 1.0 / 16.0));
  EXPECT_EQ(budgeted.verdict, Verdict::Pass);
  EXPECT_EQ(budgeted.decided_by, "per_pixel");
  EXPECT_EQ(layer(budgeted, "per_pixel").detail,
            "1 of 16 pixels differ by more than 1 sRGB step (budget 6.25% = 1 pixel); worst 2 steps at (2, 1)");

  // Two steps is within a tolerance of two.
  EXPECT_EQ(compare_images(test, reference, settings(2)).verdict, Verdict::Pass);
}

TEST(CompareImages, BudgetIsTheWholePixelsTheFractionAllows) {
  // 0.29% of 10000 pixels is 29, but 0.0029 * 10000 is 28.999999999999996 in doubles.
  const FloatImage reference = filled(100, 100, code_colour(50, 50, 50));
  FloatImage test = reference;
  for (uint32_t x = 0; x < 29; ++x) test.set(x, 7, code_colour(90, 50, 50));
  EXPECT_EQ(compare_images(test, reference, settings(1, 0.0029)).verdict, Verdict::Pass);
  test.set(29, 7, code_colour(90, 50, 50));
  const Comparison over = compare_images(test, reference, settings(1, 0.0029));
  EXPECT_EQ(over.verdict, Verdict::Fail);
  EXPECT_EQ(layer(over, "per_pixel").detail,
            "30 of 10000 pixels differ by more than 1 sRGB step (budget 0.29% = 29 pixels); worst 40 steps at (0, 7)");
}

TEST(CompareImages, AlphaIsComparedAsWell) {
  const FloatImage reference = filled(2, 2, code_colour(10, 20, 30, 255));
  FloatImage test = reference;
  test.set(1, 1, code_colour(10, 20, 30, 250));
  const Comparison comparison = compare_images(test, reference, settings(4));
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(layer(comparison, "per_pixel").detail,
            "1 of 4 pixels differ by more than 4 sRGB steps (budget 0% = 0 pixels); worst 5 steps at (1, 1)");
}

TEST(CompareImages, NanInTheTestFailsTheFiniteLayerWithTheFirstPixel) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const FloatImage reference = filled(4, 4, {0.5f, 0.5f, 0.5f, 1.0f});
  FloatImage test = reference;
  test.set(3, 1, {0.5f, nan, 0.5f, 1.0f});
  test.set(1, 2, {0.5f, 0.5f, -0.25f, 1.0f});
  test.set(0, 3, {-inf, 0.5f, 0.5f, 1.0f});
  test.set(2, 3, {0.5f, 0.5f, 0.5f, -0.0f});  // negative zero is zero, not a negative value

  const Comparison comparison = compare_images(test, reference, settings(255, 1.0));
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(comparison.decided_by, "finite");
  EXPECT_EQ(layer(comparison, "finite").verdict, Verdict::Fail);
  EXPECT_EQ(layer(comparison, "finite").detail, "test has 1 NaN, 1 Inf, 1 negative channel values, first at (3, 1)");
  EXPECT_EQ(comparison.test_non_finite.nan, 1u);
  EXPECT_EQ(comparison.test_non_finite.inf, 1u);
  EXPECT_EQ(comparison.test_non_finite.negative, 1u);
  ASSERT_TRUE(comparison.test_non_finite.first);
  EXPECT_EQ(*comparison.test_non_finite.first, std::make_pair(3u, 1u));
  EXPECT_EQ(comparison.reference_non_finite.total(), 0u);
  // The later layers still ran for the report: a tolerance of 255 passes every pixel.
  EXPECT_EQ(layer(comparison, "per_pixel").verdict, Verdict::Pass);
  // A NaN against a number is an infinite difference; mean and RMSE leave such pairs out.
  EXPECT_EQ(comparison.metrics.max_difference, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isfinite(comparison.metrics.mean));
  EXPECT_TRUE(std::isfinite(comparison.metrics.rmse));
}

TEST(CompareImages, NonFiniteValuesInTheReferenceFailToo) {
  FloatImage reference = filled(3, 2, {0.5f, 0.5f, 0.5f, 1.0f});
  reference.set(2, 1, {0.5f, 0.5f, 0.5f, std::numeric_limits<float>::infinity()});
  const FloatImage test = filled(3, 2, {0.5f, 0.5f, 0.5f, 1.0f});
  const Comparison comparison = compare_images(test, reference, settings(255, 1.0));
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(comparison.decided_by, "finite");
  EXPECT_EQ(layer(comparison, "finite").detail,
            "reference has 0 NaN, 1 Inf, 0 negative channel values, first at (2, 1)");
  EXPECT_EQ(comparison.test_non_finite.total(), 0u);
}

TEST(CompareImages, BitIdenticalNansStillFailTheFiniteLayer) {
  const FloatImage image = filled(2, 2, {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 1.0f});
  const Comparison comparison = compare_images(image, image, settings(1));
  EXPECT_EQ(layer(comparison, "exact").verdict, Verdict::Pass);
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(comparison.decided_by, "finite");
}

// A vertical edge, dark left of column `edge` and light from it on.
FloatImage vertical_edge(uint32_t edge) {
  FloatImage image = filled(8, 8, code_colour(20, 20, 20));
  for (uint32_t y = 0; y < 8; ++y)
    for (uint32_t x = edge; x < 8; ++x) image.set(x, y, code_colour(230, 230, 230));
  return image;
}

TEST(CompareImages, AnEdgeMovedByOnePixelIsForgivenWithinAPositionRadiusOfOne) {
  const FloatImage reference = vertical_edge(4);
  const FloatImage test = vertical_edge(5);  // column 4 is dark in the test, light in the reference

  const Comparison without = compare_images(test, reference, settings(1));
  EXPECT_EQ(without.verdict, Verdict::Fail);
  EXPECT_EQ(without.decided_by, "per_pixel");
  EXPECT_EQ(without.metrics.failing_pixels, 8u);

  const Comparison with = compare_images(test, reference, settings(1, 0.0, 1));
  EXPECT_EQ(with.verdict, Verdict::Pass);
  EXPECT_EQ(with.decided_by, "position");
  EXPECT_EQ(layer(with, "per_pixel").verdict, Verdict::Fail);
  EXPECT_EQ(layer(with, "position").verdict, Verdict::Pass);
  EXPECT_EQ(layer(with, "position").detail,
            "8 of 8 failing pixels match a reference pixel within 1 pixel and 1 sRGB step; 0 remain "
            "(budget 0% = 0 pixels)");
  // The metrics still count the pixels beyond the tolerance.
  EXPECT_EQ(with.metrics.failing_pixels, 8u);

  // Moved by two pixels, one radius forgives nothing: the dark test pixel at column 5 has light
  // reference pixels at 4, 5 and 6.
  const Comparison two = compare_images(vertical_edge(6), reference, settings(1, 0.0, 1));
  EXPECT_EQ(two.verdict, Verdict::Fail);
  EXPECT_EQ(two.decided_by, "position");
  EXPECT_EQ(layer(two, "position").detail,
            "8 of 16 failing pixels match a reference pixel within 1 pixel and 1 sRGB step; 8 remain "
            "(budget 0% = 0 pixels)");
  EXPECT_EQ(compare_images(vertical_edge(6), reference, settings(1, 0.0, 2)).verdict, Verdict::Pass);
}

TEST(CompareImages, APositionRadiusDoesNotForgiveAColourTheReferenceDoesNotHave) {
  const FloatImage reference = vertical_edge(4);
  FloatImage test = reference;
  test.set(4, 4, code_colour(230, 0, 0));
  const Comparison comparison = compare_images(test, reference, settings(1, 0.0, 3));
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(comparison.decided_by, "position");
  EXPECT_EQ(layer(comparison, "position").detail,
            "0 of 1 failing pixels match a reference pixel within 3 pixels and 1 sRGB step; 1 remain "
            "(budget 0% = 0 pixels)");
}

TEST(CompareImages, MetricsOfAHandMadePair) {
  // Reference black; the test has R = 1 at (0, 0) and G = 0.5 at (1, 0). In 8-bit sRGB those
  // are 255 and 188 steps (0.5 encodes as 0.7354 * 255 = 187.5, rounded up).
  const FloatImage reference = filled(2, 1, {0.0f, 0.0f, 0.0f, 1.0f});
  FloatImage test = reference;
  test.set(0, 0, {1.0f, 0.0f, 0.0f, 1.0f});
  test.set(1, 0, {0.0f, 0.5f, 0.0f, 1.0f});

  const Comparison comparison = compare_images(test, reference, settings(1, 1.0));
  const ImageMetrics& metrics = comparison.metrics;
  // Eight channel values in all: two differ, by 1 and by 0.5.
  EXPECT_EQ(metrics.max_difference, 1.0);
  EXPECT_EQ(metrics.max_x, 0u);
  EXPECT_EQ(metrics.max_y, 0u);
  EXPECT_EQ(metrics.mean, 1.5 / 8.0);
  EXPECT_DOUBLE_EQ(metrics.rmse, std::sqrt((1.0 + 0.25) / 8.0));
  // Mean squared step difference (255^2 + 188^2) / 8 = 12546.125 over a peak of 255.
  EXPECT_DOUBLE_EQ(metrics.psnr, 10.0 * std::log10(65025.0 / 12546.125));
  EXPECT_NEAR(metrics.psnr, 7.1457, 0.0001);  // the same, worked by hand to four places
  EXPECT_EQ(metrics.failing_pixels, 2u);
  EXPECT_EQ(metrics.failing_fraction, 1.0);
  EXPECT_EQ(layer(comparison, "summary").verdict, Verdict::Pass);
  // The summary is in the per-pixel layer's domain, the steps: the worst pixel, its steps, the
  // mean and RMSE of every channel's steps, the first failing pixel.
  EXPECT_EQ(metrics.max_steps, 255u);
  EXPECT_EQ(metrics.worst_x, 0u);
  EXPECT_EQ(metrics.worst_y, 0u);
  EXPECT_DOUBLE_EQ(metrics.mean_steps, (255.0 + 188.0) / 8.0);
  EXPECT_DOUBLE_EQ(metrics.rmse_steps, std::sqrt(12546.125));
  ASSERT_TRUE(metrics.first_failing);
  EXPECT_EQ(*metrics.first_failing, (std::pair<uint32_t, uint32_t>{0, 0}));
  EXPECT_EQ(layer(comparison, "summary").detail,
            "in 8-bit sRGB steps, the per-pixel layer's values: worst 255 steps at (0, 0); mean 55.38; RMSE 112; "
            "PSNR 7.15 dB; 2 pixels (100%) differ by more than 1 sRGB step, the first at (0, 0)");
}

TEST(CompareImages, TheSummaryPointsAtTheWorstPixelInStepsNotInLinearValues) {
  // Near black a small linear change is many sRGB steps; near white a larger one is few. The
  // linear maximum is at (1, 0), the per-pixel layer's worst at (0, 0).
  const FloatImage reference = filled(2, 1, {0.0f, 0.0f, 0.0f, 1.0f});
  FloatImage test = reference;
  FloatImage bright = reference;
  bright.set(1, 0, {0.9f, 0.9f, 0.9f, 1.0f});
  test.set(0, 0, {0.01f, 0.0f, 0.0f, 1.0f});  // code 25
  test.set(1, 0, {0.95f, 0.9f, 0.9f, 1.0f});  // 249 against 243
  const ImageMetrics metrics = compare_images(test, bright, settings(1)).metrics;
  EXPECT_EQ(metrics.max_x, 1u);  // linear: 0.05 beats 0.01
  EXPECT_EQ(metrics.max_steps, 25u);
  EXPECT_EQ(metrics.worst_x, 0u);
  EXPECT_EQ(metrics.worst_y, 0u);
}

// The worst pixel's own values, and every pixel beyond the tolerance in row-major order: what
// a viewer shows under the cursor and as the failing-pixel mask.
TEST(CompareImages, TheWorstPixelsValuesAndTheFailingPixelsAreKept) {
  const FloatImage reference = filled(3, 2, code_colour(100, 100, 100));
  FloatImage test = reference;
  test.set(2, 0, code_colour(103, 100, 100));       // 3 steps
  test.set(0, 1, code_colour(100, 109, 100, 250));  // 9 steps, the worst
  test.set(1, 1, code_colour(101, 100, 100));       // 1 step: within the tolerance
  const Comparison comparison = compare_images(test, reference, settings(1));
  EXPECT_EQ(comparison.failing_pixels, (std::vector<uint32_t>{2, 3}));
  EXPECT_EQ(comparison.metrics.worst_x, 0u);
  EXPECT_EQ(comparison.metrics.worst_y, 1u);
  const glm::vec4 worst = code_colour(100, 109, 100, 250), was = code_colour(100, 100, 100);
  EXPECT_EQ(comparison.metrics.worst_test, (std::array<float, 4>{worst.r, worst.g, worst.b, worst.a}));
  EXPECT_EQ(comparison.metrics.worst_reference, (std::array<float, 4>{was.r, was.g, was.b, was.a}));
  EXPECT_TRUE(compare_images(reference, reference, settings(0)).failing_pixels.empty());
}

TEST(CompareImages, AValueAboveOneThatChangedFailsTheFloatLayer) {
  // A highlight at 1.85 in the golden (a float golden keeps it) raised to 6.07: both are 255 in
  // 8-bit sRGB, so only the float layer sees it.
  FloatImage reference = filled(4, 4, {0.2f, 0.3f, 0.4f, 1.0f});
  reference.set(2, 1, {1.85f, 0.9f, 0.5f, 1.0f});
  FloatImage test = reference;
  test.set(2, 1, {6.07f, 0.9f, 0.5f, 1.0f});
  const Comparison changed = compare_images(test, reference, settings(1));
  EXPECT_EQ(layer(changed, "per_pixel").verdict, Verdict::Pass);
  EXPECT_EQ(changed.verdict, Verdict::Fail);
  EXPECT_EQ(changed.decided_by, "float");
  EXPECT_EQ(changed.metrics.float_failing_pixels, 1u);
  EXPECT_EQ(changed.metrics.float_x, 2u);
  EXPECT_EQ(changed.metrics.float_y, 1u);
  EXPECT_NEAR(changed.metrics.float_max_relative, (6.07 - 1.85) / 6.07, 1e-6);

  // Within the float tolerance (a rounding-sized change) it passes.
  test.set(2, 1, {1.85f * (1.0f + 2e-7f), 0.9f, 0.5f, 1.0f});
  const Comparison rounded = compare_images(test, reference, settings(1));
  EXPECT_EQ(rounded.verdict, Verdict::Pass);
  EXPECT_EQ(layer(rounded, "float").verdict, Verdict::Pass);
}

TEST(CompareImages, HeatMapIsBlackWhereEqualAndPlainWhereBeyondTheTolerance) {
  const FloatImage reference = filled(4, 1, code_colour(100, 100, 100));
  FloatImage test = reference;
  test.set(1, 0, code_colour(101, 100, 100));  // within the tolerance of 1
  test.set(2, 0, code_colour(100, 102, 100));  // one step beyond it
  test.set(3, 0, code_colour(100, 100, 255));  // 155 steps
  const FloatImage& heat = compare_images(test, reference, settings(1)).heat_map;
  ASSERT_EQ(heat.width, 4u);
  ASSERT_EQ(heat.height, 1u);

  auto brightest = [](glm::vec4 c) { return std::max(c.r, std::max(c.g, c.b)); };
  EXPECT_EQ(heat.at(0, 0), glm::vec4(0, 0, 0, 1));
  EXPECT_FALSE(is_black(heat.at(1, 0)));
  EXPECT_FALSE(is_black(heat.at(2, 0)));
  EXPECT_EQ(heat.at(2, 0).a, 1.0f);
  // One step beyond the tolerance must stand out on a screen: a brightest channel of at least
  // 0.2 linear is code 124 or more once written as sRGB. Within the tolerance stays darker.
  EXPECT_GE(brightest(heat.at(2, 0)), 0.2f);
  EXPECT_LT(brightest(heat.at(1, 0)), brightest(heat.at(2, 0)));
  EXPECT_GT(brightest(heat.at(3, 0)), brightest(heat.at(2, 0)));
}

TEST(CompareImages, DifferentSizesFailOnTheSizeLayer) {
  const Comparison comparison = compare_images(FloatImage(4, 3), FloatImage(3, 4), settings(1));
  EXPECT_EQ(comparison.verdict, Verdict::Fail);
  EXPECT_EQ(comparison.decided_by, "size");
  ASSERT_EQ(comparison.layers.size(), 1u);
  EXPECT_EQ(comparison.layers[0].layer, "size");
  EXPECT_EQ(comparison.layers[0].verdict, Verdict::Fail);
  EXPECT_EQ(comparison.layers[0].detail, "test is 4x3 but the reference is 3x4");
  EXPECT_EQ(comparison.heat_map.width, 0u);
}

// Smooth gradients of arbitrary floats, as a renderer makes them: almost none of them is the
// linear value of an 8-bit code. Red reaches `peak` at the right edge.
FloatImage gradient_render(float peak) {
  FloatImage render(64, 48);
  for (uint32_t y = 0; y < 48; ++y)
    for (uint32_t x = 0; x < 64; ++x)
      render.set(x, y,
                 {peak * float(x) / 63.0f, 0.5f + 0.5f * std::sin(float(x * y) * 0.01f), float(y) / 47.0f * 0.013f,
                  0.25f + 0.75f * float(x) / 63.0f});
  return render;
}

TEST(CompareImages, AnExactRenderAgainstItsPngGoldenPassesWithToleranceZero) {
  const FloatImage render = gradient_render(0.98f);
  const auto path = std::filesystem::temp_directory_path() / "xshade_image_compare_test_golden.png";
  ASSERT_TRUE(write_png(render, path));
  const auto golden = read_image(path);
  ASSERT_TRUE(golden) << golden.error().to_string();

  const Comparison comparison = compare_images(render, *golden, settings(0));
  EXPECT_EQ(layer(comparison, "exact").verdict, Verdict::Skipped);  // the floats do differ
  EXPECT_EQ(comparison.verdict, Verdict::Pass);
  EXPECT_EQ(comparison.decided_by, "per_pixel");
  EXPECT_EQ(comparison.metrics.failing_pixels, 0u);
  EXPECT_EQ(comparison.metrics.psnr, std::numeric_limits<double>::infinity());
}

TEST(CompareImages, ValuesAboveOneNeedAFloatGolden) {
  // A PNG clamps red at 1 where the render has up to 1.5: the float layer fails it. The EXR a
  // bless writes beside it keeps every value, and the same render is bit-identical to it.
  const FloatImage render = gradient_render(1.5f);
  const auto png = std::filesystem::temp_directory_path() / "xshade_image_compare_test_hdr.png";
  const auto exr = std::filesystem::temp_directory_path() / "xshade_image_compare_test_hdr.exr";
  ASSERT_TRUE(write_png(render, png));
  ASSERT_TRUE(write_exr(render, exr));
  const auto clamped = read_image(png);
  const auto kept = read_image(exr);
  ASSERT_TRUE(clamped && kept);
  const Comparison against_png = compare_images(render, *clamped, settings(0));
  EXPECT_EQ(layer(against_png, "per_pixel").verdict, Verdict::Pass);
  EXPECT_EQ(against_png.decided_by, "float");
  EXPECT_EQ(against_png.verdict, Verdict::Fail);
  const Comparison against_exr = compare_images(render, *kept, settings(0));
  EXPECT_EQ(against_exr.decided_by, "exact");
  EXPECT_EQ(against_exr.verdict, Verdict::Pass);
}

TEST(NonFinite, CountsEveryChannelAndMasksThePixels) {
  FloatImage image = filled(3, 2, {0.1f, 0.2f, 0.3f, 1.0f});
  image.set(2, 0, {std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.3f, 1.0f});
  image.set(0, 1, {0.1f, 0.2f, 0.3f, std::numeric_limits<float>::infinity()});
  const NonFiniteCount count = count_non_finite(image);
  EXPECT_EQ(count.nan, 1u);
  EXPECT_EQ(count.inf, 1u);
  EXPECT_EQ(count.negative, 1u);
  ASSERT_TRUE(count.first);
  EXPECT_EQ(*count.first, std::make_pair(2u, 0u));

  const FloatImage mask = non_finite_mask(image);
  const glm::vec4 white(1, 1, 1, 1), black(0, 0, 0, 1);
  EXPECT_EQ(mask.at(0, 0), black);
  EXPECT_EQ(mask.at(1, 0), black);
  EXPECT_EQ(mask.at(2, 0), white);
  EXPECT_EQ(mask.at(0, 1), white);
  EXPECT_EQ(mask.at(1, 1), black);
  EXPECT_FALSE(count_non_finite(filled(2, 2, {0.0f, 1.0f, 5.0f, 1.0f})).first);
}

}  // namespace
}  // namespace xshade::harness
