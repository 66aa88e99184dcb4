#include "spirv/hlsl_compiler.h"

#include <glslang/MachineIndependent/iomapper.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "base/spirv_words.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/reflection.h"
#include "hlsl_like/semantics.h"
#include "spirv/glslang_log.h"
#include "spirv/glslang_process.h"

namespace xshade::spirv {
namespace {

// Unity's `#include_with_pragmas` is an #include whose file's Unity pragmas apply to the
// program; glslang's preprocessor knows no such directive, and reads no Unity pragma either, so
// to glslang it is an #include, spelt so (padded to the same width, so columns stay right).
std::string as_glslang_reads(std::string text) {
  constexpr std::string_view kUnity = "include_with_pragmas";
  size_t line = 0;
  while (line < text.size()) {
    size_t at = text.find_first_not_of(" \t", line);
    if (at != std::string::npos && text[at] == '#') {
      at = text.find_first_not_of(" \t", at + 1);
      const size_t after = at == std::string::npos ? at : at + kUnity.size();
      if (at != std::string::npos && text.compare(at, kUnity.size(), kUnity) == 0 &&
          (after >= text.size() || !(std::isalnum(static_cast<unsigned char>(text[after])) || text[after] == '_')))
        text.replace(at, kUnity.size(), "include             ");
    }
    const size_t end = text.find('\n', line);
    if (end == std::string::npos) break;
    line = end + 1;
  }
  return text;
}

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
    auto* text = new std::string(as_glslang_reads(std::move(file->text)));
    return new IncludeResult(file->name, text->data(), text->size(), text);
  }

  const IncludeResolver& resolve_;
};

EShLanguage to_glslang(Stage stage) { return stage == Stage::Vertex ? EShLangVertex : EShLangFragment; }

// Bindings exactly as glslang's own HLSL resolver gives them (register plus the class's shift, or
// the lowest free slot for a live resource without one), but stage variables placed by their
// semantics under xshade's interface contract (reflection.h): vertex inputs where the one vertex
// format has them, varyings where the other lanes put them. glslang alone would number both in
// declaration order, and a mesh would feed the wrong attributes.
class SemanticIoResolver final : public glslang::TDefaultIoResolverBase {
 public:
  SemanticIoResolver(const glslang::TIntermediate& intermediate, const std::map<std::string, uint32_t>& bindings,
                     const std::map<std::string, uint32_t>& varying_locations,
                     const std::map<std::string, uint32_t>& vertex_input_locations)
      : TDefaultIoResolverBase(intermediate),
        bindings_(bindings),
        varying_locations_(varying_locations),
        vertex_input_locations_(vertex_input_locations) {}

  bool validateBinding(EShLanguage, glslang::TVarEntryInfo&) override { return true; }

  glslang::TResourceType getResourceType(const glslang::TType& type) override {
    if (isUavType(type)) return glslang::EResUav;
    if (isSrvType(type)) return glslang::EResTexture;
    if (isSamplerType(type)) return glslang::EResSampler;
    if (isUboType(type)) return glslang::EResUbo;
    return glslang::EResCount;
  }

  int resolveBinding(EShLanguage stage, glslang::TVarEntryInfo& entry) override {
    const glslang::TType& type = entry.symbol->getType();
    const int set = getLayoutSet(type);
    const glslang::TResourceType resource = getResourceType(type);
    if (resource < glslang::EResCount) {
      const int base = getBaseBinding(stage, resource, static_cast<unsigned>(set));
      // A constant buffer is known by its block's name, any other resource by its variable's.
      const std::string name =
          type.getBasicType() == glslang::EbtBlock ? type.getTypeName().c_str() : entry.symbol->getName().c_str();
      // Dead ones too: glslang keeps a global texture or sampler the stage never reads in the
      // module (a vertex stage declares the fragment stage's textures), and the backend checks
      // every binding a module declares against the program's layout. The reflection's number
      // comes first: it is a register's shifted as glslang shifts it, and [[vk::binding(N)]]'s N
      // itself, which glslang would shift too (DXC does not).
      if (auto given = bindings_.find(name); given != bindings_.end())
        return entry.newBinding = reserveSlot(set, int(given->second));
      if (type.getQualifier().hasBinding())
        return entry.newBinding = reserveSlot(set, base + int(type.getQualifier().layoutBinding));
      if (entry.live && doAutoBindingMapping()) return entry.newBinding = getFreeSlot(set, base);
    }
    return entry.newBinding = -1;
  }

