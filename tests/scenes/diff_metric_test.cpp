// `xshade diff --metric`: a perceptual metric's verdict against its threshold, with the value
// printed, on two goldens that differ as a change under review does (the depth of field's focus
// moved: dof_on_16 against dof_on_22) and on one golden against itself.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/scenes/gating_test_shared.h"
#include "tests/support/xshade_process.h"

namespace xshade::tests {
namespace diff_metric_test {

std::string diff(const std::string& options) {
  return "diff '" + (kSource / "golden" / "dof_on_16.png").string() + "' '" +
         (kSource / "golden" / "dof_on_22.png").string() + "' " + options;
}

TEST(DiffMetric, FlipDecidesByItsMeanAndPrintsIt) {
  // The pair measures a mean FLIP of 0.0108: above the default 0.0005, below 0.02.
  Outcome strict = run_xshade("", diff("--metric flip"));
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_NE(strict.output.find("LDR-FLIP mean 0.0107"), std::string::npos) << strict.output;
  EXPECT_NE(strict.output.find("(at most 0.0005)"), std::string::npos) << strict.output;
  Outcome loose = run_xshade("", diff("--metric flip --threshold 0.02"));
  EXPECT_EQ(loose.exit_code, 0) << loose.output;
  EXPECT_EQ(loose.output.rfind("PASS", 0), 0u) << loose.output;
}

TEST(DiffMetric, SsimDecidesByItsMean) {
  // 0.99884: below the default 0.999, above 0.998.
  Outcome strict = run_xshade("", diff("--metric ssim"));
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_NE(strict.output.find("SSIM mean 0.9988"), std::string::npos) << strict.output;
  EXPECT_EQ(run_xshade("", diff("--metric ssim --threshold 0.998")).exit_code, 0);
  const std::string golden = (kSource / "golden" / "dof_on_16.png").string();
  Outcome same = run_xshade("", "diff '" + golden + "' '" + golden + "' --metric ssim");
  EXPECT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("SSIM mean 1.000000"), std::string::npos) << same.output;
}

TEST(DiffMetric, DeltaEHoldsUnitysThresholdsAndReportsThemAsJson) {
  // The largest pixel difference is 4.87: a per-pixel threshold of 5 leaves nothing.
  Outcome strict = run_xshade("", diff("--metric deltae --json"));
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  const nlohmann::json document = nlohmann::json::parse(strict.output.substr(strict.output.find('{')));
  EXPECT_EQ(document["decided_by"], "deltae");
  EXPECT_EQ(document["verdict"], "fail");
  EXPECT_GT(document["metric"]["figures"]["incorrect_fraction"].get<double>(), 0.02);
  EXPECT_NEAR(document["metric"]["figures"]["max"].get<double>(), 4.87, 0.01);
  EXPECT_EQ(run_xshade("", diff("--metric deltae --pixel-threshold 5")).exit_code, 0);
  // Or allow the pixels above 1, and what they leave on average.
  EXPECT_EQ(run_xshade("", diff("--metric deltae --incorrect-fraction 0.03 --threshold 0.02")).exit_code, 0);
}

TEST(DiffMetric, AMetricTheCommandLineDoesNotKnowIsRefused) {
  Outcome outcome = run_xshade("", diff("--metric psnr"));
  EXPECT_EQ(outcome.exit_code, 2) << outcome.output;
  EXPECT_NE(outcome.output.find("flip"), std::string::npos) << outcome.output;
}

}  // namespace diff_metric_test
}  // namespace xshade::tests
