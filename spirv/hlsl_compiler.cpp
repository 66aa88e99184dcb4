#include "spirv/hlsl_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include "spirv/glslang_log.h"
#include "spirv/glslang_process.h"

namespace xshade::spirv {
namespace {

// glslang asks for each #include through this; the resolver decides where files come from.
class Includer final : public glslang::TShader::Includer {
 public:
  explicit Includer(const IncludeResolver& resolve) : resolve_(resolve) {}

  IncludeResult* includeLocal(const char* name, const char* includer, size_t) override {
    return include(name, includer, false);
  }
  IncludeResult* includeSystem(const char* name, const char* includer, size_t) override {
    return include(name, includer, true);
  }
  void releaseInclude(IncludeResult* result) override {
    if (!result) return;
    delete static_cast<std::string*>(result->userData);
    delete result;
  }

 private:
  IncludeResult* include(const char* name, const char* includer, bool angled) {
    if (!resolve_) return nullptr;
    std::optional<IncludedFile> file = resolve_(name, includer ? includer : "", angled);
    if (!file) return nullptr;
    auto* text = new std::string(std::move(file->text));
    return new IncludeResult(file->name, text->data(), text->size(), text);
  }

  const IncludeResolver& resolve_;
};

EShLanguage to_glslang(Stage stage) { return stage == Stage::Vertex ? EShLangVertex : EShLangFragment; }

std::vector<HlslResource> reflect(glslang::TProgram& program) {
  std::vector<HlslResource> resources;
  program.buildReflection(EShReflectionSeparateBuffers | EShReflectionAllBlockVariables);
  for (int i = 0; i < program.getNumUniformBlocks(); ++i) {
    const glslang::TObjectReflection& block = program.getUniformBlock(i);
    resources.push_back({HlslResource::Kind::ConstantBuffer, block.name, uint32_t(block.getBinding()),
                         uint32_t(block.size)});
  }
  for (int i = 0; i < program.getNumUniformVariables(); ++i) {
    const glslang::TObjectReflection& uniform = program.getUniform(i);
    const glslang::TType* type = uniform.getType();
    if (!type || type->getBasicType() != glslang::EbtSampler) continue;
    const glslang::TSampler& sampler = type->getSampler();
    HlslResource::Kind kind = sampler.isPureSampler() ? HlslResource::Kind::Sampler
                              : sampler.isCombined() ? HlslResource::Kind::CombinedSampler
                                                     : HlslResource::Kind::Texture;
    resources.push_back({kind, uniform.name, uint32_t(uniform.getBinding()), 0});
  }
  return resources;
}

}  // namespace

Result<HlslModule> compile_hlsl(const HlslStage& request) {
  ensure_glslang_initialized();
  const EShLanguage language = to_glslang(request.stage);
  const char* text = request.source.data();
  const int length = static_cast<int>(request.source.size());
  const char* name = request.source_name.c_str();

  std::string preamble;
  for (const auto& [key, value] : request.defines) preamble += "#define " + key + " " + value + "\n";

  glslang::TShader shader(language);
  shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEntryPoint(request.entry_point.c_str());
  shader.setSourceEntryPoint(request.entry_point.c_str());
  shader.setEnvInput(glslang::EShSourceHlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
  shader.setShiftBinding(glslang::EResUbo, request.shifts.constant_buffer);
  shader.setShiftBinding(glslang::EResTexture, request.shifts.texture);
  shader.setShiftBinding(glslang::EResSampler, request.shifts.sampler);
  shader.setAutoMapBindings(true);
  shader.setAutoMapLocations(true);
  shader.setHlslIoMapping(true);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgReadHlsl |
                                                 EShMsgHlslDX9Compatible | EShMsgHlslOffsets);

  Includer includer(request.resolve_include);
  if (!shader.parse(GetDefaultResources(), 100, ENoProfile, false, false, messages, includer)) {
    return fail(Error{"HLSL compilation failed (glslang)", {request.source_name, 0, 0},
                      parse_glslang_log(shader.getInfoLog())});
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages) || !program.mapIO()) {
    return fail(Error{"HLSL link failed (glslang)", {request.source_name, 0, 0},
                      parse_glslang_log(program.getInfoLog())});
  }

  HlslModule result;
  result.resources = reflect(program);
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.validate = false;  // validated below with the project's environment and messages
  glslang::GlslangToSpv(*program.getIntermediate(language), result.module.words, &logger, &options);
  if (auto valid = validate(result.module.words, request.source_name); !valid) return fail(valid.error());
  return result;
}

}  // namespace xshade::spirv
