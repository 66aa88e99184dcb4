// Float targets keep what a shader writes: values above 1, negatives, NaN and infinities.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

class FloatTargets : public LaneTest {};

TEST_F(FloatTargets, SpecialValuesSurviveReadBack) {
  const float inf = std::numeric_limits<float>::infinity();
  for (Lane lane : harness::glsl_pair_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    harness::Backend& lane_backend = backend(lane);
    auto write = program(lane, "fullscreen", "special_floats", {});
    auto target = lane_backend.create_target({4, 2, false});
    ASSERT_TRUE(target);
    ASSERT_TRUE(lane_backend.render({*target, glm::vec4(0.0f), 1.0f, {{write, {}, {}, {}, {}}}}));
    auto image = lane_backend.read_color(*target);
    ASSERT_TRUE(image) << image.error().to_string();
    for (uint32_t x = 0; x < 4; ++x) {
      const glm::vec4 top = image->at(x, 0);
      EXPECT_EQ(top.r, 2.5f);
      EXPECT_EQ(top.g, -1.0f);
      EXPECT_TRUE(std::isnan(top.b)) << top.b;
      EXPECT_EQ(top.a, inf);
      const glm::vec4 bottom = image->at(x, 1);
      EXPECT_EQ(bottom.r, -inf);
      EXPECT_EQ(bottom.g, 65504.0f);
      EXPECT_EQ(bottom.b, 1e-30f);  // a normal float far below 8-bit resolution
      EXPECT_EQ(bottom.a, 0.0f);
    }
  }
}

}  // namespace
}  // namespace xshade::tests