  int resolveInOutLocation(EShLanguage stage, glslang::TVarEntryInfo& entry) override {
    const glslang::TQualifier& qualifier = entry.symbol->getType().getQualifier();
    if (qualifier.semanticName != nullptr) {  // glslang numbered them while parsing; the contract wins
      const std::string array_semantic = hlsl::canonical_semantic_name(qualifier.semanticName);
      std::string semantic = array_semantic;
      // glslang splits an array varying (float4 offsets[3] : TEXCOORD1) into one variable per
      // element, named <name>[k], each with the array's semantic; HLSL gives element k the
      // semantic's index + k, and the element the array's location + k times the locations an
      // element takes (a matrix takes several).
      std::optional<uint32_t> element;
      if (const std::string name = entry.symbol->getName().c_str(); name.size() > 3 && name.back() == ']') {
        const size_t open = name.rfind('[');
        const std::string digits = open == std::string::npos ? "" : name.substr(open + 1, name.size() - open - 2);
        hlsl::ParsedSemantic parsed = hlsl::parse_semantic(semantic);
        if (!digits.empty() && digits.size() < 6 && digits.find_first_not_of("0123456789") == std::string::npos &&
            parsed.kind != hlsl::SemanticKind::Unknown) {
          element = uint32_t(std::stoul(digits));
          parsed.index += *element;
          semantic = hlsl::canonical_semantic(parsed);
        }
      }
      std::optional<uint32_t> location;
      const bool input = qualifier.storage == glslang::EvqVaryingIn;
      if (stage == EShLangVertex && input) {
        if (auto placed = vertex_input_locations_.find(semantic); placed != vertex_input_locations_.end())
          location = placed->second;
        else
          location = hlsl::vertex_input_location(semantic);
      } else if (stage == EShLangVertex || input) {
        if (auto placed = varying_locations_.find(array_semantic); placed != varying_locations_.end())
          location = placed->second + element.value_or(0) * uint32_t(glslang::TIntermediate::computeTypeLocationSize(
                                                                entry.symbol->getType(), stage));
        else
          location = hlsl::varying_location(semantic);
      } else if (const hlsl::ParsedSemantic target = hlsl::parse_semantic(semantic);
                 target.kind == hlsl::SemanticKind::SvTarget || target.kind == hlsl::SemanticKind::Color) {
        // A pixel shader's SV_TargetN, or DX9's COLORN, is colour attachment N. glslang numbers
        // a COLOR output like any varying (location 4 for Unity Standard's fragForwardBase,
        // whose colour then went nowhere and the attachment kept whatever memory held).
        location = target.index;
      }
      if (location) return entry.newLocation = int(*location);
      // A variable of no semantic the program places (a vk::builtin field glslang also declares as
      // a varying): past every location xshade gives, where glslang's own count from 0 would
      // collide with them.
      if (!qualifier.builtIn) return entry.newLocation = int(kUnplacedLocations + unplaced_++);
    }
    return TDefaultIoResolverBase::resolveInOutLocation(stage, entry);
  }

 private:
  const std::map<std::string, uint32_t>& bindings_;
  const std::map<std::string, uint32_t>& varying_locations_;
  const std::map<std::string, uint32_t>& vertex_input_locations_;
  static constexpr uint32_t kUnplacedLocations = 24;  // above the vertex format's and the varyings' tables
  uint32_t unplaced_ = 0;
};

