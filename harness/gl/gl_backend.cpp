// The OpenGL lane: OpenGL 4.5 core on Mesa's llvmpipe, headless, on a context from either route
// of gl_context.h (OSMesa or EGL surfaceless); nothing here knows which.
//
// Every GL entry point comes through the context's proc-address function into the table of
// gl_functions.h. All drawing goes into framebuffer objects, never into a default framebuffer
// (the OSMesa route has a 1x1 dummy one, the EGL route none). Every public call makes this
// backend's context current when it is not, so that several backends (of either route) can
// share one process, and ends by checking glGetError.
//
// Why this file is long: it is the one class of the Backend seam for OpenGL, each call one
// context-current step of the API (textures of every shape, programs with their interface checked,
// a render of draws with their state); its stateless pieces live in gl_support.
#include "harness/gl/gl_backend.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <string_view>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "harness/backend/guarded.h"
#include "harness/backend/handle_table.h"
#include "harness/backend/pass_resolution.h"
#include "harness/gl/compile_messages.h"
#include "harness/gl/gl_functions.h"
#include "harness/gl/gl_support.h"

namespace xshade::harness {
namespace {

// ---- The context's entry points ----------------------------------------------------------------

// gl::load_functions takes a plain function; this one forwards to the context being loaded from.
std::mutex proc_address_mutex;
const GlContext* loading_context = nullptr;
void* context_proc_address(const char* name) { return loading_context->proc_address(name); }

using gl_support::apply_draw_state;
using gl_support::attribute_kind;
using gl_support::base_name;
using gl_support::debug_callback;
using gl_support::gl_compare_function;
using gl_support::gl_format;
using gl_support::gl_target;
using gl_support::GlBuffer;
using gl_support::GlFormat;
using gl_support::GlFramebuffer;
using gl_support::GlProgram;
using gl_support::GlSampler;
using gl_support::GlShader;
using gl_support::GlTexture;
using gl_support::GlVertexArray;
using gl_support::is_sampler_type;
using gl_support::MessageLog;
using gl_support::parse_log;
using gl_support::round_up_16;

// ---- Resources ----------------------------------------------------------------------------------

struct Texture {
  GlTexture texture;
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t levels = 1;
  TextureShape shape;
  TextureFormat format = TextureFormat::Rgba32Float;
};

struct Target {
  GlFramebuffer framebuffer;
  Texture color;
  std::optional<Texture> depth;         // with an 8-bit stencil where `stencil`
  std::optional<Texture> second_color;  // TargetDesc::second_color
  bool stencil = false;
};

struct Mesh {
  GlVertexArray vertex_array;
  GlBuffer vertices;
  GlBuffer indices;
  uint32_t index_count = 0;
};

struct Program {
  std::string name;
  ProgramLayout layout;
  bool fullscreen = false;
  uint32_t clip_distances = 0;
  GlProgram program;
  std::vector<GlBuffer> uniform_buffers;  // per layout uniform block
  std::vector<GlBuffer> storage_buffers;  // per layout storage buffer
  // Vertex inputs no mesh supplies (locations above 3), with what they read as: each draw sets
  // their generic current value to backend.h's constant (GL's own default is (0, 0, 0, 1)).
  std::vector<std::pair<GLuint, TexelKind>> unsupplied_inputs;
};

// ---- The backend --------------------------------------------------------------------------------

class GlBackend final : public Backend {
 public:
  ~GlBackend() override;

  Result<void> init(std::unique_ptr<GlContext> context, std::filesystem::path compile_messages);

  const DriverInfo& driver_info() const override { return info_; }
  Result<TargetHandle> create_target(const TargetDesc& desc) override;
  Result<MeshHandle> upload_mesh(const MeshData& mesh) override;
  Result<TextureHandle> upload_texture(const TextureData& texture) override;
  Result<ProgramHandle> create_program(const ProgramDesc& desc) override;
  Result<void> destroy(TargetHandle target) override { return destroy_in(objects_.targets, target); }
  Result<void> destroy(MeshHandle mesh) override { return destroy_in(objects_.meshes, mesh); }
  Result<void> destroy(TextureHandle texture) override { return destroy_in(objects_.textures, texture); }
  Result<void> destroy(ProgramHandle program) override { return destroy_in(objects_.programs, program); }
  Result<void> render(const RenderPass& pass) override;
  Result<FloatImage> read_color(TargetHandle target) override;
  Result<FloatImage> read_second_color(TargetHandle target) override;
  Result<FloatImage> read_texture(TargetHandle handle, bool second);
  std::vector<std::string> take_driver_messages() override {
    std::lock_guard lock(log_->mutex);
    return std::exchange(log_->messages, {});
  }

 private:
  // Makes the context current when another (or none) is.
  bool make_current() { return context_->make_current(); }
  // Drains glGetError; fails with the error names and the driver's last message.
  Result<void> check_errors(const std::string& what);
  // Makes the context current, runs `body` (guarded), then checks glGetError.
  template <class T, class F>
  Result<T> on_context(const std::string& what, F&& body);
  // GL deletes the names at once: a later command that used them has already been given the
  // objects, and glDelete* of a texture still attached or bound only detaches it.
  template <class Table, class HandleType>
  Result<void> destroy_in(Table& table, HandleType handle) {
    return on_context<void>("destroy", [&]() -> Result<void> { return table.erase(handle, "destroy"); });
  }

