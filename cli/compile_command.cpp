// xshade compile: one shader through the front end to GLSL, SPIR-V or reflection.
#include <fmt/core.h>

#include <fstream>

#include <spirv-tools/libspirv.hpp>

#include "glsl/glsl_emitter.h"
#include "cli/commands.h"
#include "harness/render/shader_program.h"
#include "hlsl_like/compiler.h"

namespace xshade::cli {
namespace {

bool write_file(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), std::streamsize(bytes.size()));
  return bool(file);
}

std::string disassemble(const std::vector<uint32_t>& words) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  std::string text;
  tools.Disassemble(words, &text, SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES | SPV_BINARY_TO_TEXT_OPTION_INDENT);
  return text;
}

// Writes one stage's output to OUT.<stage><extension>, or to stdout under a header.
bool emit_stage(const CompileOptions& options, const char* stage, std::string_view text, bool binary,
                std::string_view binary_bytes = {}) {
  if (options.output.empty()) {
    fmt::print("// ---- {} ----\n{}", stage, text);
    return true;
  }
  const std::string extension = std::string(".") + stage + (binary ? ".spv" : ".glsl");
  const std::filesystem::path path = options.output.string() + extension;
  if (!write_file(path, binary ? binary_bytes : text)) {
    fmt::print(stderr, "xshade compile: cannot write {}\n", path.string());
    return false;
  }
  return true;
}

}  // namespace

int run_compile(const CompileOptions& options) {
  hlsl::CompileOptions front_end;
  front_end.include_dirs = include_folders(options.include_dirs);
  if (options.precision == "half") front_end.defines.push_back({harness::kHalfEmulationMacro, "1"});
  for (const std::string& define : options.defines) {
    const size_t equals = define.find('=');
    if (equals == std::string::npos) front_end.keywords.push_back(define);
    else front_end.defines.push_back({define.substr(0, equals), define.substr(equals + 1)});
  }
  auto module = hlsl::compile_file(options.file, front_end);
  if (!module->diagnostics.diagnostics().empty()) fmt::print(stderr, "{}", module->diagnostics.render_all());
  if (!module->ok()) return kBadInput;

  if (options.reflect) {
    const std::string json = hlsl::reflection_json(module->reflection) + "\n";
    if (options.output.empty()) fmt::print("{}", json);
    else if (!write_file(options.output.string() + ".json", json)) return kBackendError;
    return kPass;
  }

  if (options.target == "gl" || options.target == "vk") {
    auto emitted = glsl::emit(*module, {options.target == "gl" ? glsl::Flavour::Gl : glsl::Flavour::Vk,
                                        options.precision == "half"});
    if (!emitted) {
      fmt::print(stderr, "{}\n", emitted.error().to_string());
      return kBadInput;
    }
    if (emitted->vertex && !emit_stage(options, "vert", emitted->vertex->text, false)) return kBackendError;
    if (emitted->fragment && !emit_stage(options, "frag", emitted->fragment->text, false)) return kBackendError;
    return kPass;
  }

  // spirv and vk-hlsl: the program as the vk or vk-hlsl lane would run it.
  const harness::Lane lane = options.target == "spirv" ? harness::Lane::Vk : harness::Lane::VkHlsl;
  auto stages = harness::stages_for_lane(*module, lane, {.half_emulation = options.precision == "half"});
  if (!stages) {
    fmt::print(stderr, "{}\n", stages.error().to_string());
    return kBadInput;
  }
  for (const auto& [stage, source] : {std::pair{"vert", &stages->vertex}, std::pair{"frag", &stages->fragment}}) {
    if (!*source) continue;
    const std::vector<uint32_t>& words = (*source)->spirv;
    const std::string_view bytes(reinterpret_cast<const char*>(words.data()), words.size() * 4);
    if (!emit_stage(options, stage, disassemble(words), !options.output.empty(), bytes)) return kBackendError;
  }
  return kPass;
}

}  // namespace xshade::cli
