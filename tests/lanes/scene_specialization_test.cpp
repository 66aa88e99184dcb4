// Specialization constants set by a scene ([[vk::constant_id]] constants named in
// [object.properties], docs/scenes.md) drawn on every lane: each object its own value, the
// constant's default where the scene gives none, and a value that does not fit refused.
#include <string>

#include <gtest/gtest.h>

#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::Lane;

// A plane over the whole target showing its constants.
constexpr const char* kSpecializedMaterial = R"(#pragma vertex vert
#pragma fragment frag
[[vk::constant_id(1)]] const float LEVEL = 0.25;
[[vk::constant_id(2)]] const uint STEPS = 1;
float4 vert(float2 uv : TEXCOORD0) : SV_Position { return float4(uv * 2.0 - 1.0, 0.5, 1.0); }
float4 frag() : SV_Target { return float4(LEVEL, float(STEPS) * 0.125, 0, 1); }
)";

std::string specialized_scene(const std::string& properties) {
  return probe_scene_head("specialization constants from the scene", 2, 2) +
         "[[object]]\nmesh = \"plane\"\nmaterial = \"specialized.hlsl\"\n[object.properties]\n" + properties;
}

class SceneSpecialization : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void SetUp() override { probe_.write("specialized.hlsl", kSpecializedMaterial); }
  void TearDown() override { expect_no_driver_messages(); }
  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(SceneSpecialization, AnObjectsValueOrTheDefaultIsWhatTheShaderReadsOnEveryLane) {
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto given = probe_.render(specialized_scene("LEVEL = 0.75\nSTEPS = 3\n"), lane, suite_backend(lane));
    ASSERT_TRUE(given) << given.error().to_string();
    EXPECT_EQ(given->at(1, 1), glm::vec4(0.75f, 0.375f, 0.0f, 1.0f));
    auto defaults = probe_.render(specialized_scene(""), lane, suite_backend(lane));
    ASSERT_TRUE(defaults) << defaults.error().to_string();
    EXPECT_EQ(defaults->at(1, 1), glm::vec4(0.25f, 0.125f, 0.0f, 1.0f));
  }
}

TEST_F(SceneSpecialization, AValueThatDoesNotFitTheConstantsTypeIsRefusedAtItsLine) {
  auto fraction = probe_.render(specialized_scene("STEPS = 1.5\n"), Lane::Gl, suite_backend(Lane::Gl));
  ASSERT_FALSE(fraction);
  EXPECT_NE(
      fraction.error().to_string().find("'STEPS' is a specialization constant (uint) of material 'specialized.hlsl': "
                                        "give it a whole number, not 1.5"),
      std::string::npos)
      << fraction.error().to_string();
  auto vector = probe_.render(specialized_scene("LEVEL = [1, 2]\n"), Lane::Gl, suite_backend(Lane::Gl));
  ASSERT_FALSE(vector);
  EXPECT_NE(vector.error().to_string().find("give it 1 number, not 2 numbers"), std::string::npos)
      << vector.error().to_string();
}

}  // namespace
}  // namespace xshade::tests
