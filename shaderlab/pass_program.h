// The HLSL text a pass of a .shader compiles, composed as Unity composes it: for a CGPROGRAM,
// HLSLSupport.cginc and UnityShaderVariables.cginc first (Unity's implicit includes); then the
// include blocks of the pass's scope in the order the file holds them (the shader's, its
// Category's, its SubShader's, the pass's own: CGINCLUDE for a CGPROGRAM, HLSLINCLUDE for an
// HLSLPROGRAM); then the program. Each block stands behind a `#line` to where it is in the .shader
// file, so that a message about any of it points there.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "shaderlab/compile_environment.h"
#include "shaderlab/shader.h"

namespace xshade::shaderlab {

// The include files Unity puts before every CGPROGRAM, in order.
inline constexpr const char* kImplicitIncludes[] = {"HLSLSupport.cginc", "UnityShaderVariables.cginc"};

struct PassProgram {
  std::string text;                // to compile as a file named after the .shader
  bool implicit_includes = false;  // the text begins with kImplicitIncludes
  const Pass* pass = nullptr;
  size_t index = 0;  // of the pass in its SubShader
};

// The SubShader xshade draws, as Unity takes the first its platform runs: the first none of whose
// programs `#pragma only_renderers` or `exclude_renderers` keeps from the platform
// (compile_environment.h); null when there is none, and the shader is drawn as its Fallback.
const SubShader* drawn_subshader(const Shader& shader, UnityPlatform platform = UnityPlatform::GLCore);
// Why a shader has no drawn SubShader: "has no SubShader", or that none runs on the platform.
std::string without_subshader(const Shader& shader, UnityPlatform platform = UnityPlatform::GLCore);

// The pass `choice` names in the drawn SubShader: its index ("0", "1", ...) or its Name, ignoring
// case as UsePass does. An error lists the passes there are.
Result<const Pass*> find_pass(const Shader& shader, const std::string& choice,
                              UnityPlatform platform = UnityPlatform::GLCore);
// The same in `sub`, a SubShader of the shader named `shader_name` (one with its surface
// program's passes generated).
Result<const Pass*> find_pass_in(const SubShader& sub, const std::string& shader_name, const std::string& choice);

// Unity's implicit includes are in one of `folders`, or an error that says where a user gets them:
// xshade ships none of Unity's code.
Result<void> find_implicit_includes(const std::vector<std::filesystem::path>& folders);

// `block`'s text (or `body` in its place: the block's text rewritten, line for line) appended to
// `text` behind a #line to where the block starts, padded to its column so that columns match too.
void append_block(std::string& text, const ProgramBlock& block, std::optional<std::string_view> body = std::nullopt);

// The text of `pass` (which has a program) in `sub`. A GLSLPROGRAM is an error at its line.
Result<PassProgram> pass_program(const SubShader& sub, const Pass& pass);

}  // namespace xshade::shaderlab
