// A shader compiled by xshade's front end, made into a program for one lane's backend.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "codegen/generate.h"
#include "glsl/glsl_emitter.h"
#include "harness/backend/backend.h"
#include "harness/render/lanes.h"
#include "hlsl_like/compiler.h"

namespace xshade::harness {

// gl: the gl-flavoured GLSL; vk: the vk-flavoured GLSL through glslang to SPIR-V; vk-hlsl: the
// source itself through glslang's HLSL front end, with the variant's macros. The layout comes
// from xshade's reflection on every lane; on vk-hlsl, glslang's own reflection must agree with
// it binding for binding, or this fails naming the resource. A module without a vertex entry
// point is a full-screen pass: the shared full-screen vertex shader feeds its TEXCOORD0.
//
// With `half_emulation` the GLSL lanes round every half-typed result to fp16 (glsl::EmitOptions);
// the vk-hlsl lane compiles the source with glslang, which cannot, and fails saying so.
// The options a program's code is generated with.
using ProgramOptions = codegen::GenerateOptions;

// Half emulation also defines this macro for the front end, so that a shader can choose to
// compute in half where a GPU that prefers half would (the library's `real`, include/common.hlsl).
inline constexpr const char* kHalfEmulationMacro = "XSHADE_PRECISION_HALF";
// ProgramOptions::specialization from "NAME=VALUE" texts, each naming one of the reflection's
// specialization constants with a finite number (whole for an int or uint, 0 or 1 for a bool).
// Fails naming the first that is not, with the constants the shader has.
Result<std::map<uint32_t, double>> resolve_specialization(const std::vector<std::string>& given,
                                                          const hlsl::Reflection& reflection);

// A specialization constant's value of `scalar` as the 32-bit word Vulkan's specialization data
// holds (a bool a VkBool32); `value` is finite, and whole for an integer type.
uint32_t specialization_word(double value, hlsl::ScalarType scalar);

// With options.trace_nonfinite, `trace` receives the traced fragment stage's sites and calls.
Result<ProgramDesc> program_for_lane(const hlsl::Module& module, Lane lane, const ProgramOptions& options = {},
                                     glsl::NonfiniteTrace* trace = nullptr);

// The target whose code a lane runs: gl's GLSL, vk's SPIR-V from the vk GLSL, vk-hlsl's from glslang.
codegen::Target lane_target(Lane lane);

// A texture shape and texel type of the front end as the backends name them.
TextureShape harness_shape(hlsl::TextureShape shape);
TexelKind harness_texel(hlsl::ScalarType texel);

}  // namespace xshade::harness
