// The stability suite as CTest tests: every case on every lane, in fp32 and fp16 emulation,
// must come out as predicted (the guarded forms hold, the seed's break exactly where predicted).
// A failure prints the case, the form, the lane, the precision, the input and the value.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "stability/cases.h"
#include "stability/suite.h"

namespace xshade::stability {
namespace {

const std::filesystem::path kSource = XSHADE_SOURCE_DIR;

SuiteOptions options_for(harness::Lane lane, std::vector<Precision> precisions = {}) {
  SuiteOptions options;
  options.lanes = {lane};
  options.precisions = std::move(precisions);
  options.shaders_dir = kSource / "shaders";
  options.probes_dir = kSource / "stability" / "probes";
  options.scenes_dir = kSource / "scenes";
  // Mesa's shader cache, shared by every stability test of the build: the depth-of-field cases
  // compile the same passes (the 43-sample kernel in all four, each sampled kernel in two) on each
  // lane, and LLVM compiling them again is most of what those tests take. The cache is keyed by
  // the shader and the driver, so a hit runs the code a compile would make.
  options.backend.driver_cache = XSHADE_STABILITY_DRIVER_CACHE;
  return options;
}

const Case& find_case(const std::vector<Case>& cases, const std::string& id) {
  return *std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.id == id; });
}

struct CaseOnLane {
  std::string case_id;
  harness::Lane lane;
};

// How CTest's test names show the parameter.
void PrintTo(const CaseOnLane& param, std::ostream* out) {
  *out << param.case_id << " on " << harness::lane_name(param.lane);
}

class StabilityCase : public testing::TestWithParam<CaseOnLane> {};

TEST_P(StabilityCase, ComesOutAsPredicted) {
  const std::vector<Case> cases = all_cases();
  auto run = run_suite({find_case(cases, GetParam().case_id)}, options_for(GetParam().lane));
  ASSERT_TRUE(run) << run.error().to_string();
  ASSERT_FALSE(run->outcomes.empty());
  for (const Outcome& outcome : run->outcomes) EXPECT_TRUE(outcome.as_predicted()) << outcome.explain();
}

std::vector<CaseOnLane> every_case_on_every_lane() {
  std::vector<CaseOnLane> params;
  for (const Case& c : all_cases())
    for (harness::Lane lane : harness::all_lanes()) {
      // vk-hlsl runs fp32 only (glslang compiles the source and cannot emulate fp16).
      const bool has_fp32 = std::find(c.precisions.begin(), c.precisions.end(), Precision::Float) != c.precisions.end();
      if (lane != harness::Lane::VkHlsl || has_fp32) params.push_back({c.id, lane});
    }
  return params;
}

