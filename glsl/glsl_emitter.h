// The GLSL emitter: an analysed hlsl_like module as GLSL 4.50, in the `gl` flavour (OpenGL
// through OSMesa) or the `vk` flavour (Vulkan GLSL for glslang), computing what HLSL computes.
//
// The conventions every emitted shader follows (see docs/architecture.md):
// - HLSL's floatRxC matrix M is held as its transpose G = M^T, a GLSL matR x C: M[i] is G[i],
//   constructors keep their argument order, mul(v, M) is G * v and mul(M, v) is v * G;
// - constant buffers are std140 blocks with HLSL's offsets (reflection.h), and column_major HLSL
//   matrices are row_major GLSL ones;
// - stage variables are xs_in_<SEMANTIC> (vertex inputs), xs_v_<SEMANTIC> (varyings) and
//   xs_target<N> (fragment outputs), at the locations reflection assigned;
// - the author's names are kept unless GLSL reserves them (glsl_names.h);
// - `#line L N` directives point the driver's messages at the author's file N, line L.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "glsl/flavour.h"
#include "hlsl_like/compiler.h"
#include "base/result.h"

namespace xshade::glsl {

struct EmitOptions {
  Flavour flavour = Flavour::Gl;
  // Half-precision emulation: every half-, min16float- or fixed-typed result (arithmetic,
  // literals, calls, conversions from float) is rounded to fp16 and back, so that fp16 hazards
  // (overflow to infinity past 65504, 11-bit significands) show on drivers that compute half in
  // fp32. Values read from constant buffers stay as stored; half matrices are not rounded.
  bool half_emulation = false;
};

struct EmittedStage {
  std::string text;  // a complete GLSL shader
};

struct EmittedProgram {
  std::optional<EmittedStage> vertex;    // absent when the module has no vertex entry point
  std::optional<EmittedStage> fragment;  // absent when the module has no fragment entry point
  // Index i is the source-string number N that `#line L N` uses (the front end's file indices,
  // N >= 1); index 0 is the generated text itself.
  std::vector<std::string> source_files;
};

// The module must have compiled without errors. Fails, with the location of the construct, on
// what the flavour cannot express; the error's to_string() is that diagnostic as the front end
// renders it ("file:line:col: error: message", the source line and a caret), its message the
// same without the location.
Result<EmittedProgram> emit(const hlsl::Module& module, const EmitOptions& options);

// The GLSL name of a constant buffer's block, by which the harness binds uniform blocks on
// OpenGL: "$Globals" -> "xs_Globals"; other names unchanged unless GLSL reserves them.
std::string block_name(std::string_view constant_buffer_name);
// The GLSL instance name of a `ConstantBuffer<S> name` block, through which name.field is read.
std::string constant_buffer_instance(std::string_view variable_name);

}  // namespace xshade::glsl
