// UsePass "Shader/NAME" and Fallback "Shader" name a shader by what its `Shader "..."` line
// declares, which Unity looks up among every shader of the project: here, among the .shader files
// under the shader folders.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/result.h"

namespace xshade::shaderlab {

// The name a .shader's text declares in its `Shader "name"` line (comments and a byte-order mark
// before it skipped); empty when the text starts with anything else.
std::string declared_shader_name(std::string_view text);

// The .shader file under `folders` (in order, each searched through its subfolders) that declares
// `name`, matched exactly as Unity's Shader.Find does, else one that declares "Legacy Shaders/"
// followed by `name` (the old name of one of Unity's legacy shaders, which Unity still finds); an
// error naming the folders when none does. Each folder is read once a process.
Result<std::filesystem::path> find_shader_named(const std::string& name,
                                                const std::vector<std::filesystem::path>& folders);

// UsePass "Shader/NAME": the shader's name and the pass's, split at the last '/'.
std::pair<std::string, std::string> split_used_pass(const std::string& used);

}  // namespace xshade::shaderlab