INSTANTIATE_TEST_SUITE_P(Cases, StabilityCase, testing::ValuesIn(every_case_on_every_lane()),
                         [](const testing::TestParamInfo<CaseOnLane>& param) {
                           std::string name =
                               param.param.case_id + "_" + std::string(harness::lane_name(param.param.lane));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// A guarded form that breaks (here: the seed's D, run as if it were predicted to hold) fails
// with the case, its input and the value that broke the bound.
TEST(StabilitySuite, ABreakNamesTheCaseTheInputAndTheValue) {
  const std::vector<Case> cases = all_cases();
  Case broken = find_case(cases, "ggx_peak");
  broken.forms = {{"seed D claimed stable", {}, false}};
  broken.predict = nullptr;
  auto run = run_suite({broken}, options_for(harness::Lane::Gl, {Precision::Half}));
  ASSERT_TRUE(run) << run.error().to_string();
  ASSERT_EQ(run->outcomes.size(), 1u);
  const Outcome& outcome = run->outcomes.front();
  EXPECT_FALSE(outcome.as_predicted());
  EXPECT_EQ(run->unexpected(), 1u);
  EXPECT_THAT(outcome.explain(),
              testing::HasSubstr("stability case ggx_peak (SHADERS.md 5.1), form 'seed D claimed stable', "
                                 "lane gl, fp16 emulation: D at a = 0.002 was inf, expected finite and <= 65504"));
}

// A predicted break that does not happen is reported too: the prediction is wrong.
TEST(StabilitySuite, APredictedBreakThatHoldsIsReported) {
  const std::vector<Case> cases = all_cases();
  Case c = find_case(cases, "zero_alpha");
  c.forms = {{"guarded", {"_GUARDED", "_D_GGX_LAGRANGE"}, false}};
  c.predict = [](const Form&, Precision) -> Prediction { return {{"a = 0, NoH = 1"}, "wrongly predicted"}; };
  auto run = run_suite({c}, options_for(harness::Lane::Gl, {Precision::Float}));
  ASSERT_TRUE(run) << run.error().to_string();
  ASSERT_EQ(run->outcomes.size(), 1u);
  EXPECT_FALSE(run->outcomes.front().as_predicted());
  EXPECT_THAT(run->outcomes.front().explain(),
              testing::HasSubstr("predicted to break at a = 0, NoH = 1 but held: D = "));
}

TEST(StabilitySuite, AnUnknownCaseIsRefusedWithTheKnownOnes) {
  SuiteOptions options = options_for(harness::Lane::Gl);
  options.case_ids = {"no_such_case"};
  auto run = run_suite(all_cases(), options);
  ASSERT_FALSE(run);
  EXPECT_THAT(run.error().message, testing::HasSubstr("no stability case 'no_such_case'; the cases are: ggx_peak, "));
  EXPECT_EQ(run.error().kind, ErrorKind::Usage);  // the command line gives exit 2 for it
}

TEST(StabilitySuite, MarkdownHasTheSummaryAndEveryMeasuredValue) {
  const std::vector<Case> cases = all_cases();
  const Case& peak = find_case(cases, "ggx_peak");
  auto run = run_suite({peak}, options_for(harness::Lane::Gl));
  ASSERT_TRUE(run) << run.error().to_string();
  const std::string md = stability_markdown({peak}, *run, "xshade stability ggx_peak --lane gl");
  EXPECT_THAT(md, testing::HasSubstr("| case | SHADERS.md | form | gl fp32 | gl fp16 |"));
  EXPECT_THAT(md, testing::HasSubstr("| [ggx_peak](#ggx_peak) | 5.1 | seed | holds | breaks as predicted (2 of 4) |"));
  EXPECT_THAT(md, testing::HasSubstr("| [ggx_peak](#ggx_peak) | 5.1 | guarded | holds | holds |"));
  // The seed's fp16 row at a = 0.002: the fp32 column has its own bound's row.
  EXPECT_THAT(md, testing::HasSubstr("| seed | a = 0.002 | D | finite and <= 65504 (fp16's largest) | - | inf ✗ |"));
}

// Each predicted non-finite value names the line it was born on (the tracing variant): the seed's
// D at a = 0 and NoH = 1 is 0/0 in its division, its return in brdf.hlsl; the Lagrange form's
// finite value names nothing.
TEST(StabilitySuite, ANonFiniteValueNamesTheLineItWasBornOn) {
  const std::vector<Case> cases = all_cases();
  auto run = run_suite({find_case(cases, "zero_alpha")}, options_for(harness::Lane::Vk, {Precision::Float}));
  ASSERT_TRUE(run) << run.error().to_string();
  bool named = false;
  for (const Outcome& outcome : run->outcomes)
    for (const Measurement& m : outcome.measurements) {
      if (std::isfinite(m.value)) {
        EXPECT_EQ(m.born_at, "") << m.input;
      }
      if (outcome.form == "seed" && m.input == "a = 0, NoH = 1" && m.quantity == "D") {
        EXPECT_EQ(m.born_at, "brdf.hlsl:19: the value D_GGX_seed returns");
        named = true;
      }
    }
  EXPECT_TRUE(named) << "the seed's D at a = 0 was not measured";
  const std::string md = stability_markdown({find_case(cases, "zero_alpha")}, *run, "xshade stability zero_alpha");
  EXPECT_THAT(
      md, testing::HasSubstr("- *seed, fp32, a = 0, NoH = 1 (D)*: born at brdf.hlsl:19: the value D_GGX_seed returns"));
}

}  // namespace
}  // namespace xshade::stability
