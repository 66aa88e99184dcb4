// Private helpers of the OpenGL backend: a move-only owner per GL object kind, how each format
// and shape is named to GL, the KHR_debug message log, and the compiler's log read into
// diagnostics. Not part of the harness interface.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/diagnostic.h"
#include "harness/backend/backend.h"
#include "harness/gl/gl_functions.h"

namespace xshade::harness::gl_support {

// ---- GL objects ---------------------------------------------------------------------------------

enum class Kind { Texture, Buffer, Framebuffer, VertexArray, Sampler, Shader, Program };

// One GL object name, deleted with the right glDelete* when dropped. The backend makes its
// context current before any is dropped.
template <Kind K>
class GlObject {
 public:
  GlObject() = default;
  GlObject(const gl::Functions* gl, GLuint id) : gl_(gl), id_(id) {}
  GlObject(GlObject&& other) noexcept : gl_(other.gl_), id_(std::exchange(other.id_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      gl_ = other.gl_;
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;
  ~GlObject() { reset(); }

  GLuint get() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

  void reset() {
    if (id_ == 0 || gl_ == nullptr) return;
    if constexpr (K == Kind::Texture) gl_->DeleteTextures(1, &id_);
    if constexpr (K == Kind::Buffer) gl_->DeleteBuffers(1, &id_);
    if constexpr (K == Kind::Framebuffer) gl_->DeleteFramebuffers(1, &id_);
    if constexpr (K == Kind::VertexArray) gl_->DeleteVertexArrays(1, &id_);
    if constexpr (K == Kind::Sampler) gl_->DeleteSamplers(1, &id_);
    if constexpr (K == Kind::Shader) gl_->DeleteShader(id_);
    if constexpr (K == Kind::Program) gl_->DeleteProgram(id_);
    id_ = 0;
  }

 private:
  const gl::Functions* gl_ = nullptr;
  GLuint id_ = 0;
};

using GlTexture = GlObject<Kind::Texture>;
using GlBuffer = GlObject<Kind::Buffer>;
using GlFramebuffer = GlObject<Kind::Framebuffer>;
using GlVertexArray = GlObject<Kind::VertexArray>;
using GlSampler = GlObject<Kind::Sampler>;
using GlShader = GlObject<Kind::Shader>;
using GlProgram = GlObject<Kind::Program>;

// ---- Formats and shapes -------------------------------------------------------------------------

// How OpenGL stores and uploads each format.
struct GlFormat {
  GLenum internal_format;
  GLenum format;
  GLenum type;
};
GlFormat gl_format(TextureFormat format);
GLenum gl_target(TextureShape shape);
GLint gl_compare_function(CompareOp op);
GLenum gl_blend_factor(BlendFactor factor);
GLenum gl_blend_op(BlendOp op);
GLenum gl_stencil_op(StencilOp op);
// Culling, depth, stencil and blending for the next draws (the blend and the colour mask of
// attachment 0; a second one is written as it is), the depth state where the target has depth
// and the stencil state where it has stencil, and the clip control: its GL_UPPER_LEFT origin puts
// clip +y at row 0, GL_LOWER_LEFT (`rows_up`, RowOrigin::Bottom) clip -y. The upper left one
// turns the facing computation around with the window's y (ARB_clip_control), so a winding in
// clip space is that winding to OpenGL either way: the front is GL_CCW (backend.h's DrawState),
// for culling and the stencil test's faces alike.
void apply_draw_state(const gl::Functions& gl, const DrawState& state, bool depth, bool stencil, bool rows_up = false);

// The internal draw that fills a multisampled texture: every sample of each texel of one layer
// gets the texel of a single-sampled copy. Without sample shading a fragment's one output goes
// to every sample it covers, and the triangle covers the whole layer. The fragment stage reads
// texture unit 0 and the uniform `layer`.
extern const char* const kFillVertexShader;
std::string fill_fragment_shader(TexelKind kind);

// Enables the clip planes of the `count` distances a program writes (gl_ClipDistance[0..count))
// and disables the others: OpenGL clips by a distance only where its plane is enabled, and an
// enabled plane the shader does not write clips at random.
void enable_clip_planes(const gl::Functions& gl, uint32_t count);
// What a vertex input of GL type `type` reads as; empty for a type no mesh or zero fills (a
// matrix, a double).
std::optional<TexelKind> attribute_kind(GLint type);
bool is_sampler_type(GLint type);
// "values[0]" -> "values": GL names an array by its first element.
std::string base_name(std::string name);
inline uint32_t round_up_16(uint32_t size) { return (size + 15u) & ~15u; }

// ---- KHR_debug ----------------------------------------------------------------------------------

struct MessageLog {
  std::mutex mutex;
  std::vector<std::string> messages;
  // While a program is made, its compiler's messages wait here (see create_program).
  std::optional<std::vector<std::string>> held;
};

// Every message above notification severity goes into the MessageLog `user` points at.
void APIENTRY debug_callback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                             const GLchar* message, const void* user);

// ---- Compiler logs ------------------------------------------------------------------------------

// Mesa: "0:4(28): error: `undeclared_thing' undeclared" (string:line(column)), or "error: ..."
// in link logs. Anything else becomes a message-only diagnostic.
// `files[n]` names source string n (what `#line L n` selects); string 0, or one the table does
// not name, is `file`.
std::vector<Diagnostic> parse_log(const std::string& log, const std::string& file,
                                  const std::vector<std::string>& files = {});

// ---- The linked program -------------------------------------------------------------------------

// The linked program `id`'s uniforms, blocks and inputs against `layout`: every block and sampler
// listed and no bigger than listed, no vertex input for a full-screen program. Fills
// `unsupplied_inputs` with the inputs above location 3 (no mesh has them) and what they read as.
Result<void> check_interface(const gl::Functions& gl, GLuint id, const ProgramLayout& layout, bool fullscreen,
                             std::vector<std::pair<GLuint, TexelKind>>& unsupplied_inputs, const std::string& what);

}  // namespace xshade::harness::gl_support
