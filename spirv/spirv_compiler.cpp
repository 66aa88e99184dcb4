#include "spirv/spirv_compiler.h"

#include <mutex>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>

#include "spirv/glslang_log.h"
#include "spirv/glslang_process.h"

namespace xshade::spirv {
namespace {

EShLanguage to_glslang(Stage stage) {
  return stage == Stage::Vertex ? EShLangVertex : EShLangFragment;
}

std::vector<Diagnostic> only(std::vector<Diagnostic> diagnostics, Severity severity) {
  std::erase_if(diagnostics, [&](const Diagnostic& d) { return d.severity != severity; });
  return diagnostics;
}

}  // namespace

Result<SpirvModule> compile_vulkan_glsl(std::string_view source, Stage stage,
                                        std::string_view source_name) {
  ensure_glslang_initialized();
  const std::string name(source_name);
  const char* text = source.data();
  const int length = static_cast<int>(source.size());
  const char* names = name.c_str();

  glslang::TShader shader(to_glslang(stage));
  shader.setStringsWithLengthsAndNames(&text, &length, &names, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, to_glslang(stage), glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);

  if (!shader.parse(GetDefaultResources(), 450, ENoProfile, false, false, messages)) {
    Error error{"GLSL compilation failed", {name, 0, 0}, parse_glslang_log(shader.getInfoLog())};
    return fail(std::move(error));
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    Error error{"GLSL link failed", {name, 0, 0}, parse_glslang_log(program.getInfoLog())};
    return fail(std::move(error));
  }

  SpirvModule module;
  module.warnings = only(parse_glslang_log(shader.getInfoLog()), Severity::Warning);
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.validate = false;  // validated below with the project's own environment and messages
  glslang::GlslangToSpv(*program.getIntermediate(to_glslang(stage)), module.words, &logger,
                        &options);
  if (std::string log = logger.getAllMessages(); !log.empty())
    module.warnings.push_back({Severity::Warning, {name, 0, 0}, log});

  if (auto valid = validate(module.words, name); !valid) return fail(valid.error());
  return module;
}

Result<void> validate(const std::vector<uint32_t>& words, std::string_view module_name) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  Error error{"SPIR-V validation failed", {std::string(module_name), 0, 0}, {}};
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& position,
                               const char* message) {
    error.diagnostics.push_back({Severity::Error,
                                 {std::string(module_name), 0, 0},
                                 "instruction " + std::to_string(position.index) + ": " + message});
  });
  if (!tools.Validate(words)) return fail(std::move(error));
  return {};
}

std::string compiler_version() {
  const glslang::Version version = glslang::GetVersion();
  return "glslang " + std::to_string(version.major) + "." + std::to_string(version.minor) + "." +
         std::to_string(version.patch);
}

void ensure_glslang_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

}  // namespace xshade::spirv
