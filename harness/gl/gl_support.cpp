#include "harness/gl/gl_support.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

#include <fmt/format.h>

namespace xshade::harness::gl_support {

GlFormat gl_format(TextureFormat format) {
  switch (format) {
    case TextureFormat::Rgba8Unorm: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case TextureFormat::Rgba8Srgb: return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case TextureFormat::Rgba32Float: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case TextureFormat::R32Float: return {GL_R32F, GL_RED, GL_FLOAT};
    case TextureFormat::Depth32Float: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    case TextureFormat::Rgba32Uint: return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case TextureFormat::Rgba32Sint: return {GL_RGBA32I, GL_RGBA_INTEGER, GL_INT};
  }
  return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}

GLenum gl_target(TextureShape shape) {
  switch (shape.dimension) {
    case TextureDimension::Tex1D: return GL_TEXTURE_1D;
    case TextureDimension::Tex1DArray: return GL_TEXTURE_1D_ARRAY;
    case TextureDimension::Tex2D: return shape.multisampled ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    case TextureDimension::Tex2DArray:
      return shape.multisampled ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_ARRAY;
    case TextureDimension::Tex3D: return GL_TEXTURE_3D;
    case TextureDimension::Cube: return GL_TEXTURE_CUBE_MAP;
    case TextureDimension::CubeArray: return GL_TEXTURE_CUBE_MAP_ARRAY;
  }
  return GL_TEXTURE_2D;
}

GLenum gl_blend_factor(BlendFactor factor) {
  switch (factor) {
    case BlendFactor::Zero: return GL_ZERO;
    case BlendFactor::One: return GL_ONE;
    case BlendFactor::SrcColor: return GL_SRC_COLOR;
    case BlendFactor::OneMinusSrcColor: return GL_ONE_MINUS_SRC_COLOR;
    case BlendFactor::DstColor: return GL_DST_COLOR;
    case BlendFactor::OneMinusDstColor: return GL_ONE_MINUS_DST_COLOR;
    case BlendFactor::SrcAlpha: return GL_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha: return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstAlpha: return GL_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha: return GL_ONE_MINUS_DST_ALPHA;
    case BlendFactor::SrcAlphaSaturate: return GL_SRC_ALPHA_SATURATE;
  }
  return GL_ONE;
}

GLenum gl_blend_op(BlendOp op) {
  switch (op) {
    case BlendOp::Add: return GL_FUNC_ADD;
    case BlendOp::Subtract: return GL_FUNC_SUBTRACT;
    case BlendOp::ReverseSubtract: return GL_FUNC_REVERSE_SUBTRACT;
    case BlendOp::Min: return GL_MIN;
    case BlendOp::Max: return GL_MAX;
  }
  return GL_FUNC_ADD;
}

GLenum gl_stencil_op(StencilOp op) {
  switch (op) {
    case StencilOp::Keep: return GL_KEEP;
    case StencilOp::Zero: return GL_ZERO;
    case StencilOp::Replace: return GL_REPLACE;
    case StencilOp::IncrementClamp: return GL_INCR;
    case StencilOp::DecrementClamp: return GL_DECR;
    case StencilOp::Invert: return GL_INVERT;
    case StencilOp::IncrementWrap: return GL_INCR_WRAP;
    case StencilOp::DecrementWrap: return GL_DECR_WRAP;
  }
  return GL_KEEP;
}

void apply_draw_state(const gl::Functions& gl, const DrawState& state, bool depth, bool stencil, bool rows_up) {
  gl.ClipControl(rows_up ? GL_LOWER_LEFT : GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  gl.FrontFace(GL_CCW);
  if (state.cull == CullMode::Off) {
    gl.Disable(GL_CULL_FACE);
  } else {
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(state.cull == CullMode::Back ? GL_BACK : GL_FRONT);
  }
  if (stencil && state.stencil.enabled) {
    const StencilState& s = state.stencil;
    gl.Enable(GL_STENCIL_TEST);
    for (const auto& [face, ops] : {std::pair{GLenum(GL_FRONT), s.front}, std::pair{GLenum(GL_BACK), s.back}}) {
      gl.StencilFuncSeparate(face, GLenum(gl_compare_function(ops.compare)), s.reference, s.read_mask);
      gl.StencilOpSeparate(face, gl_stencil_op(ops.fail), gl_stencil_op(ops.depth_fail), gl_stencil_op(ops.pass));
    }
    gl.StencilMask(s.write_mask);
  } else {
    gl.Disable(GL_STENCIL_TEST);
  }
  if (depth) {
    gl.DepthMask(state.depth_write ? GL_TRUE : GL_FALSE);
    gl.DepthFunc(static_cast<GLenum>(gl_compare_function(state.depth_compare)));
  }
  if (state.depth_bias_slope != 0.0f || state.depth_bias_units != 0.0f) {
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(state.depth_bias_slope, state.depth_bias_units);
  } else {
    gl.Disable(GL_POLYGON_OFFSET_FILL);
  }
  if (state.blend.enabled) {
    const BlendState& b = state.blend;
    gl.Enablei(GL_BLEND, 0);
    gl.BlendFuncSeparatei(0, gl_blend_factor(b.color_source), gl_blend_factor(b.color_destination),
                          gl_blend_factor(b.alpha_source), gl_blend_factor(b.alpha_destination));
    gl.BlendEquationSeparatei(0, gl_blend_op(b.color_op), gl_blend_op(b.alpha_op));
  } else {
    gl.Disablei(GL_BLEND, 0);
  }
  const auto bit = [&](int channel) -> GLboolean { return (state.color_write >> channel) & 1 ? GL_TRUE : GL_FALSE; };
  gl.ColorMaski(0, bit(0), bit(1), bit(2), bit(3));
}

GLint gl_compare_function(CompareOp op) {
  switch (op) {
    case CompareOp::Never: return GL_NEVER;
    case CompareOp::Less: return GL_LESS;
    case CompareOp::Equal: return GL_EQUAL;
    case CompareOp::LessEqual: return GL_LEQUAL;
    case CompareOp::Greater: return GL_GREATER;
    case CompareOp::NotEqual: return GL_NOTEQUAL;
    case CompareOp::GreaterEqual: return GL_GEQUAL;
    case CompareOp::Always: return GL_ALWAYS;
  }
  return GL_LEQUAL;
}

// What a vertex input of GL type `type` reads as; empty for a type no mesh or zero fills (a
// matrix, a double).
std::optional<TexelKind> attribute_kind(GLint type) {
  switch (static_cast<GLenum>(type)) {
    case GL_FLOAT:
    case GL_FLOAT_VEC2:
    case GL_FLOAT_VEC3:
    case GL_FLOAT_VEC4: return TexelKind::Float;
    case GL_INT:
    case GL_INT_VEC2:
    case GL_INT_VEC3:
    case GL_INT_VEC4: return TexelKind::Int;
    case GL_UNSIGNED_INT:
    case GL_UNSIGNED_INT_VEC2:
    case GL_UNSIGNED_INT_VEC3:
    case GL_UNSIGNED_INT_VEC4: return TexelKind::Uint;
    default: return std::nullopt;
  }
}

namespace {

const char* severity_name(GLenum severity) {
  switch (severity) {
    case GL_DEBUG_SEVERITY_HIGH: return "high";
    case GL_DEBUG_SEVERITY_MEDIUM: return "medium";
    case GL_DEBUG_SEVERITY_LOW: return "low";
    default: return "notification";
  }
}

const char* source_name(GLenum source) {
  switch (source) {
    case GL_DEBUG_SOURCE_API: return "API";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
  }
}

const char* type_name(GLenum type) {
  switch (type) {
    case GL_DEBUG_TYPE_ERROR: return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR: return "deprecated behaviour";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR: return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY: return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE: return "performance";
    default: return "other";
  }
}

}  // namespace

void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                             const GLchar* message, const void* user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  auto* log = static_cast<MessageLog*>(const_cast<void*>(user));
  std::string text = length >= 0 ? std::string(message, static_cast<size_t>(length)) : std::string(message);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  std::string line = fmt::format("OpenGL {} {} (severity {}, id {}): {}", source_name(source), type_name(type),
                                 severity_name(severity), id, text);
  std::lock_guard lock(log->mutex);
  (log->held ? *log->held : log->messages).push_back(std::move(line));
}

// ---- Compiler logs ------------------------------------------------------------------------------

namespace {

bool parse_number(std::string_view& text, uint32_t& value) {
  size_t digits = 0;
  value = 0;
  while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) {
    value = value * 10 + static_cast<uint32_t>(text[digits] - '0');
    ++digits;
  }
  text.remove_prefix(digits);
  return digits > 0;
}

bool consume(std::string_view& text, std::string_view prefix) {
  if (!text.starts_with(prefix)) return false;
  text.remove_prefix(prefix.size());
  return true;
}

}  // namespace

