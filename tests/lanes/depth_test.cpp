// Depth testing, and depth sampled by a later pass, on every lane.
#include <gtest/gtest.h>

#include "harness/assets/meshes.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;
using harness::TextureSource;

constexpr uint32_t kDepthImageSize = 32;
constexpr glm::vec4 kNearColor{1.0f, 0.5f, 0.0f, 1.0f};
constexpr glm::vec4 kFarColor{0.0f, 0.5f, 1.0f, 1.0f};
constexpr float kNearDepth = 0.25f;
constexpr float kFarDepth = 0.75f;

class Depth : public LaneTest {
 protected:
  struct Rendered {
    harness::FloatImage color;
    harness::FloatImage depth;  // the depth as a second pass sampled it
  };

  // Left half: near drawn before far; right half: far drawn before near. Each pair overlaps in
  // the middle of its half, so the nearer must win regardless of the order of drawing.
  Rendered render(Lane lane) {
    harness::Backend& lane_backend = backend(lane);
    auto flat = program(lane, "mesh", "flat", {{{"Flat", 0, 16}}, {}});
    auto show_depth = program(lane, "fullscreen", "show_depth", {{}, {{"scene_depth", 0, 1}}});
    auto scene = lane_backend.create_target({kDepthImageSize, kDepthImageSize, true});
    auto view = lane_backend.create_target({kDepthImageSize, kDepthImageSize, false});
    EXPECT_TRUE(scene && view);
    auto draw = [&](float x0, float x1, float z, glm::vec4 color) {
      auto mesh = lane_backend.upload_mesh(harness::clip_rectangle(x0, -1.0f, x1, 1.0f, z));
      EXPECT_TRUE(mesh);
      return harness::DrawItem{flat, *mesh, {{"Flat", harness::uniform_bytes(color)}}, {}, {}};
    };
    harness::RenderPass scene_pass{*scene, glm::vec4(0.0f), 1.0f, {}};
    scene_pass.draws = {draw(-1.0f, -0.25f, kNearDepth, kNearColor), draw(-0.75f, 0.0f, kFarDepth, kFarColor),
                        draw(0.25f, 1.0f, kFarDepth, kFarColor), draw(0.0f, 0.75f, kNearDepth, kNearColor)};
    EXPECT_TRUE(lane_backend.render(scene_pass));

    harness::RenderPass view_pass{*view, glm::vec4(0.0f), 1.0f, {}};
    view_pass.draws = {{show_depth,
                        {},
                        {},
                        {{"scene_depth", TextureSource::depth_of(
                                             *scene, {harness::Filter::Nearest, harness::AddressMode::ClampToEdge})}},
                        {}}};
    EXPECT_TRUE(lane_backend.render(view_pass));

    auto color = lane_backend.read_color(*scene);
    auto depth = lane_backend.read_color(*view);
    EXPECT_TRUE(color && depth);
    return {color ? *color : harness::FloatImage{}, depth ? *depth : harness::FloatImage{}};
  }
};

TEST_F(Depth, NearerGeometryWinsAndLaterPassesSampleTheSameDepth) {
  std::map<Lane, Rendered> results;
  for (Lane lane : harness::glsl_pair_lanes()) {
    SCOPED_TRACE(harness::lane_name(lane));
    Rendered rendered = render(lane);
    ASSERT_EQ(rendered.color.width, kDepthImageSize);
    ASSERT_EQ(rendered.depth.width, kDepthImageSize);
    const uint32_t y = kDepthImageSize / 2;
    // Pixel columns (32 wide): near-first pair covers x in [0,12) near, [4,16) far; the
    // far-first pair covers [20,32) far and [16,28) near.
    EXPECT_EQ(rendered.color.at(2, y), kNearColor);
    EXPECT_EQ(rendered.color.at(8, y), kNearColor);  // overlap, near drawn first
    EXPECT_EQ(rendered.color.at(14, y), kFarColor);
    EXPECT_EQ(rendered.color.at(18, y), kNearColor);
    EXPECT_EQ(rendered.color.at(24, y), kNearColor);  // overlap, near drawn last
    EXPECT_EQ(rendered.color.at(30, y), kFarColor);
    EXPECT_EQ(rendered.depth.at(8, y).r, kNearDepth);
    EXPECT_EQ(rendered.depth.at(14, y).r, kFarDepth);
    results.emplace(lane, std::move(rendered));
  }
  const auto& gl = results.at(Lane::Gl);
  const auto& vk = results.at(Lane::Vk);
  EXPECT_TRUE(harness::bitwise_equal(gl.color, vk.color));
  // The bound for sampled depth; the lanes are in fact expected to agree exactly.
  EXPECT_LE(harness::max_difference(gl.depth, vk.depth).max, 1e-6);
}

}  // namespace
}  // namespace xshade::tests