  GLint get_integer(GLenum name) const {
    GLint value = 0;
    gl_.GetIntegerv(name, &value);
    return value;
  }
  std::string get_string(GLenum name) const {
    const GLubyte* text = gl_.GetString(name);
    return text ? reinterpret_cast<const char*>(text) : "";
  }
  // `compare`: a comparison sampler (of a shadow sampler's unit), with desc.compare.
  GLuint sampler(const SamplerDesc& desc, bool mipmapped, bool compare);
  // Clears the depth (and the stencil, where the target has one) with every bit writable, as a
  // clear must be whatever the last draw's masks were.
  void clear_depth_stencil(const Target& target, float depth, uint8_t stencil);
  // Every sample of each texel of `texture` (multisampled, just allocated) from level 0 of `data`.
  Result<void> fill_multisampled(const Texture& texture, const TextureData& data, const std::string& what);
  Result<GLuint> fill_program(TexelKind kind, const std::string& what);
  Result<GlShader> compile(const ShaderStageSource& source, GLenum stage, const char* stage_name,
                           const std::string& what);

  // Declaration order is teardown order reversed: GL objects go first, then the context (which
  // closes its library); the log outlives the context that writes into it.
  std::unique_ptr<MessageLog> log_ = std::make_unique<MessageLog>();
  CompileMessages compile_messages_{{}};
  std::unique_ptr<GlContext> context_;
  gl::Functions gl_;
  DriverInfo info_;
  GLint max_texture_size_ = 0;
  GLint max_uniform_buffer_bindings_ = 0;
  GLint max_texture_units_ = 0;
  GLint max_storage_buffer_bindings_ = 0;
  GLint max_uniform_block_size_ = 0;
  GLint max_3d_texture_size_ = 0;
  GLint max_array_layers_ = 0;
  GLint max_color_samples_ = 0;
  GLint max_integer_samples_ = 0;

  GlVertexArray empty_vertex_array_;  // for full-screen programs
  std::map<std::tuple<Filter, AddressMode, bool, std::optional<CompareOp>>, GlSampler> samplers_;
  std::map<TexelKind, GlProgram> fill_programs_;  // by the texel kind they copy
  BackendObjects<Target, Mesh, Texture, Program> objects_;
};

GlBackend::~GlBackend() {
  if (context_ == nullptr) return;
  if (make_current()) {
    objects_.clear();
    fill_programs_.clear();
    samplers_.clear();
    empty_vertex_array_.reset();
    if (gl_.Finish != nullptr) gl_.Finish();  // null when loading the entry points failed
  } else {
    // Another context (or none) is current, so a glDelete* would hit the wrong objects. The
    // names are dropped instead; destroying the context frees them.
    gl_.DeleteTextures = [](GLsizei, const GLuint*) {};
    gl_.DeleteBuffers = [](GLsizei, const GLuint*) {};
    gl_.DeleteFramebuffers = [](GLsizei, const GLuint*) {};
    gl_.DeleteVertexArrays = [](GLsizei, const GLuint*) {};
    gl_.DeleteSamplers = [](GLsizei, const GLuint*) {};
    gl_.DeleteShader = [](GLuint) {};
    gl_.DeleteProgram = [](GLuint) {};
  }
  context_.reset();
}

Result<void> GlBackend::check_errors(const std::string& what) {
  std::vector<std::string> errors;
  for (int i = 0; i < 32; ++i) {
    const GLenum error = gl_.GetError();
    if (error == GL_NO_ERROR) break;
    errors.push_back(gl::error_name(error));
  }
  if (errors.empty()) return {};
  std::string message = fmt::format("{}: OpenGL reported {}", what, fmt::join(errors, ", "));
  std::lock_guard lock(log_->mutex);
  const std::vector<std::string>& messages = log_->held ? *log_->held : log_->messages;
  if (!messages.empty()) message += fmt::format(" (the driver's last message: {})", messages.back());
  return fail(ErrorKind::Backend, std::move(message));
}

template <class T, class F>
Result<T> GlBackend::on_context(const std::string& what, F&& body) {
  return harness::guarded<T>(what, [&]() -> Result<T> {
    if (!make_current())
      return fail(ErrorKind::Backend,
                  fmt::format("{}: {} could not make this backend's context current", what, context_->route()));
    Result<T> result = body();
    Result<void> checked = check_errors(what);
    if (!result) return result;
    if (!checked) return fail(checked.error());
    return result;
  });
}

Result<void> GlBackend::init(std::unique_ptr<GlContext> context, std::filesystem::path compile_messages) {
  context_ = std::move(context);
  compile_messages_ = CompileMessages(std::move(compile_messages));
  if (!make_current())
    return fail(ErrorKind::Backend, fmt::format("{} could not make a new 4.5 core context current", context_->route()));

  std::vector<std::string> missing;
  {
    std::lock_guard lock(proc_address_mutex);
    loading_context = context_.get();
    missing = gl::load_functions(gl_, &context_proc_address);
    loading_context = nullptr;
  }
  if (!missing.empty())
    return fail(ErrorKind::Backend,
                fmt::format("the {} context lacks OpenGL functions: {}; install the Debian package {}",
                            context_->route(), fmt::join(missing, ", "), context_->packages()));

  info_.api = fmt::format("OpenGL 4.5 core ({})", context_->route());
  info_.renderer = get_string(GL_RENDERER);
  info_.api_version = get_string(GL_VERSION);
  if (size_t mesa = info_.api_version.find("Mesa "); mesa != std::string::npos) {
    info_.driver_version = info_.api_version.substr(mesa);
    if (size_t paren = info_.driver_version.find(" ("); paren != std::string::npos) info_.driver_version.resize(paren);
  }
  info_.llvm_version = llvm_version_of(info_.renderer);
  const GLint major = get_integer(GL_MAJOR_VERSION);
  const GLint minor = get_integer(GL_MINOR_VERSION);
  if (major < 4 || (major == 4 && minor < 5))
    return fail(ErrorKind::Backend, fmt::format("'{}' gives OpenGL {}.{} ({}), but 4.5 core is required; install a "
                                                "newer Debian package {}",
                                                info_.renderer, major, minor, info_.api_version, context_->packages()));

  gl_.Enable(GL_DEBUG_OUTPUT);
  gl_.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  gl_.DebugMessageCallback(&debug_callback, log_.get());
  gl_.DebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);

