// libFuzzer target: any bytes as a .shader file. The ShaderLab reader must report, never crash,
// hang or read out of bounds; every location it gives is inside the text.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "shaderlab/reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto shader = xshade::shaderlab::read_shader(text, "fuzz.shader");
  if (!shader) {
    // A line past the text's last would be a location the reader made up.
    size_t lines = 1;
    for (char c : text) lines += c == '\n';
    if (shader.error().where.line > lines) std::abort();
    return 0;
  }
  for (const auto& sub : shader->subshaders)
    for (const auto& pass : sub.passes)
      if (pass.program && pass.program->text.size() > size) std::abort();
  return 0;
}
