// The generator's parts, shared by its files and their tests.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "codegen/generate.h"
#include "hlsl_like/compiler.h"
#include "spirv/spirv_compiler.h"

namespace xshade::codegen {

// The validator's verdict on one stage of GLSL xshade generated for a GLSL target (gl, or vk and
// spirv, whose GLSL is compiled to SPIR-V): the SPIR-V for vk and spirv, none for gl; or the
// Internal error that reports the refusal. `name` names the stage ("toon.hlsl.vert");
// `source_files` are the emitter's (glsl::EmittedProgram::source_files), which name the author's
// files that the text's #line directives number.
Result<std::vector<uint32_t>> validate_generated_glsl(Target target, spirv::Stage stage, std::string_view text,
                                                      std::string_view name,
                                                      const std::vector<std::string>& source_files);

// One stage of the vk-hlsl target: the module's source through glslang's HLSL front end, its
// resources bound where xshade's reflection puts them (and checked to be there).
Result<GeneratedStage> vk_hlsl_stage(const hlsl::Module& module, spirv::Stage stage, const std::string& entry);

}  // namespace xshade::codegen
