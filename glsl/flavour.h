// The two GLSL dialects xshade emits, and the one vertex shader every full-screen pass shares.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hlsl_like/reflection.h"

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

// The same triangle feeding every varying a fragment shader reads (hlsl::Reflection::varyings):
// a float scalar or vector gets the first components of (u, v, 0, 1), so TEXCOORD0 is uv as
// above and every other texture coordinate (Unity's texcoordStereo) is uv too; an integer one
// gets 0; a float matrix the identity; each element of an array of those gets the same. The
// clip and cull distances the fragment stage reads (Reflection::clip_distances, cull_distances)
// are 0: nothing clips or culls the full-screen triangle.
std::string fullscreen_vertex_shader(Flavour flavour, const hlsl::Reflection& reflection);

}  // namespace xshade::glsl
