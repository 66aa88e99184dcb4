#include "shaderlab/pass_program.h"

#include <algorithm>
#include <charconv>

#include "shaderlab/compile_environment.h"

namespace xshade::shaderlab {
namespace {

std::string pass_label(const Pass& pass, size_t index) {
  return std::to_string(index) + (pass.name.empty() ? "" : " (\"" + pass.name + "\")");
}

}  // namespace

void append_block(std::string& text, const ProgramBlock& block, std::optional<std::string_view> body) {
  text += "#line " + std::to_string(block.start.line) + " \"" + block.start.file + "\"\n";
  text.append(block.start.column > 0 ? block.start.column - 1 : 0, ' ');
  text += body ? *body : std::string_view(block.text);
  text += '\n';
}

const SubShader* drawn_subshader(const Shader& shader, UnityPlatform platform) {
  for (const SubShader& sub : shader.subshaders) {
    const bool runs = std::all_of(sub.passes.begin(), sub.passes.end(), [&](const Pass& pass) {
      if (pass.kind != PassKind::Program) return true;
      auto program = pass_program(sub, pass);
      return !program || compiles_for_platform(program->text, platform);
    });
    if (runs) return &sub;
  }
  return nullptr;
}

std::string without_subshader(const Shader& shader, UnityPlatform platform) {
  return shader.subshaders.empty()
             ? "has no SubShader"
             : "has no SubShader that Unity compiles for " + std::string(renderer_name(platform)) +
                   " (#pragma only_renderers or exclude_renderers keeps each out)";
}

Result<const Pass*> find_pass(const Shader& shader, const std::string& choice, UnityPlatform platform) {
  const SubShader* sub = drawn_subshader(shader, platform);
  if (!sub)
    return fail(ErrorKind::UserInput, "the shader '" + shader.name + "' " + without_subshader(shader, platform));
  return find_pass_in(*sub, shader.name, choice);
}

Result<const Pass*> find_pass_in(const SubShader& sub, const std::string& shader_name, const std::string& choice) {
  size_t index = 0;
  const auto [end, error] = std::from_chars(choice.data(), choice.data() + choice.size(), index);
  if (error == std::errc() && end == choice.data() + choice.size()) {
    if (index < sub.passes.size()) return &sub.passes[index];
  } else {
    for (const Pass& pass : sub.passes)
      if (!pass.name.empty() && same_word(pass.name, choice)) return &pass;
  }
  std::string list;
  for (size_t i = 0; i < sub.passes.size(); ++i) list += (i ? ", " : "") + pass_label(sub.passes[i], i);
  return fail(ErrorKind::Usage, "the shader '" + shader_name + "' has no pass '" + choice +
                                    "' in the SubShader it draws (its passes: " + (list.empty() ? "none" : list) + ")");
}

Result<void> find_implicit_includes(const std::vector<std::filesystem::path>& folders) {
  for (const std::filesystem::path& folder : folders) {
    bool all = true;
    for (const char* include : kImplicitIncludes) {
      std::error_code error;
      all = all && std::filesystem::is_regular_file(folder / include, error);
    }
    if (all) return {};
  }
  return fail(
      ErrorKind::Usage,
      "a CGPROGRAM includes Unity's HLSLSupport.cginc and UnityShaderVariables.cginc first, as Unity does, and no "
      "include folder holds them. xshade ships none of Unity's code: take the CGIncludes folder of the "
      "\"Built-in shaders\" download of your Unity version (or the Editor's Data/CGIncludes) and give it with -I "
      "or the project file's `shaders`");
}

Result<PassProgram> pass_program(const SubShader& sub, const Pass& pass) {
  if (!pass.program) return fail(ErrorKind::UserInput, "the pass has no program", pass.where);
  const ProgramBlock& program = *pass.program;
  if (program.language == ProgramLanguage::Glsl)
    return fail(ErrorKind::UserInput,
                "a GLSLPROGRAM is OpenGL-only GLSL that Unity passes through untouched; xshade compiles HLSL "
                "(CGPROGRAM or HLSLPROGRAM)",
                program.start);
  PassProgram composed;
  composed.pass = &pass;
  for (size_t i = 0; i < sub.passes.size(); ++i)
    if (&sub.passes[i] == &pass) composed.index = i;
  if (program.language == ProgramLanguage::Cg) {
    composed.implicit_includes = true;
    for (const char* include : kImplicitIncludes) composed.text += "#include \"" + std::string(include) + "\"\n";
  }
  if (!pass.generated)
    for (const std::vector<ProgramBlock>* blocks : {&sub.includes, &pass.includes})
      for (const ProgramBlock& block : *blocks)
        if (block.language == program.language) append_block(composed.text, block);
  append_block(composed.text, program);
  return composed;
}

}  // namespace xshade::shaderlab
