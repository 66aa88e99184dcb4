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

EShLanguage to_glslang(Stage stage) { return stage == Stage::Vertex ? EShLangVertex : EShLangFragment; }

std::vector<Diagnostic> only(std::vector<Diagnostic> diagnostics, Severity severity) {
  std::erase_if(diagnostics, [&](const Diagnostic& d) { return d.severity != severity; });
  return diagnostics;
}

// The environments a GLSL text is checked in.
enum class Client { OpenGL, Vulkan };

// The message of validate()'s error: is_spirv_validation_failure() knows that error by it.
constexpr std::string_view kSpirvValidationFailed = "SPIR-V validation failed";

// One stage parsed and linked as a program of its own, the setup every GLSL check here shares.
// The program refers to the shader, so it is declared after it and destroyed before it.
struct LinkedStage {
  explicit LinkedStage(Stage stage) : shader(to_glslang(stage)) {}
  glslang::TShader shader;
  glslang::TProgram program;
};

EShMessages messages_for(Client client) {
  return client == Client::Vulkan ? static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules) : EShMsgDefault;
}

Result<void> parse_and_link(LinkedStage& linked, std::string_view source, Stage stage, const std::string& name,
                            Client client) {
  ensure_glslang_initialized();
  // The shader keeps pointers to these three until it is parsed, which happens below.
  const char* text = source.data();
  const int length = static_cast<int>(source.size());
  const char* names = name.c_str();

  glslang::TShader& shader = linked.shader;
  shader.setStringsWithLengthsAndNames(&text, &length, &names, 1);
  if (client == Client::Vulkan) {
    shader.setEnvInput(glslang::EShSourceGlsl, to_glslang(stage), glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
  } else {
    // No client, as glslangValidator checks a file without -V or -G: the text as an OpenGL driver
    // compiles it. glslang's OpenGL client is GLSL for SPIR-V (ARB_gl_spirv), whose extra rules
    // a driver reading text does not apply.
    shader.setEnvInput(glslang::EShSourceGlsl, to_glslang(stage), glslang::EShClientNone, 0);
  }
  // A text without #version is read as 4.50 core; the emitter always writes one.
  const EProfile profile = client == Client::Vulkan ? ENoProfile : ECoreProfile;
  if (!shader.parse(GetDefaultResources(), 450, profile, false, false, messages_for(client))) {
    Error error{"GLSL compilation failed", {name, 0, 0}, parse_glslang_log(shader.getInfoLog())};
    return fail(std::move(error));
  }
  linked.program.addShader(&shader);
  if (!linked.program.link(messages_for(client))) {
    Error error{"GLSL link failed", {name, 0, 0}, parse_glslang_log(linked.program.getInfoLog())};
    return fail(std::move(error));
  }
  return {};
}

}  // namespace

Result<std::vector<Diagnostic>> validate_opengl_glsl(std::string_view source, Stage stage,
                                                     std::string_view source_name) {
  LinkedStage linked(stage);
  if (auto valid = parse_and_link(linked, source, stage, std::string(source_name), Client::OpenGL); !valid)
    return fail(valid.error());
  return only(parse_glslang_log(linked.shader.getInfoLog()), Severity::Warning);
}

Result<SpirvModule> compile_vulkan_glsl(std::string_view source, Stage stage, std::string_view source_name) {
  const std::string name(source_name);
  LinkedStage linked(stage);
  if (auto valid = parse_and_link(linked, source, stage, name, Client::Vulkan); !valid) return fail(valid.error());

  SpirvModule module;
  module.warnings = only(parse_glslang_log(linked.shader.getInfoLog()), Severity::Warning);
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.validate = false;  // validated below with the project's own environment and messages
  glslang::GlslangToSpv(*linked.program.getIntermediate(to_glslang(stage)), module.words, &logger, &options);
  if (std::string log = logger.getAllMessages(); !log.empty())
    module.warnings.push_back({Severity::Warning, {name, 0, 0}, log});

  if (auto valid = validate(module.words, name); !valid) return fail(valid.error());
  return module;
}

Result<void> validate(const std::vector<uint32_t>& words, std::string_view module_name) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_3);
  Error error{std::string(kSpirvValidationFailed), {std::string(module_name), 0, 0}, {}};
  tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t& position, const char* message) {
    error.diagnostics.push_back({Severity::Error,
                                 {std::string(module_name), 0, 0},
                                 "instruction " + std::to_string(position.index) + ": " + message});
  });
  if (!tools.Validate(words)) return fail(std::move(error));
  return {};
}

bool is_spirv_validation_failure(const Error& error) { return error.message == kSpirvValidationFailed; }

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