  // Direct3D orientation: clip +y maps to window row 0 (the first row read back), z in [0, 1].
  gl_.ClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
  gl_.Disable(GL_CULL_FACE);
  gl_.Disable(GL_BLEND);
  gl_.Disable(GL_DITHER);
  gl_.Disable(GL_FRAMEBUFFER_SRGB);
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.ClampColor(GL_CLAMP_READ_COLOR, GL_FALSE);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.DepthFunc(GL_LESS);

  max_texture_size_ = get_integer(GL_MAX_TEXTURE_SIZE);
  max_uniform_buffer_bindings_ = get_integer(GL_MAX_UNIFORM_BUFFER_BINDINGS);
  max_texture_units_ = get_integer(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS);
  max_storage_buffer_bindings_ = get_integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
  max_uniform_block_size_ = get_integer(GL_MAX_UNIFORM_BLOCK_SIZE);
  max_3d_texture_size_ = get_integer(GL_MAX_3D_TEXTURE_SIZE);
  max_array_layers_ = get_integer(GL_MAX_ARRAY_TEXTURE_LAYERS);
  max_color_samples_ = get_integer(GL_MAX_COLOR_TEXTURE_SAMPLES);
  max_integer_samples_ = get_integer(GL_MAX_INTEGER_SAMPLES);
  // Vulkan (and Direct3D 10 on) filter across cube faces; OpenGL does only when asked.
  gl_.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);

  GLuint vertex_array = 0;
  gl_.CreateVertexArrays(1, &vertex_array);
  empty_vertex_array_ = GlVertexArray(&gl_, vertex_array);

  return check_errors(fmt::format("creating the OpenGL {} backend", context_->route()));
}

GLuint GlBackend::sampler(const SamplerDesc& desc, bool mipmapped, bool compare) {
  const auto key = std::make_tuple(desc.filter, desc.address, mipmapped,
                                   compare ? std::optional<CompareOp>(desc.compare) : std::nullopt);
  auto found = samplers_.find(key);
  if (found != samplers_.end()) return found->second.get();
  GLuint id = 0;
  gl_.CreateSamplers(1, &id);
  GlSampler sampler(&gl_, id);
  const bool linear = desc.filter == Filter::Linear;
  const GLint min_filter =
      mipmapped ? (linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST) : (linear ? GL_LINEAR : GL_NEAREST);
  const GLint mag_filter = linear ? GL_LINEAR : GL_NEAREST;
  const GLint wrap = desc.address == AddressMode::Repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
  gl_.SamplerParameteri(id, GL_TEXTURE_MIN_FILTER, min_filter);
  gl_.SamplerParameteri(id, GL_TEXTURE_MAG_FILTER, mag_filter);
  gl_.SamplerParameteri(id, GL_TEXTURE_WRAP_S, wrap);
  gl_.SamplerParameteri(id, GL_TEXTURE_WRAP_T, wrap);
  gl_.SamplerParameteri(id, GL_TEXTURE_WRAP_R, wrap);
  // A shadow sampler with compare mode NONE is undefined; any other sampler must not compare.
  gl_.SamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, compare ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  if (compare) gl_.SamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, gl_compare_function(desc.compare));
  return samplers_.emplace(key, std::move(sampler)).first->second.get();
}

void GlBackend::clear_depth_stencil(const Target& target, float depth, uint8_t stencil) {
  gl_.DepthMask(GL_TRUE);
  if (target.stencil) {
    gl_.StencilMask(0xFF);
    gl_.ClearNamedFramebufferfi(target.framebuffer.get(), GL_DEPTH_STENCIL, 0, depth, stencil);
  } else {
    gl_.ClearNamedFramebufferfv(target.framebuffer.get(), GL_DEPTH, 0, &depth);
  }
}

Result<TargetHandle> GlBackend::create_target(const TargetDesc& desc) {
  return on_context<TargetHandle>("create_target", [&]() -> Result<TargetHandle> {
    if (desc.width == 0 || desc.height == 0)
      return fail(ErrorKind::Internal, fmt::format("create_target: size {}x{} is empty", desc.width, desc.height));
    if (std::max(desc.width, desc.height) > static_cast<uint32_t>(max_texture_size_))
      return fail(ErrorKind::Backend, fmt::format("create_target: size {}x{} exceeds the driver limit of {}",
                                                  desc.width, desc.height, max_texture_size_));
    const uint32_t id = objects_.targets.next_handle().id;
    const GLsizei width = static_cast<GLsizei>(desc.width);
    const GLsizei height = static_cast<GLsizei>(desc.height);
    auto target = std::make_unique<Target>();
    // A depth texture with stencil holds both; sampled, it reads the depth
    // (GL_DEPTH_STENCIL_TEXTURE_MODE's default).
    const auto make_texture = [&](TextureFormat format, bool with_stencil = false) {
      GLuint texture = 0;
      gl_.CreateTextures(GL_TEXTURE_2D, 1, &texture);
      Texture result{GlTexture(&gl_, texture), desc.width, desc.height, 1, {}, format};
      gl_.TextureStorage2D(texture, 1, with_stencil ? GL_DEPTH32F_STENCIL8 : gl_format(format).internal_format, width,
                           height);
      return result;
    };
    target->color = make_texture(TextureFormat::Rgba32Float);
    if (desc.second_color) target->second_color = make_texture(TextureFormat::Rgba32Float);
    if (desc.stencil && !desc.depth)
      return fail(ErrorKind::Internal, "create_target: a stencil buffer needs a depth buffer");
    if (desc.depth) {
      target->depth = make_texture(TextureFormat::Depth32Float, desc.stencil);
      gl_.TextureParameteri(target->depth->texture.get(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
      target->stencil = desc.stencil;
    }
    GLuint framebuffer = 0;
    gl_.CreateFramebuffers(1, &framebuffer);
    target->framebuffer = GlFramebuffer(&gl_, framebuffer);
    gl_.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target->color.texture.get(), 0);
    if (target->depth)
      gl_.NamedFramebufferTexture(framebuffer, target->stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                                  target->depth->texture.get(), 0);
    if (target->second_color) {
      gl_.NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, target->second_color->texture.get(), 0);
      const std::array<GLenum, 2> both = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
      gl_.NamedFramebufferDrawBuffers(framebuffer, 2, both.data());
    } else {
      gl_.NamedFramebufferDrawBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    }
    gl_.NamedFramebufferReadBuffer(framebuffer, GL_COLOR_ATTACHMENT0);
    const GLenum status = gl_.CheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      return fail(ErrorKind::Backend, fmt::format("create_target: the framebuffer of target {} ({}x{}, RGBA32F{}) is "
                                                  "incomplete (status 0x{:04X})",
                                                  id, desc.width, desc.height,
                                                  desc.depth ? (desc.stencil ? " + D32F S8" : " + D32F") : "", status));
    // Start from defined contents (zero colour, far depth) so that reads before a render are
    // stable.
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    const float far_depth = 1.0f;
    gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, zero.data());
    if (target->second_color) gl_.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zero.data());
    if (target->depth) clear_depth_stencil(*target, far_depth, 0);
    return objects_.targets.insert(std::move(target));
  });
}