// Mesa: "0:4(28): error: `undeclared_thing' undeclared" (string:line(column)), or "error: ..."
// in link logs. Anything else becomes a message-only diagnostic.
// `files[n]` names source string n (what `#line L n` selects); string 0, or one the table does
// not name, is `file`.
std::vector<Diagnostic> parse_log(const std::string& log, const std::string& file,
                                  const std::vector<std::string>& files) {
  std::vector<Diagnostic> diagnostics;
  size_t start = 0;
  while (start < log.size()) {
    size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    std::string_view line(log.data() + start, end - start);
    start = end + 1;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
    if (line.empty()) continue;

    Diagnostic diagnostic;
    std::string_view rest = line;
    uint32_t string_index = 0, line_number = 0, column = 0;
    if (parse_number(rest, string_index) && consume(rest, ":") && parse_number(rest, line_number) &&
        consume(rest, "(") && parse_number(rest, column) && consume(rest, "):")) {
      const bool named = string_index > 0 && string_index < files.size();
      diagnostic.where = SourceLocation{named ? files[string_index] : file, line_number, column};
      while (consume(rest, " ")) {
      }
    } else {
      rest = line;
    }
    const size_t colon = rest.find(": ");
    std::string_view kind = colon == std::string_view::npos ? std::string_view{} : rest.substr(0, colon);
    if (kind.find("error") != std::string_view::npos) {
      diagnostic.severity = Severity::Error;
      rest.remove_prefix(colon + 2);
    } else if (kind.find("warning") != std::string_view::npos) {
      diagnostic.severity = Severity::Warning;
      rest.remove_prefix(colon + 2);
    } else if (diagnostic.where.known()) {
      diagnostic.severity = Severity::Note;
    } else {
      // Unparsed: keep the whole line as the message.
      diagnostic.severity = Severity::Note;
      rest = line;
    }
    diagnostic.message = std::string(rest);
    diagnostics.push_back(std::move(diagnostic));
  }
  return diagnostics;
}

