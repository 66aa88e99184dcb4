// What `xshade compile` writes for one compiled module and target, and the check that none of it
// is invalid: every stage passes its validator before it leaves xshade.
//
// The validators judge xshade's own output (GLSL it generated, SPIR-V it had made), so a refusal
// is xshade's bug, never the shader author's: such an error has ErrorKind::Internal (exit 3) and
// carries what a bug report needs, the validator's messages and the generated lines they name.
// The author's own mistakes (a construct the target cannot express) keep their kind (exit 2).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "hlsl_like/compiler.h"
#include "spirv/spirv_compiler.h"

namespace xshade::cli {

// The targets of `xshade compile --target` (main.cpp accepts only these names).
enum class Target { Gl, Vk, Spirv, VkHlsl };
Target target_named(std::string_view name);  // "gl", "vk", "spirv" or "vk-hlsl"

struct OutputOptions {
  Target target = Target::Vk;
  bool half_emulation = false;
  bool trace_nonfinite = false;
};

// One stage of the output: GLSL (gl, vk) or a SPIR-V module with its disassembly (spirv, vk-hlsl).
struct OutputStage {
  std::string text;
  std::vector<uint32_t> words;  // empty for the GLSL targets
};

struct CompileOutput {
  std::optional<OutputStage> vertex;    // absent when the module has no vertex entry point
  std::optional<OutputStage> fragment;  // absent when the module has no fragment entry point
};

// The module (which compiled without errors) for the target, each stage validated: gl's GLSL by
// glslang as OpenGL GLSL 4.50 core, vk's as Vulkan GLSL (compiled and its SPIR-V through
// spirv-val), spirv's and vk-hlsl's SPIR-V by spirv-val. spirv and vk-hlsl are the programs the vk
// and vk-hlsl lanes run. Neither stage when the module has no entry point.
Result<CompileOutput> compile_output(const hlsl::Module& module, const OutputOptions& options);

// The validator's verdict on one stage of GLSL xshade generated for a GLSL target (gl, or vk and
// spirv, whose GLSL is compiled to SPIR-V): the SPIR-V for vk and spirv, none for gl; or the
// Internal error that reports the refusal. `name` names the stage ("toon.hlsl.vert");
// `source_files` are the emitter's (glsl::EmittedProgram::source_files), which name the author's
// files that the text's #line directives number.
Result<std::vector<uint32_t>> validate_generated_glsl(Target target, spirv::Stage stage, std::string_view text,
                                                      std::string_view name,
                                                      const std::vector<std::string>& source_files);

// The lines of `text` with their numbers, "  12 | text", from `first` to `last` (1-based, both
// included, clamped to the text); a '>' before the number of each line in `marked`.
std::string numbered_lines(std::string_view text, uint32_t first, uint32_t last,
                           const std::vector<uint32_t>& marked = {});

}  // namespace xshade::cli