Result<MeshHandle> GlBackend::upload_mesh(const MeshData& data) {
  return on_context<MeshHandle>("upload_mesh", [&]() -> Result<MeshHandle> {
    if (auto valid = validate_mesh(data); !valid) return fail(valid.error());
    auto mesh = std::make_unique<Mesh>();
    GLuint buffers[2] = {0, 0};
    gl_.CreateBuffers(2, buffers);
    mesh->vertices = GlBuffer(&gl_, buffers[0]);
    mesh->indices = GlBuffer(&gl_, buffers[1]);
    gl_.NamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(data.vertices.size() * sizeof(Vertex)),
                           data.vertices.data(), 0);
    gl_.NamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(data.indices.size() * sizeof(uint32_t)),
                           data.indices.data(), 0);
    GLuint vertex_array = 0;
    gl_.CreateVertexArrays(1, &vertex_array);
    mesh->vertex_array = GlVertexArray(&gl_, vertex_array);
    gl_.VertexArrayVertexBuffer(vertex_array, 0, buffers[0], 0, sizeof(Vertex));
    gl_.VertexArrayElementBuffer(vertex_array, buffers[1]);
    struct Attribute {
      GLuint location;
      GLint components;
      GLuint offset;
    };
    for (const Attribute& attribute :
         {Attribute{0, 3, offsetof(Vertex, position)}, Attribute{1, 3, offsetof(Vertex, normal)},
          Attribute{2, 4, offsetof(Vertex, tangent)}, Attribute{3, 2, offsetof(Vertex, uv)}}) {
      gl_.EnableVertexArrayAttrib(vertex_array, attribute.location);
      gl_.VertexArrayAttribFormat(vertex_array, attribute.location, attribute.components, GL_FLOAT, GL_FALSE,
                                  attribute.offset);
      gl_.VertexArrayAttribBinding(vertex_array, attribute.location, 0);
    }
    mesh->index_count = static_cast<uint32_t>(data.indices.size());
    return objects_.meshes.insert(std::move(mesh));
  });
}

Result<TextureHandle> GlBackend::upload_texture(const TextureData& data) {
  return on_context<TextureHandle>("upload_texture", [&]() -> Result<TextureHandle> {
    if (auto valid = validate_texture(data, static_cast<uint32_t>(max_texture_size_)); !valid)
      return fail(valid.error());
    const TextureShape shape = data.shape();
    const std::string what = "upload_texture: " + shape_name(shape);
    if (data.dimension == TextureDimension::Tex3D &&
        std::max({data.width, data.height, data.layers}) > static_cast<uint32_t>(max_3d_texture_size_))
      return fail(ErrorKind::Backend, fmt::format("{}: size {}x{}x{} exceeds the driver limit of {}", what, data.width,
                                                  data.height, data.layers, max_3d_texture_size_));
    if (is_array(data.dimension) && data.layers > static_cast<uint32_t>(max_array_layers_))
      return fail(ErrorKind::Backend,
                  fmt::format("{}: {} layers exceed the driver limit of {}", what, data.layers, max_array_layers_));
    const GLint max_samples = texel_kind(data.format) == TexelKind::Float ? max_color_samples_ : max_integer_samples_;
    if (shape.multisampled && (data.samples > static_cast<uint32_t>(max_samples) || !std::has_single_bit(data.samples)))
      return fail(ErrorKind::Backend, fmt::format("{}: {} samples of {}; the driver has powers of two up to {}", what,
                                                  data.samples, format_name(data.format), max_samples));
    const GlFormat format = gl_format(data.format);
    const uint32_t levels = static_cast<uint32_t>(data.levels.size());
    GLuint id = 0;
    gl_.CreateTextures(gl_target(shape), 1, &id);
    auto texture =
        std::make_unique<Texture>(Texture{GlTexture(&gl_, id), data.width, data.height, levels, shape, data.format});
    const auto size = [](uint32_t extent, uint32_t level) {
      return static_cast<GLsizei>(std::max<uint32_t>(1, extent >> level));
    };
    const GLsizei width = static_cast<GLsizei>(data.width), height = static_cast<GLsizei>(data.height);
    const GLsizei layers = static_cast<GLsizei>(data.layers);
    // Row 0 of the data goes to t = 0, which the clip control made the top; each layer (cube
    // face, 3D slice) the same, so the faces take Direct3D's and Vulkan's data unchanged.
    if (shape.multisampled) {
      if (data.dimension == TextureDimension::Tex2D)
        gl_.TextureStorage2DMultisample(id, static_cast<GLsizei>(data.samples), format.internal_format, width, height,
                                        GL_TRUE);
      else
        gl_.TextureStorage3DMultisample(id, static_cast<GLsizei>(data.samples), format.internal_format, width, height,
                                        layers, GL_TRUE);
      if (auto filled = fill_multisampled(*texture, data, what); !filled) return fail(filled.error());
    } else {
      switch (data.dimension) {
        case TextureDimension::Tex1D:
          gl_.TextureStorage1D(id, static_cast<GLsizei>(levels), format.internal_format, width);
          for (uint32_t level = 0; level < levels; ++level)
            gl_.TextureSubImage1D(id, static_cast<GLint>(level), 0, size(data.width, level), format.format, format.type,
                                  data.levels[level].data());
          break;
        case TextureDimension::Tex1DArray:  // a 2D storage whose rows are the layers
        case TextureDimension::Tex2D: {
          const bool layered = data.dimension == TextureDimension::Tex1DArray;
          gl_.TextureStorage2D(id, static_cast<GLsizei>(levels), format.internal_format, width,
                               layered ? layers : height);
          for (uint32_t level = 0; level < levels; ++level)
            gl_.TextureSubImage2D(id, static_cast<GLint>(level), 0, 0, size(data.width, level),
                                  layered ? layers : size(data.height, level), format.format, format.type,
                                  data.levels[level].data());
          break;
        }
        case TextureDimension::Cube:  // 2D storage; the faces are addressed as the layers of TextureSubImage3D
        case TextureDimension::Tex2DArray:
        case TextureDimension::Tex3D:
        case TextureDimension::CubeArray: {
          const bool volume = data.dimension == TextureDimension::Tex3D;
          if (data.dimension == TextureDimension::Cube)
            gl_.TextureStorage2D(id, static_cast<GLsizei>(levels), format.internal_format, width, height);
          else
            gl_.TextureStorage3D(id, static_cast<GLsizei>(levels), format.internal_format, width, height, layers);
          for (uint32_t level = 0; level < levels; ++level)
            gl_.TextureSubImage3D(id, static_cast<GLint>(level), 0, 0, 0, size(data.width, level),
                                  size(data.height, level), volume ? size(data.layers, level) : layers, format.format,
                                  format.type, data.levels[level].data());
          break;
        }
      }
    }
    return objects_.textures.insert(std::move(texture));
  });
}