bool is_sampler_type(GLint type) {
  switch (static_cast<GLenum>(type)) {
    case GL_SAMPLER_1D:
    case GL_SAMPLER_2D:
    case GL_SAMPLER_3D:
    case GL_SAMPLER_CUBE:
    case GL_SAMPLER_1D_SHADOW:
    case GL_SAMPLER_2D_SHADOW:
    case GL_SAMPLER_1D_ARRAY:
    case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_1D_ARRAY_SHADOW:
    case GL_SAMPLER_2D_ARRAY_SHADOW:
    case GL_SAMPLER_2D_MULTISAMPLE:
    case GL_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_SAMPLER_CUBE_SHADOW:
    case GL_SAMPLER_BUFFER:
    case GL_SAMPLER_2D_RECT:
    case GL_SAMPLER_2D_RECT_SHADOW:
    case GL_SAMPLER_CUBE_MAP_ARRAY:
    case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
    case GL_INT_SAMPLER_1D:
    case GL_INT_SAMPLER_2D:
    case GL_INT_SAMPLER_3D:
    case GL_INT_SAMPLER_CUBE:
    case GL_INT_SAMPLER_1D_ARRAY:
    case GL_INT_SAMPLER_2D_ARRAY:
    case GL_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_INT_SAMPLER_BUFFER:
    case GL_INT_SAMPLER_2D_RECT:
    case GL_INT_SAMPLER_CUBE_MAP_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_1D:
    case GL_UNSIGNED_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_3D:
    case GL_UNSIGNED_INT_SAMPLER_CUBE:
    case GL_UNSIGNED_INT_SAMPLER_1D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_BUFFER:
    case GL_UNSIGNED_INT_SAMPLER_2D_RECT:
    case GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY: return true;
    default: return false;
  }
}

