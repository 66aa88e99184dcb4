#include "glsl/flavour.h"

namespace xshade::glsl {

std::string_view flavour_name(Flavour flavour) { return flavour == Flavour::Gl ? "gl" : "vk"; }

std::string fullscreen_vertex_shader(Flavour flavour) {
  hlsl::Reflection uv_only;
  uv_only.varyings.push_back({"TEXCOORD0", hlsl::Type::vector(hlsl::ScalarType::Float, 2)});
  return fullscreen_vertex_shader(flavour, uv_only);
}

std::string fullscreen_vertex_shader(Flavour flavour, const hlsl::Reflection& reflection) {
  // Vertices (-1,-1), (3,-1), (-1,3) cover the whole clip square with one triangle.
  const char* vertex_index = flavour == Flavour::Gl ? "gl_VertexID" : "gl_VertexIndex";
  std::string text = flavour == Flavour::Gl ? "#version 450 core\n" : "#version 450\n";
  std::string writes;
  for (const auto& [array, count] : {std::pair{"gl_ClipDistance", reflection.clip_distances},
                                     std::pair{"gl_CullDistance", reflection.cull_distances}}) {
    if (count == 0) continue;
    text += std::string("out float ") + array + "[" + std::to_string(count) + "];\n";
    for (uint32_t i = 0; i < count; ++i) writes += std::string("  ") + array + "[" + std::to_string(i) + "] = 0.0;\n";
  }
  for (const hlsl::StageVariable& varying : reflection.varyings) {
    // An array takes consecutive locations, each element fed alike.
    const bool array = varying.type.kind() == hlsl::TypeKind::Array;
    const hlsl::Type& type = array ? varying.type.element() : varying.type;
    if (!type.is_numeric()) continue;
    const uint32_t n = type.component_count();
    const hlsl::ScalarType scalar = type.scalar_type();
    const bool is_float = scalar == hlsl::ScalarType::Float || scalar == hlsl::ScalarType::Half;
    const char* prefix = is_float ? "" : scalar == hlsl::ScalarType::Int ? "i" : "u";
    if (!is_float && scalar != hlsl::ScalarType::Int && scalar != hlsl::ScalarType::Uint) continue;
    if (type.is_matrix() && !is_float) continue;
    // HLSL's floatRxC is GLSL's matRxC (each HLSL row one GLSL column), so matRxC(1.0), the
    // identity, is fed: a transform that leaves what it multiplies as it was.
    const std::string glsl_type = type.is_matrix()
                                      ? "mat" + std::to_string(type.rows()) + "x" + std::to_string(type.cols())
                                  : n == 1 ? (is_float                          ? "float"
                                              : scalar == hlsl::ScalarType::Int ? "int"
                                                                                : "uint")
                                           : std::string(prefix) + "vec" + std::to_string(n);
    const std::string name = "xs_fed" + std::to_string(varying.location);
    // The fragment's interpolation, so that both stages say the same.
    const bool flat = !is_float || varying.interpolation == hlsl::Interpolation::NoInterpolation;
    const char* qualifier = flat                                                          ? "flat "
                            : varying.interpolation == hlsl::Interpolation::NoPerspective ? "noperspective "
                            : varying.interpolation == hlsl::Interpolation::Centroid      ? "centroid "
                            : varying.interpolation == hlsl::Interpolation::Sample        ? "sample "
                                                                                          : "";
    const uint32_t elements = array ? varying.type.array_length() : 0;
    text += "layout(location = " + std::to_string(varying.location) + ") " + qualifier + "out " + glsl_type + " " +
            name + (array ? "[" + std::to_string(elements) + "]" : std::string()) + ";\n";
    static const char* const kComponents[] = {"", ".x", ".xy", ".xyz", ""};
    const std::string value = type.is_matrix() ? glsl_type + "(1.0)"
                              : is_float       ? "vec4(uv, 0.0, 1.0)" + std::string(kComponents[n])
                                               : glsl_type + "(0)";
    if (!array) writes += "  " + name + " = " + value + ";\n";
    for (uint32_t e = 0; e < elements; ++e) writes += "  " + name + "[" + std::to_string(e) + "] = " + value + ";\n";
  }
  text +=
      "void main() {\n"
      "  vec2 position = vec2(float((";
  text += vertex_index;
  text += " & 1) << 2) - 1.0, float((";
  text += vertex_index;
  text +=
      " & 2) << 1) - 1.0);\n"
      "  vec2 uv = vec2(position.x * 0.5 + 0.5, 0.5 - position.y * 0.5);\n";
  text += writes;
  text +=
      "  gl_Position = vec4(position, 0.0, 1.0);\n"
      "}\n";
  return text;
}

}  // namespace xshade::glsl