Result<GLuint> GlBackend::fill_program(TexelKind kind, const std::string& what) {
  if (auto found = fill_programs_.find(kind); found != fill_programs_.end()) return found->second.get();
  ShaderStageSource vertex_source{gl_support::kFillVertexShader, {}, "main", "multisample_fill.vert", {}};
  ShaderStageSource fragment_source{gl_support::fill_fragment_shader(kind), {}, "main", "multisample_fill.frag", {}};
  auto vertex = compile(vertex_source, GL_VERTEX_SHADER, "vertex", what);
  if (!vertex) return fail(vertex.error());
  auto fragment = compile(fragment_source, GL_FRAGMENT_SHADER, "fragment", what);
  if (!fragment) return fail(fragment.error());
  GlProgram program(&gl_, gl_.CreateProgram());
  gl_.AttachShader(program.get(), vertex->get());
  gl_.AttachShader(program.get(), fragment->get());
  gl_.LinkProgram(program.get());
  gl_.DetachShader(program.get(), vertex->get());
  gl_.DetachShader(program.get(), fragment->get());
  GLint linked = GL_FALSE;
  gl_.GetProgramiv(program.get(), GL_LINK_STATUS, &linked);
  if (linked != GL_TRUE) return fail(ErrorKind::Backend, what + ": the multisample fill program does not link");
  return fill_programs_.emplace(kind, std::move(program)).first->second.get();
}