// "values[0]" -> "values": GL names an array by its first element.
std::string base_name(std::string name) {
  if (name.ends_with("[0]")) name.resize(name.size() - 3);
  return name;
}

// The linked program's uniforms, blocks and inputs against the layout and GL's limits.
Result<void> check_interface(const gl::Functions& gl, GLuint id, const ProgramLayout& layout, bool fullscreen,
                             std::vector<std::pair<GLuint, TexelKind>>& unsupplied_inputs, const std::string& what) {
  const auto resource_name = [&](GLenum interface, GLuint index) {
    GLint length = 0;
    const GLenum property = GL_NAME_LENGTH;
    gl.GetProgramResourceiv(id, interface, index, 1, &property, 1, nullptr, &length);
    std::string name(static_cast<size_t>(std::max(length, 1)), '\0');
    GLsizei written = 0;
    gl.GetProgramResourceName(id, interface, index, static_cast<GLsizei>(name.size()), &written, name.data());
    name.resize(static_cast<size_t>(std::max(written, 0)));
    return name;
  };
  const auto count = [&](GLenum interface) {
    GLint value = 0;
    gl.GetProgramInterfaceiv(id, interface, GL_ACTIVE_RESOURCES, &value);
    return static_cast<GLuint>(std::max(value, 0));
  };

  // Uniform blocks: listed, and no bigger than the layout says.
  const GLuint blocks = count(GL_UNIFORM_BLOCK);
  for (GLuint index = 0; index < blocks; ++index) {
    const std::string name = base_name(resource_name(GL_UNIFORM_BLOCK, index));
    const GLenum property = GL_BUFFER_DATA_SIZE;
    GLint size = 0;
    gl.GetProgramResourceiv(id, GL_UNIFORM_BLOCK, index, 1, &property, 1, nullptr, &size);
    auto slot = std::find_if(layout.uniform_blocks.begin(), layout.uniform_blocks.end(),
                             [&](const UniformBlockSlot& s) { return s.glsl_block_name() == name; });
    if (slot == layout.uniform_blocks.end())
      return fail(ErrorKind::Internal, fmt::format("{}: the program uses uniform block '{}', which the layout does not "
                                                   "list",
                                                   what, name));
    if (static_cast<uint32_t>(size) > round_up_16(slot->size))
      return fail(ErrorKind::Internal, fmt::format("{}: uniform block '{}' is {} bytes in the GLSL, but the layout "
                                                   "gives it {}",
                                                   what, name, size, slot->size));
  }

  // Storage blocks: each one a listed buffer's.
  const GLuint storage_blocks = count(GL_SHADER_STORAGE_BLOCK);
  for (GLuint index = 0; index < storage_blocks; ++index) {
    const std::string name = resource_name(GL_SHADER_STORAGE_BLOCK, index);
    if (std::none_of(layout.storage_buffers.begin(), layout.storage_buffers.end(),
                     [&](const StorageBufferSlot& s) { return s.glsl_block == name; }))
      return fail(ErrorKind::Internal,
                  fmt::format("{}: the program uses storage block '{}', which the layout does not list", what, name));
  }

  // Uniforms outside blocks: only samplers, each listed as a texture.
  const GLuint uniforms = count(GL_UNIFORM);
  for (GLuint index = 0; index < uniforms; ++index) {
    const std::array<GLenum, 3> properties = {GL_BLOCK_INDEX, GL_TYPE, GL_LOCATION};
    std::array<GLint, 3> values = {-1, 0, -1};
    gl.GetProgramResourceiv(id, GL_UNIFORM, index, static_cast<GLsizei>(properties.size()), properties.data(),
                            static_cast<GLsizei>(values.size()), nullptr, values.data());
    if (values[0] != -1) continue;  // a member of a block
    const std::string name = base_name(resource_name(GL_UNIFORM, index));
    if (name.starts_with("gl_")) continue;
    auto slot = std::find_if(layout.textures.begin(), layout.textures.end(),
                             [&](const TextureSlot& s) { return s.uniform_name() == name; });
    if (slot == layout.textures.end())
      return fail(ErrorKind::Internal,
                  fmt::format("{}: the program uses uniform '{}', which the layout does not list", what, name));
    if (!is_sampler_type(values[1]))
      return fail(ErrorKind::Internal,
                  fmt::format("{}: the layout lists '{}' as a texture, but it is not a sampler", what, name));
  }

  // Vertex inputs: none for a full-screen program; for a mesh program the mesh's locations 0..3,
  // and backend.h's constant for any other (what glGetActiveAttrib reports, here through the
  // program interface query that gives the location with the type).
  const GLuint inputs = count(GL_PROGRAM_INPUT);
  unsupplied_inputs.clear();
  for (GLuint index = 0; index < inputs; ++index) {
    const std::array<GLenum, 2> properties = {GL_LOCATION, GL_TYPE};
    std::array<GLint, 2> values = {-1, 0};
    gl.GetProgramResourceiv(id, GL_PROGRAM_INPUT, index, static_cast<GLsizei>(properties.size()), properties.data(),
                            static_cast<GLsizei>(values.size()), nullptr, values.data());
    const GLint location = values[0];
    if (location < 0) continue;  // a built-in such as gl_VertexID
    if (fullscreen)
      return fail(ErrorKind::Internal, fmt::format("{}: a full-screen program's vertex shader must read no vertex "
                                                   "input, but it reads location {}",
                                                   what, location));
    if (location <= 3) continue;
    const std::optional<TexelKind> kind = attribute_kind(values[1]);
    if (!kind)
      return fail(ErrorKind::UserInput,
                  fmt::format("{}: the vertex shader reads input '{}' at location {} of GL type 0x{:04X}, which "
                              "no mesh supplies and which is not a float, int or uint scalar or vector",
                              what, resource_name(GL_PROGRAM_INPUT, index), location, values[1]));
    unsupplied_inputs.emplace_back(static_cast<GLuint>(location), *kind);
  }
  return {};
}

const char* const kFillVertexShader = R"(#version 450 core
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

std::string fill_fragment_shader(TexelKind kind) {
  const std::string prefix = kind == TexelKind::Int ? "i" : kind == TexelKind::Uint ? "u" : "";
  return "#version 450 core\nlayout(binding = 0) uniform " + prefix +
         "sampler2DArray source;\n"
         "uniform int layer;\nlayout(location = 0) out " +
         prefix +
         "vec4 color;\n"
         "void main() { color = texelFetch(source, ivec3(ivec2(gl_FragCoord.xy), layer), 0); }\n";
}

void enable_clip_planes(const gl::Functions& gl, uint32_t count) {
  constexpr uint32_t kMaxClipDistances = 8;  // Direct3D's and Vulkan's clip and cull distances together
  for (uint32_t plane = 0; plane < kMaxClipDistances; ++plane) {
    if (plane < count)
      gl.Enable(GL_CLIP_DISTANCE0 + plane);
    else
      gl.Disable(GL_CLIP_DISTANCE0 + plane);
  }
}

}  // namespace xshade::harness::gl_support
