// Vertex inputs no mesh supplies (TEXCOORD1..7, COLOR0..1: every location but 0..3) read zeros
// of their type on every lane, and a float colour white, as from a Unity mesh without vertex
// colours: OpenGL through the generic current attribute value, set per draw (its own default
// would be (0, 0, 0, 1)), Vulkan from a constant buffer read at stride 0.
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "harness/render/shader_program.h"
#include "hlsl_like/compiler.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

constexpr const char* kSource = R"(
#pragma vertex vert
#pragma fragment frag
struct appdata {
  float3 position : POSITION;
  float4 extra : TEXCOORD5;
  float4 tint : COLOR1;
  int index : TEXCOORD7;
  uint2 flags : TEXCOORD2;
};
struct v2f {
  float4 position : SV_Position;
  float4 extra : TEXCOORD0;
  float4 tint : TEXCOORD1;
  nointerpolation int index : TEXCOORD2;
  nointerpolation uint2 flags : TEXCOORD3;
};
v2f vert(appdata v) {
  v2f o;
  o.position = float4(v.position, 1);
  o.extra = v.extra;
  o.tint = v.tint;
  o.index = v.index;
  o.flags = v.flags;
  return o;
}
float4 frag(v2f i) : SV_Target {
  // Each input at its own scale, so that any non-zero component shows which input it came from.
  return i.extra + i.tint * 10 + float(i.index) * 100 + float(i.flags.x + i.flags.y) * 1000 +
         float4(0.25, 0.5, 0.75, 1.0);
}
)";

class VertexInputs : public LaneTest {
 protected:
  // Draws a quad over a 4 x 4 target cleared to -1 on every lane and gives each lane's image to
  // `check` (a pixel the quad missed cannot pass).
  void render_on_every_lane(const std::string& name, const char* source,
                            const std::function<void(const harness::FloatImage&)>& check) {
    auto module = hlsl::compile_text(name, source, {});
    ASSERT_TRUE(module->ok()) << module->diagnostics.render_all();
    harness::MeshData quad;
    for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      quad.vertices.push_back({glm::vec3(corner, 0.5f)});
    quad.indices = {0, 1, 2, 0, 2, 3};
    for (Lane lane : harness::all_lanes()) {
      SCOPED_TRACE(harness::lane_name(lane));
      harness::Backend& lane_backend = backend(lane);
      auto desc = harness::program_for_lane(*module, lane);
      ASSERT_TRUE(desc) << desc.error().to_string();
      auto program = lane_backend.create_program(*desc);
      ASSERT_TRUE(program) << program.error().to_string();
      auto mesh = lane_backend.upload_mesh(quad);
      auto target = lane_backend.create_target({4, 4, false});
      ASSERT_TRUE(mesh && target);
      auto rendered = lane_backend.render({*target, glm::vec4(-1.0f), 1.0f, {{*program, *mesh, {}, {}, {}}}});
      ASSERT_TRUE(rendered) << rendered.error().to_string();
      auto image = lane_backend.read_color(*target);
      ASSERT_TRUE(image);
      check(*image);
    }
  }
};

TEST_F(VertexInputs, InputsNoMeshSuppliesReadZerosOfTheirTypeAndColoursWhite) {
  auto module = hlsl::compile_text("vertex_inputs.hlsl", kSource, {});
  ASSERT_TRUE(module->ok());
  // The reflection places them where the backends feed zeros: above location 3.
  for (const hlsl::StageVariable& input : module->reflection.vertex_inputs)
    if (input.semantic != "POSITION0") {
      EXPECT_GT(input.location, 3u) << input.semantic;
    }
  // The backends' white inputs are the colours' locations.
  for (const char* semantic : {"COLOR0", "COLOR1", "TEXCOORD1", "TEXCOORD7"})
    EXPECT_EQ(harness::unsupplied_input_reads_white(*hlsl::vertex_input_location(semantic)),
              std::string(semantic).starts_with("COLOR"))
        << semantic;
  render_on_every_lane("vertex_inputs.hlsl", kSource, [](const harness::FloatImage& image) {
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x)  // the COLOR1 tint, white, times 10
        EXPECT_EQ(image.at(x, y), glm::vec4(10.25f, 10.5f, 10.75f, 11.0f)) << x << "," << y;
  });
}

// An array varying takes a location per element and the varying after it moves past them
// (hlsl::Reflection::varyings), as HLSL written for SPIR-V declares them: each lane links the
// two stages, and each value arrives where the vertex stage wrote it.
TEST_F(VertexInputs, VaryingsAfterAnArrayArriveWhereTheyWereWritten) {
  constexpr const char* kArrays = R"(
#pragma vertex vert
#pragma fragment frag
struct v2f {
  float4 position : SV_Position;
  nointerpolation float3 light[2] : TEXCOORD2;
  nointerpolation float3 view : TEXCOORD3;
  nointerpolation float intensity : TEXCOORD4;
  nointerpolation float2 basis[2] : TEXCOORD5;
  nointerpolation float tail : TEXCOORD6;
};
v2f vert(float3 position : POSITION) {
  v2f o;
  o.position = float4(position, 1);
  o.light[0] = float3(1, 2, 3);
  o.light[1] = float3(4, 5, 6);
  o.view = float3(7, 8, 9);
  o.intensity = 10;
  o.basis[0] = float2(11, 12);
  o.basis[1] = float2(13, 14);
  o.tail = 15;
  return o;
}
float4 frag(v2f i) : SV_Target {
  return float4(i.light[0].x + i.light[1].z * 16, i.view.y + i.intensity * 16,
                i.basis[1].x + i.basis[0].y * 16, i.tail);
}
)";
  render_on_every_lane("varying_arrays.hlsl", kArrays, [](const harness::FloatImage& image) {
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x)
        EXPECT_EQ(image.at(x, y), glm::vec4(1 + 6 * 16, 8 + 10 * 16, 13 + 12 * 16, 15)) << x << "," << y;
  });
}

}  // namespace
}  // namespace xshade::tests
