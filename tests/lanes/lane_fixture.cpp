#include "tests/lanes/lane_fixture.h"

#include <fstream>
#include <sstream>

#include "glsl/flavour.h"
#include "harness/vulkan/vulkan_backend.h"

namespace xshade::tests {

std::string read_shader(const std::string& name) {
  const std::string path = std::string(XSHADE_TEST_SHADER_DIR) + "/" + name;
  std::ifstream file(path);
  if (!file) ADD_FAILURE() << "cannot read " << path;
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

harness::GlslStagePair load_shader_pair(const std::string& name, const std::string& stage) {
  return {read_shader(name + ".gl." + stage), read_shader(name + ".vk." + stage), name + "." + stage};
}

void LaneTest::SetUp() {
  for (harness::Lane lane : harness::all_lanes()) {
    auto created = harness::create_backend(lane, {.validation = harness::vulkan_validation_available()});
    ASSERT_TRUE(created) << harness::lane_name(lane) << ": " << created.error().to_string();
    backends_.emplace(lane, std::move(*created));
  }
}

void LaneTest::TearDown() {
  for (auto& [lane, lane_backend] : backends_)
    for (const std::string& message : lane_backend->take_driver_messages())
      ADD_FAILURE() << harness::lane_name(lane) << " driver message: " << message;
}

harness::ProgramHandle LaneTest::program(harness::Lane lane, const std::string& vertex, const std::string& fragment,
                                         harness::ProgramLayout layout) {
  harness::ProgramDesc desc;
  desc.name = fragment;
  desc.layout = std::move(layout);
  desc.fullscreen = vertex == "fullscreen";
  harness::GlslStagePair vertex_pair =
      desc.fullscreen ? harness::GlslStagePair{glsl::fullscreen_vertex_shader(glsl::Flavour::Gl),
                                               glsl::fullscreen_vertex_shader(glsl::Flavour::Vk), "fullscreen.vert"}
                      : load_shader_pair(vertex, "vert");
  auto vertex_stage = harness::stage_for_lane(lane, spirv::Stage::Vertex, vertex_pair);
  auto fragment_stage = harness::stage_for_lane(lane, spirv::Stage::Fragment, load_shader_pair(fragment, "frag"));
  EXPECT_TRUE(vertex_stage) << vertex_stage.error().to_string();
  EXPECT_TRUE(fragment_stage) << fragment_stage.error().to_string();
  if (!vertex_stage || !fragment_stage) return {};
  desc.vertex = std::move(*vertex_stage);
  desc.fragment = std::move(*fragment_stage);
  auto handle = backend(lane).create_program(desc);
  EXPECT_TRUE(handle) << harness::lane_name(lane) << ": " << handle.error().to_string();
  return handle ? *handle : harness::ProgramHandle{};
}

}  // namespace xshade::tests
