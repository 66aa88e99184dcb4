// Generation: an analysed module as the stages of one target, and the names by which the target's
// code declares the module's resources. The one way from a module to a target's code: the harness
// (which maps a lane to a target) and `xshade compile` both call generate().
//
// Whatever a validator refuses here is xshade's output, never the shader author's: such an error
// has ErrorKind::Internal (exit 3) and carries what a bug report needs, the validator's messages
// and the generated lines they name. A construct the target cannot express keeps the author's kind.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"

namespace xshade::codegen {

// gl: OpenGL GLSL 4.50 core text. vk: Vulkan GLSL text (checked by compiling it). spirv: the vk
// GLSL compiled to SPIR-V 1.6 by glslang. vk-hlsl: the source itself through glslang's HLSL front
// end to SPIR-V, with the module's macros and include folders.
enum class Target { Gl, Vk, Spirv, VkHlsl };
std::string_view target_name(Target target);
std::optional<Target> target_named(std::string_view name);
// Whether the target's code is SPIR-V (spirv, vk-hlsl) rather than GLSL text (gl, vk).
bool makes_spirv(Target target);

// glsl::EmitOptions' knobs. vk-hlsl, which glslang compiles from the source, refuses half
// emulation and tracing, and cannot filter comparisons.
struct GenerateOptions {
  // Every half-typed result rounded to fp16, as hardware with a half type computes it.
  bool half_emulation = false;
  // The tracing variant of the fragment stage (glsl::EmitOptions::trace_nonfinite), numbered
  // `trace_program`.
  bool trace_nonfinite = false;
  uint32_t trace_program = 0;
  // The comparison samplers are bound filtering linearly (a soft shadow's map). OpenGL filters a
  // depth texture itself; lavapipe cannot, so the vk flavour's code filters its 2D comparison
  // reads itself (BindingInterface::Texture::filtered_in_shader).
  bool filter_comparisons = false;
  // Values of the module's specialization constants by constant_id: written into the GLSL on gl,
  // given to the pipeline on vk and vk-hlsl.
  std::map<uint32_t, double> specialization = {};
  // gl: check the text with glslang as OpenGL GLSL 4.50 core before handing it on, as `xshade
  // compile` does (a driver that compiles it anyway need not wait for this).
  bool check_gl = false;
};

struct GeneratedStage {
  std::string glsl;             // gl, vk
  std::vector<uint32_t> spirv;  // spirv, vk-hlsl; vk too, the module it was checked by
  std::string entry_point = "main";
  std::string name;  // in diagnostics: "toon.hlsl.vert"
  // `#line L N` in the GLSL names source string N: entry N is the author's file (0 the text itself).
  std::vector<std::string> source_files;
};

// The module's resources as the generated code declares them: each with its HLSL name, the name
// the code gives it where an API binds it by name (OpenGL), and where it is bound. Only the
// resources an entry point reaches are listed, except constant buffers, which are all declared.
struct BindingInterface {
  struct UniformBlock {
    std::string name;       // as the shader declares it ("$Globals" for loose globals)
    std::string code_name;  // the block's name in the code (gl: "xs_Globals")
    uint32_t binding = 0;
    uint32_t size = 0;
    bool push_constant = false;  // Vulkan's push constants (gl reads it as a uniform block)
  };
  struct Texture {
    std::string name;
    std::string code_name;  // the sampler uniform's name (gl renames what GLSL reserves)
    uint32_t binding = 0;
    // Vulkan: the separate sampler's binding; absent for a sampled image without one or for an
    // image and sampler at one binding (a combined image sampler).
    std::optional<uint32_t> sampler_binding;
    bool image_only = false;          // Vulkan: a sampled image without a sampler
    bool filtered_in_shader = false;  // a 2D comparison the code filters (GenerateOptions::filter_comparisons)
    hlsl::TextureShape shape = hlsl::TextureShape::Tex2D;
    hlsl::ScalarType texel = hlsl::ScalarType::Float;
    bool comparison = false;
  };
  struct StorageBuffer {
    std::string name;
    std::string code_name;  // the storage block's name in the code
    uint32_t binding = 0;
  };
  std::vector<UniformBlock> uniform_blocks;
  std::vector<Texture> textures;
  std::vector<StorageBuffer> storage_buffers;
};

struct Generated {
  std::optional<GeneratedStage> vertex;    // absent when the module has no vertex entry point
  std::optional<GeneratedStage> fragment;  // absent when the module has no fragment entry point
  BindingInterface interface;
  glsl::NonfiniteTrace trace;  // with GenerateOptions::trace_nonfinite: the fragment stage's sites
};

// The module (compiled without errors) for the target, every stage validated as the target's
// description says. Neither stage when the module has no entry point.
Result<Generated> generate(const hlsl::Module& module, Target target, const GenerateOptions& options = {});

// The full-screen triangle (glsl::fullscreen_vertex_shader) feeding `reflection`'s varyings, for
// the target: its GLSL for gl and vk, SPIR-V for spirv and vk-hlsl.
Result<GeneratedStage> fullscreen_vertex(Target target, const hlsl::Reflection& reflection);

// The lines of `text` with their numbers, "  12 | text", from `first` to `last` (1-based, both
// included, clamped to the text); a '>' before the number of each line in `marked`.
std::string numbered_lines(std::string_view text, uint32_t first, uint32_t last,
                           const std::vector<uint32_t>& marked = {});

}  // namespace xshade::codegen
