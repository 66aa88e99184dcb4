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

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "glsl/flavour.h"
#include "hlsl_like/compiler.h"

namespace xshade::glsl {

struct EmitOptions {
  Flavour flavour = Flavour::Gl;
  // Half-precision emulation: every half-, min16float- or fixed-typed result (arithmetic,
  // literals, calls, conversions from float) is rounded to fp16 and back, so that fp16 hazards
  // (overflow to infinity past 65504, 11-bit significands) show on drivers that compute half in
  // fp32. Values read from constant buffers stay as stored; half matrices are not rounded.
  bool half_emulation = false;
  // The tracing variant (fragment stage): every float-typed assignment, initialisation, return
  // value and call result is tested for NaN and infinity (and the colour outputs for negative
  // components too); the first site that fails in an invocation is written, with the calls that
  // led to it, to fragment output location 1 (see NonfiniteTrace). The values computed are the
  // untraced variant's: each test reads a value and returns it unchanged.
  bool trace_nonfinite = false;
  // The traced program's number (below 256), the high bits of its sites' numbers, so that the
  // record of a target several programs drew into says which program's site it is.
  uint32_t trace_program = 0;
  // Comparison reads of a 2D texture (SampleCmp, SampleCmpLevelZero) filter in the shader: the
  // four nearest comparisons (textureGather with the reference) weighted bilinearly, which is
  // what a linear comparison sampler computes (a soft shadow's 2x2 PCF). For a driver that
  // cannot filter a depth texture (lavapipe has no linear filtering of any depth format); the
  // sampler bound is then read nearest (glsl::filters_comparisons_in_shader).
  bool filter_comparisons = false;
  // Specialization constants' values by constant_id ([[vk::constant_id(N)]]), each in its
  // constant's scalar type (finite; whole for an int, uint or bool). The gl flavour writes the
  // value where the constant is declared (GLSL for OpenGL has no specialization); the vk flavour
  // keeps the default, which the pipeline's specialization replaces.
  std::map<uint32_t, double> specialization = {};
};

// A place in the author's source the tracing variant tests.
struct TraceSite {
  enum class Kind {
    Initialization,      // `float x = value;`
    Assignment,          // `x = value`
    CompoundAssignment,  // `x += value`, ...
    Return,              // `return value;`
    Call,                // the result of a call: the author's function, an intrinsic, a texture read
    Input,               // a fragment input that arrived non-finite from the vertex stage
    Output,              // the entry point's colour output (nothing earlier failed)
    NegativeOutput,      // a colour output component below zero (tested at the output only)
  };
  Kind kind = Kind::Assignment;
  std::string file;         // the source file's name, as messages call it
  uint32_t line = 0;        // 1-based; 0 for generated code
  uint32_t column = 0;      // 1-based
  std::string source_line;  // the text of that line
  std::string function;     // the function it is in ("main" for the generated entry code)
  // What the site names: the place assigned or initialised ("D", "color.rgb"), the function
  // returning, the intrinsic called ("pow"), the input's or output's semantic ("TEXCOORD0").
  std::string what;
};
const char* trace_site_kind_name(TraceSite::Kind kind);
// "the value D_GGX returns", "the result of pow", "input TEXCOORD0 as it arrived from the vertex stage".
std::string describe_site(const TraceSite& site);

// A call of one of the author's functions, by which a traced site names its callers.
struct TraceCall {
  std::string callee;
  std::string caller;
  std::string file;
  uint32_t line = 0;
  uint32_t column = 0;
  std::string source_line;
};

// What a traced fragment stage records per pixel, in the four channels of location 1, as whole
// numbers (exact in a float target below 2^24): R the first site that failed, as
// EmitOptions::trace_program * 65536 + 1 + an index into `sites` (0 where none did); G, B and A
// the calls that led there, innermost first (1 + an index into `calls`; 0 past the outermost).
// Calls more than kRecordedCalls deep are not recorded.
struct NonfiniteTrace {
  std::vector<TraceSite> sites;
  std::vector<TraceCall> calls;
  static constexpr uint32_t kRecordedCalls = 3;
  static constexpr uint32_t kMaxCalls = 1023;    // a call's number takes 10 bits of the path
  static constexpr uint32_t kMaxSites = 65535;   // a site's number the low 16 bits of R
  static constexpr uint32_t kMaxPrograms = 256;  // so that R stays below 2^24

  // The program and the site a recorded R names; `site_in` null where R names none of the sites
  // this table has (0: nothing failed).
  static uint32_t program_in(uint32_t recorded) { return recorded >> 16; }
  const TraceSite* site_in(uint32_t recorded) const {
    const uint32_t site = recorded & 0xFFFFu;
    return site == 0 || site > sites.size() ? nullptr : &sites[site - 1];
  }
};

struct EmittedStage {
  std::string text;  // a complete GLSL shader
};

// The names the GLSL gives what an OpenGL program binds by name, by their HLSL names: each constant
// buffer's block ("$Globals" is "xs_Globals"), each texture's sampler uniform (renamed where GLSL
// reserves the HLSL name) and each read-only buffer's storage block.
struct DeclaredNames {
  std::map<std::string, std::string> blocks;
  std::map<std::string, std::string> textures;
  std::map<std::string, std::string> storage_blocks;
};

struct EmittedProgram {
  std::optional<EmittedStage> vertex;    // absent when the module has no vertex entry point
  std::optional<EmittedStage> fragment;  // absent when the module has no fragment entry point
  // Index i is the source-string number N that `#line L N` uses (the front end's file indices,
  // N >= 1); index 0 is the generated text itself.
  std::vector<std::string> source_files;
  // With EmitOptions::trace_nonfinite: the fragment stage's sites and calls.
  NonfiniteTrace trace;
  DeclaredNames names;
};

// The module must have compiled without errors. Fails, with the location of the construct, on
// what the flavour cannot express; the error's to_string() is that diagnostic as the front end
// renders it ("file:line:col: error: message", the source line and a caret), its message the
// same without the location.
Result<EmittedProgram> emit(const hlsl::Module& module, const EmitOptions& options);

// The GLSL name of a constant buffer's block, by which the harness binds uniform blocks on
// OpenGL: "$Globals" -> "xs_Globals"; other names unchanged unless GLSL reserves them.
std::string block_name(std::string_view constant_buffer_name);
// The GLSL name of a read-only buffer's storage block (hlsl::StorageBufferResource), which an
// OpenGL program lists among its storage blocks.
std::string buffer_block_name(std::string_view buffer_name);
// The GLSL instance name of a `ConstantBuffer<S> name` block, through which name.field is read.
std::string constant_buffer_instance(std::string_view variable_name);

}  // namespace xshade::glsl
