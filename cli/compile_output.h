// What `xshade compile` writes for one compiled module and target: codegen::generate's stages,
// each validated before it leaves xshade (a refusal is xshade's bug, ErrorKind::Internal, exit 3;
// the author's own mistakes keep their kind, exit 2), with SPIR-V disassembled for the console.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "codegen/generate.h"
#include "hlsl_like/compiler.h"

namespace xshade::cli {

struct OutputOptions {
  codegen::Target target = codegen::Target::Vk;
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

// The module (which compiled without errors) for the target, as the lanes run it (spirv is the vk
// lane's, vk-hlsl the vk-hlsl lane's), gl's GLSL checked by glslang as OpenGL GLSL 4.50 core too.
// Neither stage when the module has no entry point.
Result<CompileOutput> compile_output(const hlsl::Module& module, const OutputOptions& options);

}  // namespace xshade::cli
