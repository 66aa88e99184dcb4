// Vulkan GLSL -> SPIR-V in-process through glslang, and validation of every module by SPIRV-Tools.
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
Result<SpirvModule> compile_vulkan_glsl(std::string_view source, Stage stage,
                                        std::string_view source_name);

// spirv-val for the Vulkan 1.3 environment; the error lists the validator's messages.
Result<void> validate(const std::vector<uint32_t>& words, std::string_view module_name);

// "glslang 12.0.0", for reports and cache keys.
std::string compiler_version();

}  // namespace xshade::spirv
