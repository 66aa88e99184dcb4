// What goes wrong must be reported, never crash: bad GLSL, validation messages.
#include <gtest/gtest.h>

#include "harness/vulkan/vulkan_backend.h"
#include "tests/lanes/lane_fixture.h"

namespace xshade::tests {
namespace {

using harness::Lane;

TEST(BrokenGlsl, EachLaneNamesTheLine) {
  const harness::GlslStagePair broken = load_shader_pair("broken", "frag");
  constexpr uint32_t kBrokenLine = 4;  // `target = vec4(not_declared_anywhere, 1.0);`

  // vk: glslang rejects it before any driver sees it.
  auto vk_stage = harness::stage_for_lane(Lane::Vk, spirv::Stage::Fragment, broken);
  ASSERT_FALSE(vk_stage);
  ASSERT_FALSE(vk_stage.error().diagnostics.empty());
  EXPECT_EQ(vk_stage.error().diagnostics[0].where.file, "broken.frag");
  EXPECT_EQ(vk_stage.error().diagnostics[0].where.line, kBrokenLine);

  // gl: the driver's compiler rejects it, and its log is parsed into the same form.
  auto gl = harness::create_backend(Lane::Gl);
  ASSERT_TRUE(gl) << gl.error().to_string();
  auto gl_stage = harness::stage_for_lane(Lane::Gl, spirv::Stage::Fragment, broken);
  ASSERT_TRUE(gl_stage);  // gl takes the text as it is
  harness::ProgramDesc desc;
  desc.name = "broken";
  desc.fullscreen = true;
  desc.vertex = *harness::stage_for_lane(Lane::Gl, spirv::Stage::Vertex, load_shader_pair("mesh", "vert"));
  desc.fragment = *gl_stage;
  auto program = (*gl)->create_program(desc);
  ASSERT_FALSE(program);
  bool found_line = false;
  for (const Diagnostic& diagnostic : program.error().diagnostics)
    found_line |= diagnostic.where.file == "broken.frag" && diagnostic.where.line == kBrokenLine;
  EXPECT_TRUE(found_line) << program.error().to_string();
}

TEST(VulkanValidation, AMessageFromTheLayerReachesTheTest) {
  if (!harness::vulkan_validation_available()) GTEST_SKIP() << "vulkan-validationlayers is not installed";
  auto vk = harness::create_backend(Lane::Vk, {.validation = true});
  ASSERT_TRUE(vk) << vk.error().to_string();
  harness::ProgramDesc desc;
  desc.name = "unfed_input";
  desc.vertex = *harness::stage_for_lane(Lane::Vk, spirv::Stage::Vertex, load_shader_pair("mesh", "vert"));
  auto fragment =
      spirv::compile_vulkan_glsl(read_shader("unfed_input.vk.frag"), spirv::Stage::Fragment, "unfed_input.vk.frag");
  ASSERT_TRUE(fragment) << fragment.error().to_string();
  desc.fragment.spirv = fragment->words;
  desc.fragment.name = "unfed_input.vk.frag";

  // The pipeline may be made when the program is created or at its first draw; either way the
  // layer must speak by the end of a draw.
  auto program = (*vk)->create_program(desc);
  if (program) {
    auto target = (*vk)->create_target({4, 4, false});
    auto mesh = (*vk)->upload_mesh(harness::MeshData{{{}, {}, {}}, {0, 1, 2}});
    ASSERT_TRUE(target && mesh);
    (void)(*vk)->render({*target, glm::vec4(0.0f), 1.0f, {{*program, *mesh, {}, {}, {}}}});
  }
  EXPECT_FALSE((*vk)->take_driver_messages().empty());
}

}  // namespace
}  // namespace xshade::tests
