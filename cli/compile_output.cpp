#include "cli/compile_output.h"

#include <spirv-tools/libspirv.hpp>

namespace xshade::cli {
namespace {

std::string disassemble(const std::vector<uint32_t>& words) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  std::string text;
  tools.Disassemble(words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES | SPV_BINARY_TO_TEXT_OPTION_INDENT);
  return text;
}

}  // namespace

Result<CompileOutput> compile_output(const hlsl::Module& module, const OutputOptions& options) {
  auto generated = codegen::generate(
      module, options.target,
      {.half_emulation = options.half_emulation, .trace_nonfinite = options.trace_nonfinite, .check_gl = true});
  if (!generated) return fail(generated.error());
  CompileOutput output;
  for (auto [from, to] :
       {std::pair{&generated->vertex, &output.vertex}, std::pair{&generated->fragment, &output.fragment}}) {
    if (!*from) continue;
    OutputStage stage;
    if (codegen::makes_spirv(options.target)) {
      stage.text = disassemble((*from)->spirv);
      stage.words = std::move((*from)->spirv);
    } else {
      stage.text = std::move((*from)->glsl);
    }
    *to = std::move(stage);
  }
  return output;
}

}  // namespace xshade::cli
