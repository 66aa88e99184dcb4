// The two GLSL dialects xshade emits, and the one vertex shader every full-screen pass shares.
#pragma once

#include <string>
#include <string_view>

namespace xshade::glsl {

enum class Flavour {
  Gl,  // #version 450 core for OpenGL: combined samplers, explicit locations and bindings
  Vk,  // Vulkan GLSL for glslang: set/binding, separate texture and sampler objects
};

std::string_view flavour_name(Flavour flavour);

// A full-screen triangle without vertex input, in Direct3D conventions: clip +y is up, and the
// varying `uv` at location 0 is (0,0) at the top-left of the target, so that uv addresses a
// sampled target the way it addresses an image file.
std::string fullscreen_vertex_shader(Flavour flavour);

}  // namespace xshade::glsl