Result<void> GlBackend::fill_multisampled(const Texture& texture, const TextureData& data, const std::string& what) {
  // Multisampled storage takes no pixel uploads: the data goes into a single-sampled 2D array
  // first, and a draw per layer copies it into every sample.
  const GlFormat format = gl_format(data.format);
  const GLsizei width = static_cast<GLsizei>(data.width), height = static_cast<GLsizei>(data.height);
  const GLsizei layers = static_cast<GLsizei>(data.layers);
  GLuint source_id = 0;
  gl_.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &source_id);
  GlTexture source(&gl_, source_id);
  gl_.TextureStorage3D(source_id, 1, format.internal_format, width, height, layers);
  gl_.TextureSubImage3D(source_id, 0, 0, 0, 0, width, height, layers, format.format, format.type,
                        data.levels[0].data());
  // An integer texture filtered linearly is incomplete, and texelFetch of one reads nothing.
  gl_.TextureParameteri(source_id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TextureParameteri(source_id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  auto program = fill_program(texel_kind(data.format), what);
  if (!program) return fail(program.error());
  const GLint layer_location = gl_.GetUniformLocation(*program, "layer");
  GLuint framebuffer_id = 0;
  gl_.CreateFramebuffers(1, &framebuffer_id);
  GlFramebuffer framebuffer(&gl_, framebuffer_id);
  gl_.NamedFramebufferDrawBuffer(framebuffer_id, GL_COLOR_ATTACHMENT0);
  gl_.UseProgram(*program);
  gl_.BindTextureUnit(0, source_id);
  gl_.BindSampler(0, 0);
  gl_.BindVertexArray(empty_vertex_array_.get());
  gl_.Disable(GL_DEPTH_TEST);
  gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl_.Viewport(0, 0, width, height);
  Result<void> result;
  for (GLsizei layer = 0; layer < layers && result; ++layer) {
    if (data.dimension == TextureDimension::Tex2D)
      gl_.NamedFramebufferTexture(framebuffer_id, GL_COLOR_ATTACHMENT0, texture.texture.get(), 0);
    else
      gl_.NamedFramebufferTextureLayer(framebuffer_id, GL_COLOR_ATTACHMENT0, texture.texture.get(), 0, layer);
    const GLenum status = gl_.CheckNamedFramebufferStatus(framebuffer_id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      result = fail(ErrorKind::Backend,
                    fmt::format("{}: the framebuffer that fills layer {} ({} samples of {}) is incomplete "
                                "(status 0x{:04X})",
                                what, layer, data.samples, format_name(data.format), status));
      break;
    }
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_id);
    gl_.ProgramUniform1i(*program, layer_location, layer);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  gl_.Finish();
  gl_.BindTextureUnit(0, 0);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  return result;
}

Result<GlShader> GlBackend::compile(const ShaderStageSource& source, GLenum stage, const char* stage_name,
                                    const std::string& what) {
  const std::string shader = fmt::format("{}: the {} shader '{}'", what, stage_name, source.name);
  if (source.glsl.empty()) return fail(ErrorKind::Internal, shader + " has no GLSL");
  if (source.entry_point != "main")
    return fail(ErrorKind::Internal,
                fmt::format("{} has entry point '{}', but OpenGL calls 'main' only", shader, source.entry_point));
  GlShader object(&gl_, gl_.CreateShader(stage));
  if (!object) return fail(ErrorKind::Backend, shader + ": glCreateShader failed");
  const GLchar* text = source.glsl.c_str();
  const GLint length = static_cast<GLint>(source.glsl.size());
  gl_.ShaderSource(object.get(), 1, &text, &length);
  gl_.CompileShader(object.get());
  GLint status = GL_FALSE;
  gl_.GetShaderiv(object.get(), GL_COMPILE_STATUS, &status);
  if (status == GL_TRUE) return object;

  GLint log_length = 0;
  gl_.GetShaderiv(object.get(), GL_INFO_LOG_LENGTH, &log_length);
  std::string log(static_cast<size_t>(std::max(log_length, 1)), '\0');
  GLsizei written = 0;
  gl_.GetShaderInfoLog(object.get(), static_cast<GLsizei>(log.size()), &written, log.data());
  log.resize(static_cast<size_t>(std::max(written, 0)));
  Error error;
  error.diagnostics = parse_log(log, source.name, source.source_files);
  error.message = shader + " does not compile";
  auto first = std::find_if(error.diagnostics.begin(), error.diagnostics.end(),
                            [](const Diagnostic& d) { return d.severity == Severity::Error; });
  if (first == error.diagnostics.end() && !error.diagnostics.empty()) first = error.diagnostics.begin();
  if (first != error.diagnostics.end()) {
    error.message += ": " + first->message;
    error.where = first->where;
  }
  if (error.where.file.empty()) error.where.file = source.name;
  if (error.diagnostics.empty())
    error.diagnostics.push_back(Diagnostic{Severity::Error, {source.name, 0, 0}, "the compiler gave no log"});
  return fail(std::move(error));
}

Result<ProgramHandle> GlBackend::create_program(const ProgramDesc& desc) {
  const std::string what = fmt::format("create_program '{}'", desc.name);
  // The compiler's messages wait until the outcome is known: a failure carries them in its
  // diagnostics, a success hands them on as driver messages naming the program.
  {
    std::lock_guard lock(log_->mutex);
    log_->held.emplace();
  }
  Result<ProgramHandle> result = on_context<ProgramHandle>(what, [&]() -> Result<ProgramHandle> {
    // The layout first: GL's limits, names and bindings used once.
    std::set<std::string> names;
    std::map<uint32_t, std::string> block_bindings, texture_units;
    for (const UniformBlockSlot& slot : desc.layout.uniform_blocks) {
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      if (slot.size == 0 || slot.size > static_cast<uint32_t>(max_uniform_block_size_))
        return fail(ErrorKind::Backend, fmt::format("{}: uniform block '{}' has size {}; the driver allows 1..{} bytes",
                                                    what, slot.name, slot.size, max_uniform_block_size_));
      if (slot.binding >= static_cast<uint32_t>(max_uniform_buffer_bindings_))
        return fail(ErrorKind::Backend, fmt::format("{}: uniform block '{}' has binding {}, but OpenGL allows "
                                                    "0..{} (GL_MAX_UNIFORM_BUFFER_BINDINGS)",
                                                    what, slot.name, slot.binding, max_uniform_buffer_bindings_ - 1));
      if (auto [it, fresh] = block_bindings.emplace(slot.binding, slot.name); !fresh)
        return fail(ErrorKind::Internal, fmt::format("{}: binding {} is used by both uniform block '{}' and uniform "
                                                     "block '{}'",
                                                     what, slot.binding, it->second, slot.name));
    }
    for (const TextureSlot& slot : desc.layout.textures) {
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      if (slot.binding >= static_cast<uint32_t>(max_texture_units_))
        return fail(ErrorKind::Backend, fmt::format("{}: texture '{}' has binding {}, but OpenGL allows 0..{} "
                                                    "(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS)",
                                                    what, slot.name, slot.binding, max_texture_units_ - 1));
      if (auto [it, fresh] = texture_units.emplace(slot.binding, slot.name); !fresh)
        return fail(ErrorKind::Internal, fmt::format("{}: binding {} is used by both texture '{}' and texture '{}'",
                                                     what, slot.binding, it->second, slot.name));
    }
    std::map<uint32_t, std::string> storage_bindings;
    for (const StorageBufferSlot& slot : desc.layout.storage_buffers) {
      if (!names.insert(slot.name).second)
        return fail(ErrorKind::Internal, fmt::format("{}: the layout names '{}' twice", what, slot.name));
      if (slot.binding >= static_cast<uint32_t>(max_storage_buffer_bindings_))
        return fail(ErrorKind::Backend, fmt::format("{}: storage buffer '{}' has binding {}, but OpenGL allows 0..{} "
                                                    "(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS)",
                                                    what, slot.name, slot.binding, max_storage_buffer_bindings_ - 1));
      if (auto [it, fresh] = storage_bindings.emplace(slot.binding, slot.name); !fresh)
        return fail(ErrorKind::Internal,
                    fmt::format("{}: binding {} is used by both storage buffer '{}' and storage buffer '{}'", what,
                                slot.binding, it->second, slot.name));
    }

    // Each step's messages, or (when Mesa's shader cache skipped the step) those it gave before.
    const std::string driver = info_.renderer + '\n' + info_.driver_version;
    const auto held_count = [&] {
      std::lock_guard lock(log_->mutex);
      return log_->held->size();
    };
    const auto settle = [&](size_t from, const std::string& source) {
      std::lock_guard lock(log_->mutex);
      std::vector<std::string>& held = *log_->held;
      std::vector<std::string> step(held.begin() + std::ptrdiff_t(from), held.end());
      held.resize(from);
      for (std::string& message : compile_messages_.settle(driver, source, std::move(step)))
        held.push_back(std::move(message));
    };
    size_t before = held_count();
    auto vertex = compile(desc.vertex, GL_VERTEX_SHADER, "vertex", what);
    if (!vertex) return fail(vertex.error());
    settle(before, desc.vertex.glsl);
    before = held_count();
    auto fragment = compile(desc.fragment, GL_FRAGMENT_SHADER, "fragment", what);
    if (!fragment) return fail(fragment.error());
    settle(before, desc.fragment.glsl);
    before = held_count();

    auto program = std::make_unique<Program>();
    program->name = desc.name;
    program->layout = desc.layout;
    program->fullscreen = desc.fullscreen;
    program->clip_distances = desc.clip_distances;
    program->program = GlProgram(&gl_, gl_.CreateProgram());
    const GLuint id = program->program.get();
    gl_.AttachShader(id, vertex->get());
    gl_.AttachShader(id, fragment->get());
    gl_.LinkProgram(id);
    gl_.DetachShader(id, vertex->get());
    gl_.DetachShader(id, fragment->get());
    GLint linked = GL_FALSE;
    gl_.GetProgramiv(id, GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
      GLint log_length = 0;
      gl_.GetProgramiv(id, GL_INFO_LOG_LENGTH, &log_length);
      std::string log(static_cast<size_t>(std::max(log_length, 1)), '\0');
      GLsizei written = 0;
      gl_.GetProgramInfoLog(id, static_cast<GLsizei>(log.size()), &written, log.data());
      log.resize(static_cast<size_t>(std::max(written, 0)));
      Error error;
      error.diagnostics = parse_log(log, {});
      error.message = fmt::format(
          "{}: the vertex shader '{}' and the fragment shader '{}' do not "
          "link",
          what, desc.vertex.name, desc.fragment.name);
      auto first = std::find_if(error.diagnostics.begin(), error.diagnostics.end(),
                                [](const Diagnostic& d) { return d.severity == Severity::Error; });
      if (first != error.diagnostics.end()) error.message += ": " + first->message;
      if (error.diagnostics.empty())
        error.diagnostics.push_back(Diagnostic{Severity::Error, {}, "the linker gave no log"});
      return fail(std::move(error));
    }
    settle(before, desc.vertex.glsl + '\0' + desc.fragment.glsl);  // the link's own

    if (auto checked = gl_support::check_interface(gl_, id, program->layout, program->fullscreen,
                                                   program->unsupplied_inputs, what);
        !checked)
      return fail(checked.error());

    // Bindings by name, from the layout.
    for (const UniformBlockSlot& slot : desc.layout.uniform_blocks) {
      const GLuint index = gl_.GetUniformBlockIndex(id, slot.glsl_block_name().c_str());
      if (index != GL_INVALID_INDEX) gl_.UniformBlockBinding(id, index, slot.binding);
      GLuint buffer = 0;
      gl_.CreateBuffers(1, &buffer);
      program->uniform_buffers.emplace_back(&gl_, buffer);
    }
    for (const TextureSlot& slot : desc.layout.textures) {
      const GLint location = gl_.GetUniformLocation(id, slot.uniform_name().c_str());
      if (location >= 0) gl_.ProgramUniform1i(id, location, static_cast<GLint>(slot.binding));
    }
    for (size_t s = 0; s < desc.layout.storage_buffers.size(); ++s) {
      GLuint buffer = 0;
      gl_.CreateBuffers(1, &buffer);
      program->storage_buffers.emplace_back(&gl_, buffer);
    }
    return objects_.programs.insert(std::move(program));
  });

  std::lock_guard lock(log_->mutex);
  std::vector<std::string> held = std::move(*log_->held);
  log_->held.reset();
  if (result)
    for (std::string& message : held) log_->messages.push_back(fmt::format("program '{}': {}", desc.name, message));
  return result;
}

Result<void> GlBackend::render(const RenderPass& pass) {
  const std::string what = fmt::format("render into target {}", pass.target.id);
  return on_context<void>(what, [&]() -> Result<void> {
    // Resolve every draw before drawing anything.
    auto resolved = resolve_pass(objects_, pass, what, [](const Texture& texture) {
      return std::pair{texture.shape, texture.format};
    });
    if (!resolved) return fail(resolved.error());
    const Target* target = resolved->target;

    // The pass: clear, then each draw.
    const GLuint framebuffer = target->framebuffer.get();
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl_.Viewport(0, 0, static_cast<GLsizei>(target->color.width), static_cast<GLsizei>(target->color.height));
    gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const std::array<float, 4> clear = {pass.clear_color.r, pass.clear_color.g, pass.clear_color.b, pass.clear_color.a};
    gl_.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, clear.data());
    if (target->second_color) {
      const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
      gl_.ClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, zero.data());
    }
    if (target->depth) {
      gl_.Enable(GL_DEPTH_TEST);
      gl_.DepthFunc(GL_LESS);
      clear_depth_stencil(*target, pass.clear_depth, pass.clear_stencil);
    } else {
      gl_.Disable(GL_DEPTH_TEST);
    }

    std::set<GLuint> used_units;
    std::vector<std::byte> padded;
    for (size_t d = 0; d < resolved->draws.size(); ++d) {
      const auto& draw = resolved->draws[d];
      const Program& program = *draw.program;
      // A full-screen program's uv (0, 0) is row 0 whatever the pass's row origin (backend.h).
      apply_draw_state(gl_, pass.draws[d].state, target->depth.has_value(), target->stencil,
                       pass.row_origin == RowOrigin::Bottom && !program.fullscreen);
      gl_.UseProgram(program.program.get());
      gl_support::enable_clip_planes(gl_, program.clip_distances);
      const auto& blocks = program.layout.uniform_blocks;
      for (size_t s = 0; s < blocks.size(); ++s) {
        const std::vector<std::byte>& bytes = draw.uniforms[s]->bytes;
        // Padded to 16 bytes: std140 rounds a block's size up to a vec4.
        padded.assign(round_up_16(blocks[s].size), std::byte{0});
        std::copy(bytes.begin(), bytes.end(), padded.begin());
        const GLuint buffer = program.uniform_buffers[s].get();
        gl_.NamedBufferData(buffer, static_cast<GLsizeiptr>(padded.size()), padded.data(), GL_STREAM_DRAW);
        gl_.BindBufferBase(GL_UNIFORM_BUFFER, blocks[s].binding, buffer);
      }
      const auto& storage = program.layout.storage_buffers;
      for (size_t s = 0; s < storage.size(); ++s) {
        const std::vector<std::byte>& bytes = draw.storage_buffers[s]->bytes;
        const GLuint buffer = program.storage_buffers[s].get();
        gl_.NamedBufferData(buffer, static_cast<GLsizeiptr>(bytes.size()), bytes.data(), GL_STREAM_DRAW);
        gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, storage[s].binding, buffer);
      }
      const auto& slots = program.layout.textures;
      for (size_t s = 0; s < slots.size(); ++s) {
        const auto& bound = draw.textures[s];
        gl_.BindTextureUnit(slots[s].binding, bound.texture->texture.get());
        gl_.BindSampler(slots[s].binding, sampler(bound.sampler, bound.texture->levels > 1, slots[s].comparison));
        used_units.insert(slots[s].binding);
      }
      if (program.fullscreen) {
        gl_.BindVertexArray(empty_vertex_array_.get());
        gl_.DrawArrays(GL_TRIANGLES, 0, 3);
      } else {
        // Attributes outside the vertex array read the generic current value.
        for (const auto& [location, kind] : program.unsupplied_inputs) {
          const float value = unsupplied_input_reads_white(location) ? 1.0f : 0.0f;
          if (kind == TexelKind::Float) gl_.VertexAttrib4f(location, value, value, value, value);
          if (kind == TexelKind::Int) gl_.VertexAttribI4i(location, 0, 0, 0, 0);
          if (kind == TexelKind::Uint) gl_.VertexAttribI4ui(location, 0, 0, 0, 0);
        }
        gl_.BindVertexArray(draw.mesh->vertex_array.get());
        gl_.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(draw.mesh->index_count), GL_UNSIGNED_INT, nullptr);
      }
    }
    gl_.Finish();

    // Nothing stays bound that a later pass might render into.
    for (GLuint unit : used_units) {
      gl_.BindTextureUnit(unit, 0);
      gl_.BindSampler(unit, 0);
    }
    gl_.BindVertexArray(0);
    gl_.UseProgram(0);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    apply_draw_state(gl_, {}, false, false);
    return {};
  });
}

