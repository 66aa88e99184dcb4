// Shared set-up for tests that draw the same thing on every lane and compare.
#pragma once

#include <map>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "harness/backend/backend.h"
#include "harness/render/lanes.h"

namespace xshade::tests {

// Reads tests/shaders/<name>.<gl|vk>.<vert|frag> as a pair of hand-written GLSL stages.
harness::GlslStagePair load_shader_pair(const std::string& name, const std::string& stage);
// The text of tests/shaders/<file>.
std::string read_shader(const std::string& file);

// A backend per lane, the Vulkan one with its validation layer when installed. After each test
// no lane may have left a driver message: any debug or validation output fails the test.
class LaneTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  harness::Backend& backend(harness::Lane lane) { return *backends_.at(lane); }

  // A program of two hand-written stages (tests/shaders/<vertex>.*.vert, <fragment>.*.frag);
  // vertex "fullscreen" is the shared full-screen triangle.
  harness::ProgramHandle program(harness::Lane lane, const std::string& vertex, const std::string& fragment,
                                 harness::ProgramLayout layout);

 private:
  std::map<harness::Lane, std::unique_ptr<harness::Backend>> backends_;
};

}  // namespace xshade::tests
