// Vulkan GLSL -> SPIR-V in-process through glslang, validation of every module by SPIRV-Tools, and
// glslang's check of OpenGL GLSL (the gl lane's drivers compile the text themselves).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"

namespace xshade::spirv {

enum class Stage { Vertex, Fragment };

struct SpirvModule {
  std::vector<uint32_t> words;
  std::vector<Diagnostic> warnings;  // what the compiler warned about; empty when clean
};

// Compiles Vulkan-flavoured GLSL (#version 450, targeting Vulkan 1.3 / SPIR-V 1.6) and validates
// the result. On failure the error's diagnostics carry `source_name` and the line of each problem.
Result<SpirvModule> compile_vulkan_glsl(std::string_view source, Stage stage, std::string_view source_name);

// Checks OpenGL GLSL (#version 450 core) as glslang does without a SPIR-V target, the stage parsed
// and linked on its own: what the GLSL specification has an OpenGL driver refuse, as far as
// glslang knows it (glslangValidator FILE gives the same verdict). Returns glslang's warnings. On
// failure the error's diagnostics carry `source_name`, or the source string a #line names
// ("1"), and the line of each problem.
Result<std::vector<Diagnostic>> validate_opengl_glsl(std::string_view source, Stage stage,
                                                     std::string_view source_name);

// spirv-val for the Vulkan 1.3 environment; the error lists the validator's messages.
Result<void> validate(const std::vector<uint32_t>& words, std::string_view module_name);

// Whether `error` is validate()'s, passed on unchanged (compile_vulkan_glsl's and compile_hlsl's
// are): spirv-val refused a module the compiler made, rather than the compiler its source. Whose
// fault that is only the caller knows, so the error's kind says nothing of it.
bool is_spirv_validation_failure(const Error& error);

// "glslang 12.0.0", for reports and cache keys.
std::string compiler_version();

}  // namespace xshade::spirv
