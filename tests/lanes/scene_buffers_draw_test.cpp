// Read-only buffers a scene gives an object ([object.buffers], docs/scenes.md) drawn on every
// lane: numbers written in the scene and a file of bytes, each read back where the shader reads
// them; a buffer the material reads and the scene does not give, or one it gives that the
// material does not read, is refused at the scene's line.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/lanes/probe_scene.h"

namespace xshade::tests {
namespace {

using harness::Lane;

constexpr uint32_t kBufferColumns = 4;

// A plane over the whole target; column x shows element x of a structured buffer of float4
// (row 0) and words 2x, 2x + 1 of a raw buffer (row 1).
constexpr const char* kBufferMaterial = R"(#pragma vertex vert
#pragma fragment frag
StructuredBuffer<float4> palette;
ByteAddressBuffer words;
float4 vert(float2 uv : TEXCOORD0) : SV_Position { return float4(uv * 2.0 - 1.0, 0.5, 1.0); }
float4 frag(float4 pos : SV_Position) : SV_Target {
  uint x = uint(pos.x);
  if (pos.y < 1) return palette[x];
  return float4(asfloat(words.Load2(8 * x)), 0, 1);
}
)";

std::string buffer_scene(const std::string& buffers) {
  return probe_scene_head("buffers given by the scene", kBufferColumns, 2) +
         "[[object]]\nmesh = \"plane\"\nmaterial = \"buffers.hlsl\"\n[object.buffers]\n" + buffers;
}

class SceneBuffersDraw : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { release_suite_backends(); }
  void SetUp() override {
    probe_.write("buffers.hlsl", kBufferMaterial);
    std::vector<float> raw;
    for (uint32_t i = 0; i < 2 * kBufferColumns; ++i) raw.push_back(0.125f * float(i));
    std::string bytes(raw.size() * 4, '\0');
    std::memcpy(bytes.data(), raw.data(), bytes.size());
    probe_.write("words.bin", bytes);
  }
  void TearDown() override { expect_no_driver_messages(); }
  ProbeScene probe_{::testing::UnitTest::GetInstance()->current_test_info()->name()};
};

TEST_F(SceneBuffersDraw, NumbersAndAFileReadBackWhereTheShaderReadsThemOnEveryLane) {
  const std::string scene = buffer_scene(
      "palette = [0.1, 0.2, 0.3, 1, 0.4, 0.5, 0.6, 1, 0.7, 0.8, 0.9, 1, 1, 0, 0.5, 1]\nwords = \"words.bin\"\n");
  for (Lane lane : harness::all_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    auto image = probe_.render(scene, lane, suite_backend(lane));
    ASSERT_TRUE(image) << image.error().to_string();
    const glm::vec4 palette[kBufferColumns] = {
        {0.1f, 0.2f, 0.3f, 1.0f}, {0.4f, 0.5f, 0.6f, 1.0f}, {0.7f, 0.8f, 0.9f, 1.0f}, {1.0f, 0.0f, 0.5f, 1.0f}};
    for (uint32_t x = 0; x < kBufferColumns; ++x) {
      EXPECT_EQ(image->at(x, 0), palette[x]) << "column " << x;
      EXPECT_EQ(image->at(x, 1), glm::vec4(0.25f * float(x), 0.25f * float(x) + 0.125f, 0.0f, 1.0f)) << "column " << x;
    }
  }
}

TEST_F(SceneBuffersDraw, ABufferNotGivenOrNotReadIsRefusedAtTheScenesLine) {
  auto missing = probe_.render(buffer_scene("palette = [1, 1, 1, 1]\n"), Lane::Gl, suite_backend(Lane::Gl));
  ASSERT_FALSE(missing);
  EXPECT_NE(
      missing.error().to_string().find("reads the buffer 'words', which has no default: give it in [object.buffers]"),
      std::string::npos)
      << missing.error().to_string();
  auto unknown = probe_.render(buffer_scene("palette = [1, 1, 1, 1]\nwords = [1, 2]\npalete = [1]\n"), Lane::Gl,
                               suite_backend(Lane::Gl));
  ASSERT_FALSE(unknown);
  EXPECT_NE(unknown.error().to_string().find("reads no buffer 'palete'; did you mean"), std::string::npos)
      << unknown.error().to_string();
  auto partial =
      probe_.render(buffer_scene("palette = [1, 1, 1]\nwords = [1, 2]\n"), Lane::Gl, suite_backend(Lane::Gl));
  ASSERT_FALSE(partial);
  EXPECT_NE(partial.error().to_string().find("is 4 32-bit words: give a multiple of 4 numbers, not 3"),
            std::string::npos)
      << partial.error().to_string();
}

}  // namespace
}  // namespace xshade::tests
