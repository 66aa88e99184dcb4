// Reads a `.shader` file's ShaderLab (Unity's manual: "ShaderLab: defining a Shader object" and
// the pages it links): its structure, properties and render state, checked as it is read. An
// error stops the reading and says where, at the file's line and column, and what is allowed
// there; what the reader passes over is a note in Shader::notes.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "base/result.h"
#include "shaderlab/shader.h"

namespace xshade::shaderlab {

// `file` is what locations name.
Result<Shader> read_shader(std::string_view text, const std::string& file);
Result<Shader> read_shader_file(const std::filesystem::path& path);

}  // namespace xshade::shaderlab
