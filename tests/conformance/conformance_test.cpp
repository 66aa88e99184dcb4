// Semantics conformance: each HLSL rule the GLSL emitter maps runs on every lane over a table of
// inputs, and the images are checked against the CPU's answer under HLSL semantics.
//
// A lane that disagrees on purpose is listed in kDivergences with the reason (and in
// docs/divergences.md); the test then checks that it still disagrees, so that the list cannot
// outlive the bug it describes.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <numbers>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "harness/render/evaluate.h"
#include "harness/render/lanes.h"
#include "hlsl_like/compiler.h"

namespace xshade::tests {
namespace {

using harness::Lane;

struct Rule {
  const char* name;  // tests/conformance/shaders/<name>.hlsl
  uint32_t width;    // one pixel per input
  std::function<glm::dvec4(uint32_t x)> expected;
  double tolerance;  // absolute, per channel
  const char* why_tolerance;
  std::map<std::string, std::vector<std::byte>> constant_buffers = {};
  std::function<bool(uint32_t x)> discarded = {};  // pixels the shader discards keep the clear value
};

// Lanes that translate a rule differently from HLSL, and why. Kept in step with docs/divergences.md.
const std::map<std::pair<std::string, Lane>, const char*> kDivergences{
    {{"fmod_frac", Lane::VkHlsl},
     "glslang's HLSL front end gives fmod (and float %) the sign of the divisor, as GLSL's mod "
     "does; HLSL truncates, giving the sign of the dividend"},
    {{"matrices", Lane::VkHlsl},
     "glslang's HLSL front end compiles matrix * matrix as a matrix product; HLSL's * is "
     "component-wise (mul() is the product)"},
    {{"lit", Lane::VkHlsl},
     "glslang's HLSL front end gives lit()'s specular as n_dot_h * m (as DXC does); HLSL's "
     "documentation gives pow(n_dot_h, m)"},
    {{"one_component_vectors", Lane::VkHlsl},
     "glslang's HLSL front end refuses a float1's .x as an l-value ('assign': l-value required), "
     "so Unity's fog (UNITY_TRANSFER_FOG) does not compile there"},
};

double hlsl_fmod(double a, double b) { return a - b * std::trunc(a / b); }

// lit() as HLSL's documentation defines it: ambient, diffuse, specular, 1.
glm::dvec4 hlsl_lit(double n_dot_l, double n_dot_h, double m) {
  const double specular = n_dot_l < 0.0 || n_dot_h < 0.0 ? 0.0 : std::pow(n_dot_h, m);
  return glm::dvec4(1.0, std::max(n_dot_l, 0.0), specular, 1.0);
}
const glm::dvec3 kLitArgs[8] = {{0.5, 0.25, 2.0}, {0.5, 0.75, 4.0}, {2.0, 3.0, 2.0},  {1.0, 2.0, 3.0},
                                {0.25, 0.5, 3.0}, {0.25, 0.5, 3.0}, {-0.5, 0.5, 2.0}, {0.5, -0.25, 2.0}};

const float kFmodInputs[8] = {-7.5f, -3.0f, -0.5f, 0.0f, 0.5f, 3.0f, 7.25f, -1.75f};
const int kIntA[8] = {-7, -7, 7, 7, -8, 0, 5, -1};
const int kIntB[8] = {2, -2, 2, -2, 3, 3, -5, 1};
const float kRoundInputs[8] = {-2.5f, -1.5f, -0.5f, 0.5f, 1.5f, 2.5f, 2.4f, -2.6f};
const glm::dvec2 kAtanYX[8] = {{1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {0, -1}, {2, 0}, {-3, 0.5}, {0.25, 4}};
const double kPositive[8] = {0.25, 1.0, 4.0, 100.0, 1e-3, 0.5, 7.0, 1e4};
const double kLerpS[8] = {-1.0, 0.0, 0.25, 0.5, 1.0, 2.0, -0.5, 0.75};

// The Params buffer of constant_buffer.hlsl, packed by HLSL's rules: a float3 at 4, a float2 at
// 20, the matrix at 32 stored by columns.
std::vector<std::byte> params_bytes();

// globals_packing.hlsl's $Globals: the first 32 bytes of Params, the same members at the same offsets.
std::vector<std::byte> globals_bytes() {
  std::vector<std::byte> bytes = params_bytes();
  bytes.resize(32);
  return bytes;
}

std::vector<std::byte> params_bytes() {
  std::vector<float> floats(32 / 4 + 16, 0.0f);
  floats[0] = 1.0f;                                      // first
  floats[1] = 2.0f, floats[2] = 3.0f, floats[3] = 4.0f;  // packed
  floats[4] = 5.0f;                                      // scalar
  floats[5] = 6.0f, floats[6] = 7.0f;                    // pair
  // matrix_ M with rows (1 2 3 4), (5 6 7 8), (9 10 11 12), (13 14 15 16): column c at 32 + 16c.
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) floats[8 + size_t(col) * 4 + size_t(row)] = float(row * 4 + col + 1);
  std::vector<std::byte> bytes(floats.size() * 4);
  std::memcpy(bytes.data(), floats.data(), bytes.size());
  return bytes;
}

std::vector<Rule> rules() {
  return {
      {"fmod_frac", 8,
       [](uint32_t x) {
         const double v = kFmodInputs[x];
         return glm::dvec4(hlsl_fmod(v, 2.0), hlsl_fmod(v, -2.0), hlsl_fmod(v, 2.0), v - std::floor(v));
       },
       0.0, "inputs are exact in float and a - b * trunc(a / b) is exact for them"},
      {"int_div_mod", 8,
       [](uint32_t x) {
         const int a = kIntA[x], b = kIntB[x];
         const unsigned ua = unsigned(std::abs(a)) + 10u;
         return glm::dvec4(a / b, a % b, ua / 3u, ua % 3u);  // C++ truncates, as HLSL does
       },
       0.0, "integers are exact"},
      {"int_div_mod_vector", 8,
       [](uint32_t x) {
         const int a = kIntA[x], b = kIntB[x];
         return glm::dvec4(a / b, a % b, -a / b, -a % b);
       },
       0.0, "integers are exact"},
      {"matrices", 7,
       [](uint32_t x) {
         const glm::dvec4 results[7] = {{321, 654, 0, 0}, {41, 52, 63, 0}, {4, 5, 6, 3}, {2, 4, 2, -2},
                                        {19, 22, 43, 50}, {5, 12, 21, 32}, {1, 4, 3, 6}};
         return results[x];
       },
       0.0, "small integers in float are exact"},
      {"rounding", 8,
       [](uint32_t x) {
         const double v = kRoundInputs[x];
         return glm::dvec4(std::nearbyint(v), std::trunc(v), std::floor(v), std::ceil(v));  // halves to even
       },
       0.0, "the results are integers"},
      {"transcendental", 8,
       [](uint32_t x) {
         const double v = kPositive[x];
         return glm::dvec4(std::atan2(kAtanYX[x].x, kAtanYX[x].y), 1.0 / std::sqrt(v), std::log10(v),
                           std::clamp(v - 2.0, 0.0, 1.0));
       },
       // GLSL allows atan a few ULP and inversesqrt 2 ULP; log10 is log2 times a constant (two
       // roundings of values up to 4). 4e-6 is ~10 ULP at pi, and far below any wrong quadrant
       // (errors of pi/2) or a wrong base (log10 vs log).
       4e-6, "fp32 transcendentals differ in the last few bits from the fp64 reference"},
      {"lerp_sincos", 8,
       [](uint32_t x) {
         const double s = kLerpS[x];
         return glm::dvec4(2.0 + 4.0 * s, -1.0 + 6.0 * s, std::sin(s * 3.0), std::cos(s * 3.0));
       },
       // sin and cos of arguments up to 6 in fp32: GLSL leaves their precision to the driver;
       // llvmpipe is within ~1e-6 here. 4e-6 still catches swapped or sign-flipped outputs.
       4e-6, "fp32 sin and cos against the fp64 reference"},
      {"select_splat", 8,
       [](uint32_t x) {
         const double v = double(x) + 0.5 - 3.5;
         const double r = (v > 0 ? v : 10.0) + (-v > 0 ? -v : 10.0);
         const double b = v * 2.0 > 0 ? v * 2.0 : 10.0;
         return glm::dvec4(r, b, 2.0 * (0.5 + v), -v);
       },
       0.0, "halves and small integers are exact"},
      {"derivatives", 8, [](uint32_t) { return glm::dvec4(1.0 / 8.0, 1.0 / 2.0, 1.0, 0.0); }, 0.0,
       "uv steps by 1/8 across and 1/2 down (an 8x2 image); pixel positions by 1"},
      {"clip",
       8,
       [](uint32_t) { return glm::dvec4(1, 2, 3, 4); },
       0.0,
       "constants",
       {},
       [](uint32_t x) { return double(x) + 0.5 - 3.5 < 0.0; }},
      {"constant_buffer",
       3,
       [](uint32_t x) {
         const glm::dvec4 results[3] = {{1, 2, 3, 4}, {5, 6, 7, 0}, {30, 70, 110, 150}};
         return results[x];
       },
       0.0,
       "small integers are exact",
       {{"Params", params_bytes()}}},
      {"one_component_vectors", 4, [](uint32_t x) { return glm::dvec4(x + 1.0, x + 1.0, x + 1.0, 2.0 * (x + 1.0)); },
       0.0, "small integers are exact"},
      {"lit", 8, [](uint32_t x) { return hlsl_lit(kLitArgs[x].x, kLitArgs[x].y, kLitArgs[x].z); },
       // GLSL's pow is exp2(m * log2(h)), each within a few ULP; the largest result is 9.
       2e-5, "fp32 pow against the fp64 reference"},
      {"globals_packing",
       2,
       [](uint32_t x) { return x == 0 ? glm::dvec4(1, 2, 3, 4) : glm::dvec4(5, 6, 7, 0); },
       0.0,
       "small integers are exact",
       {{std::string(hlsl::kGlobalsBufferName), globals_bytes()}}},
  };
}

class Conformance : public ::testing::TestWithParam<Rule> {};

TEST_P(Conformance, EveryLaneComputesWhatHlslDefines) {
  const Rule& rule = GetParam();
  const std::string path = std::string(XSHADE_CONFORMANCE_DIR) + "/" + rule.name + ".hlsl";
  auto module = hlsl::compile_file(path, {});
  ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
  const uint32_t height = std::string(rule.name) == "derivatives" ? 2 : 1;
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto backend = harness::create_backend(lane);
    ASSERT_TRUE(backend) << backend.error().to_string();
    auto image = harness::evaluate(*module, lane, **backend, rule.width, height, rule.constant_buffers);
    auto divergence = kDivergences.find({rule.name, lane});
    // A lane that cannot compile the rule diverges too, where that is the listed divergence.
    if (!image && divergence != kDivergences.end()) continue;
    ASSERT_TRUE(image) << image.error().to_string();
    EXPECT_TRUE((*backend)->take_driver_messages().empty());

    std::string first_mismatch;
    for (uint32_t x = 0; x < rule.width && first_mismatch.empty(); ++x) {
      const bool discarded = rule.discarded && rule.discarded(x);
      const glm::dvec4 expected = discarded ? glm::dvec4(0.0) : rule.expected(x);
      const glm::vec4 got = image->at(x, 0);
      for (int c = 0; c < 4; ++c)
        if (!(std::fabs(double(got[c]) - expected[c]) <= rule.tolerance)) {
          first_mismatch = "pixel " + std::to_string(x) + " channel " + "rgba"[c] + ": got " + std::to_string(got[c]) +
                           ", HLSL gives " + std::to_string(expected[c]);
          break;
        }
    }
    if (divergence == kDivergences.end()) {
      EXPECT_EQ(first_mismatch, "") << "tolerance " << rule.tolerance << ": " << rule.why_tolerance;
    } else {
      EXPECT_NE(first_mismatch, "") << "the listed divergence no longer occurs: " << divergence->second;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Rules, Conformance, ::testing::ValuesIn(rules()),
                         [](const ::testing::TestParamInfo<Rule>& rule_info) {
                           return std::string(rule_info.param.name);
                         });

}  // namespace
}  // namespace xshade::tests