Result<FloatImage> GlBackend::read_color(TargetHandle handle) { return read_texture(handle, false); }
Result<FloatImage> GlBackend::read_second_color(TargetHandle handle) { return read_texture(handle, true); }

Result<FloatImage> GlBackend::read_texture(TargetHandle handle, bool second) {
  const std::string what = fmt::format("{} of target {}", second ? "read_second_color" : "read_color", handle.id);
  return on_context<FloatImage>(what, [&]() -> Result<FloatImage> {
    auto found = objects_.targets.find(handle, what);
    if (!found) return fail(found.error());
    const Target* target = *found;
    if (second && !target->second_color)
      return fail(ErrorKind::Internal, what + ": the target has no second colour attachment");
    const Texture& texture = second ? *target->second_color : target->color;
    FloatImage result(texture.width, texture.height);
    // Texture row 0 is window row 0, which the clip control made the top: no flip.
    gl_.GetTextureImage(texture.texture.get(), 0, GL_RGBA, GL_FLOAT,
                        static_cast<GLsizei>(result.rgba.size() * sizeof(float)), result.rgba.data());
    return result;
  });
}

}  // namespace

Result<std::unique_ptr<Backend>> create_gl_backend(std::unique_ptr<GlContext> context,
                                                   const std::filesystem::path& compile_messages) {
  if (context == nullptr) return fail(ErrorKind::Internal, "creating the OpenGL backend: no context");
  const std::string route(context->route());
  try {
    auto backend = std::make_unique<GlBackend>();
    if (auto ok = backend->init(std::move(context), compile_messages); !ok) return fail(ok.error());
    return std::unique_ptr<Backend>(std::move(backend));
  } catch (const std::exception& e) {
    return fail(ErrorKind::Backend, fmt::format("creating the OpenGL {} backend: {}", route, e.what()));
  } catch (...) {
    return fail(ErrorKind::Backend, fmt::format("creating the OpenGL {} backend: unknown exception", route));
  }
}

Result<std::unique_ptr<Backend>> create_gl_backend(const GlContextOptions& options) {
  auto context = create_gl_context(options);
  if (!context) return fail(context.error());
  return create_gl_backend(std::move(*context), options.compile_messages);
}

}  // namespace xshade::harness
