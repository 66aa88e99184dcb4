// A scene written into a temporary folder with its shaders and files, then planned, compiled and
// rendered on a lane through the real renderer: for tests of what the renderer gives a shader.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "base/result.h"
#include "harness/backend/backend.h"
#include "harness/image/image.h"
#include "harness/scene/lane.h"

namespace xshade::tests {

class ProbeScene {
 public:
  // A new, empty folder named after `name` (and the process, so that test runs in parallel do not meet).
  explicit ProbeScene(const std::string& name);
  ~ProbeScene();  // removes the folder
  ProbeScene(const ProbeScene&) = delete;
  ProbeScene& operator=(const ProbeScene&) = delete;

  const std::filesystem::path& folder() const { return folder_; }
  void write(const std::string& file, const std::string& text) const;
  // PNG (8-bit sRGB) or EXR by the name's extension.
  void write_image(const std::string& file, const harness::FloatImage& image) const;
  // direction_equirect() as an EXR, always the same bytes.
  void write_direction_equirect(const std::string& file) const;

  // `scene_text` as `probe.toml` in the folder, its shaders found in the folder, then the library.
  Result<harness::FloatImage> render(const std::string& scene_text, harness::Lane lane,
                                     harness::Backend& backend) const;

 private:
  std::filesystem::path folder_;
};

// A probe scene's first lines: its description, its size and a camera, which probes drawn
// full-screen or by their own vertex shader do not look through.
std::string probe_scene_head(const std::string& description, uint32_t width, uint32_t height);

// An equirect environment of radiance 0.5 + 0.5 d in direction d (256 x 128): every direction,
// and so every cube face and axis, reads differently.
harness::FloatImage direction_equirect();

// The vertex functions Unity's code draws a full-screen triangle with, for the HLSLINCLUDE of a probe
// .shader: `vert_img` through the matrices, as Graphics.Blit's vert_img; `vert_triangle` with the
// triangle's corners as they are and uv flipped where UNITY_UV_STARTS_AT_TOP is defined, as Post
// Processing v2's VertDefault. Both output `Blit` (pos : SV_Position, uv : TEXCOORD0).
extern const char* const kUnityBlitVertexFunctions;

// One backend per lane for a whole test suite (creating a Vulkan instance per test costs more
// than the test), the Vulkan one with its validation layer when installed.
harness::Backend& suite_backend(harness::Lane lane);
void release_suite_backends();
// Fails the current test for every message a lane's driver left.
void expect_no_driver_messages();

}  // namespace xshade::tests
