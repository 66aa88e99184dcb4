#include "glsl/flavour.h"

namespace xshade::glsl {

std::string_view flavour_name(Flavour flavour) {
  return flavour == Flavour::Gl ? "gl" : "vk";
}

std::string fullscreen_vertex_shader(Flavour flavour) {
  // Vertices (-1,-1), (3,-1), (-1,3) cover the whole clip square with one triangle.
  const char* vertex_index = flavour == Flavour::Gl ? "gl_VertexID" : "gl_VertexIndex";
  std::string text = flavour == Flavour::Gl ? "#version 450 core\n" : "#version 450\n";
  text += "layout(location = 0) out vec2 uv;\n"
          "void main() {\n"
          "  vec2 position = vec2(float((";
  text += vertex_index;
  text += " & 1) << 2) - 1.0, float((";
  text += vertex_index;
  text += " & 2) << 1) - 1.0);\n"
          "  uv = vec2(position.x * 0.5 + 0.5, 0.5 - position.y * 0.5);\n"
          "  gl_Position = vec4(position, 0.0, 1.0);\n"
          "}\n";
  return text;
}

}  // namespace xshade::glsl