// Sets the Offset decoration of each member of the named structs (blocks) that `offsets` gives
// another offset; glslang names a block's struct type after the buffer ("$Global" for the globals).
void set_member_offsets(std::vector<uint32_t>& words,
                        const std::map<std::string, std::map<std::string, uint32_t>>& offsets) {
  constexpr uint32_t kOpName = 5, kOpMemberName = 6, kOpMemberDecorate = 72, kDecorationOffset = 35;
  std::map<uint32_t, std::string> names;
  std::map<std::pair<uint32_t, uint32_t>, std::string> member_names;
  for_each_instruction(words, [&](uint32_t opcode, uint32_t count, uint32_t* op) {
    if (opcode == kOpName && count >= 3) names[op[1]] = literal_string(&op[2], count - 2);
    if (opcode == kOpMemberName && count >= 4) member_names[{op[1], op[2]}] = literal_string(&op[3], count - 3);
  });
  for_each_instruction(words, [&](uint32_t opcode, uint32_t count, uint32_t* op) {
    if (opcode != kOpMemberDecorate || count < 5 || op[3] != kDecorationOffset) return;
    auto block = names.find(op[1]);
    auto member = member_names.find({op[1], op[2]});
    if (block == names.end() || member == member_names.end()) return;
    auto buffer = offsets.find(block->second);
    if (buffer == offsets.end()) return;
    if (auto offset = buffer->second.find(member->second); offset != buffer->second.end()) op[4] = offset->second;
  });
}

std::vector<HlslResource> reflect(glslang::TProgram& program) {
  std::vector<HlslResource> resources;
  program.buildReflection(EShReflectionSeparateBuffers | EShReflectionAllBlockVariables);
  for (int i = 0; i < program.getNumUniformBlocks(); ++i) {
    const glslang::TObjectReflection& block = program.getUniformBlock(i);
    const bool push_constant = block.getType() && block.getType()->getQualifier().isPushConstant();
    resources.push_back({HlslResource::Kind::ConstantBuffer, block.name, uint32_t(block.getBinding()),
                         uint32_t(block.size), push_constant});
  }
  for (int i = 0; i < program.getNumUniformVariables(); ++i) {
    const glslang::TObjectReflection& uniform = program.getUniform(i);
    const glslang::TType* type = uniform.getType();
    if (!type || type->getBasicType() != glslang::EbtSampler) continue;
    const glslang::TSampler& sampler = type->getSampler();
    HlslResource::Kind kind = sampler.isPureSampler() ? HlslResource::Kind::Sampler
                              : sampler.isCombined()  ? HlslResource::Kind::CombinedSampler
                                                      : HlslResource::Kind::Texture;
    resources.push_back({kind, uniform.name, uint32_t(uniform.getBinding()), 0});
  }
  return resources;
}

}  // namespace

Result<HlslModule> compile_hlsl(const HlslStage& request) {
  ensure_glslang_initialized();
  const EShLanguage language = to_glslang(request.stage);
  const std::string source = as_glslang_reads(std::string(request.source));
  const char* text = source.data();
  const int length = static_cast<int>(source.size());
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
  shader.setEnvTarget(glslang::EShTargetSpv,
                      request.storage_buffers ? glslang::EShTargetSpv_1_3 : glslang::EShTargetSpv_1_6);
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
    return fail(Error{
        "HLSL compilation failed (glslang)", {request.source_name, 0, 0}, parse_glslang_log(shader.getInfoLog())});
  }
  glslang::TProgram program;
  program.addShader(&shader);
  SemanticIoResolver resolver(*shader.getIntermediate(), request.bindings, request.varying_locations,
                              request.vertex_input_locations);
  if (!program.link(messages) || !program.mapIO(&resolver)) {
    return fail(
        Error{"HLSL link failed (glslang)", {request.source_name, 0, 0}, parse_glslang_log(program.getInfoLog())});
  }

  HlslModule result;
  result.resources = reflect(program);
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.validate = false;                      // validated below with the project's environment and messages
  options.disableOptimizer = !request.legalize;  // glslang legalizes HLSL when its optimizer runs
  glslang::GlslangToSpv(*program.getIntermediate(language), result.module.words, &logger, &options);
  set_member_offsets(result.module.words, request.member_offsets);
  if (auto valid = validate(result.module.words, request.source_name); !valid) return fail(valid.error());
  return result;
}

IncludeResolver include_resolver(std::vector<std::filesystem::path> include_dirs) {
  return [dirs = std::move(include_dirs)](std::string_view name, std::string_view includer,
                                          bool angled) -> std::optional<IncludedFile> {
    const std::optional<std::filesystem::path> found =
        hlsl::find_include(name, std::filesystem::path(includer), angled, dirs);
    if (!found) return std::nullopt;
    std::ifstream file(*found, std::ios::binary);
    if (!file) return std::nullopt;
    std::stringstream text;
    text << file.rdbuf();
    return IncludedFile{found->string(), text.str()};
  };
}

}  // namespace xshade::spirv
