// The OSMesa route to an OpenGL 4.5 core context on llvmpipe. libOSMesa is opened at run time;
// the context renders into a 1x1 dummy buffer that nothing reads (the backend draws into
// framebuffer objects). Mesa removed OSMesa in 25.1; egl_context.cpp is the other route.
#include <array>
#include <vector>

#include <fmt/format.h>

#include "harness/gl/gl_context.h"
#include "harness/gl/gl_functions.h"
#include "harness/gl/shared_library.h"
// After glcorearb.h (from gl_functions.h); osmesa.h brings GL/gl.h, whose declarations agree.
#include <GL/osmesa.h>

namespace xshade::harness {
namespace {

constexpr const char* kDebianPackage = "libosmesa6";

struct OsmesaFunctions {
  decltype(&OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) MakeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) DestroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) GetProcAddress = nullptr;
};

class OsmesaContext final : public GlContext {
 public:
  ~OsmesaContext() override {
    if (context_ != nullptr) osmesa_.DestroyContext(context_);
  }

  Result<void> init(const std::string& requested) {
    disable_shader_cache();
    const std::string library = library_name(requested, "XSHADE_OSMESA_LIBRARY", "libOSMesa.so.8");
    auto opened = SharedLibrary::open(library);
    if (!opened)
      return fail(ErrorKind::Backend, fmt::format("cannot open OSMesa library '{}' ({}); install the Debian package {}",
                                                  library, opened.error().message, kDebianPackage));
    library_ = std::move(*opened);

    std::vector<std::string> missing;
    library_.load(osmesa_.CreateContextAttribs, "OSMesaCreateContextAttribs", missing);
    library_.load(osmesa_.MakeCurrent, "OSMesaMakeCurrent", missing);
    library_.load(osmesa_.DestroyContext, "OSMesaDestroyContext", missing);
    library_.load(osmesa_.GetProcAddress, "OSMesaGetProcAddress", missing);
    if (!missing.empty())
      return fail(ErrorKind::Backend, fmt::format("'{}' lacks {}; install the Debian package {}", library,
                                                  fmt::join(missing, ", "), kDebianPackage));

    const std::array<int, 15> attributes = {OSMESA_FORMAT,
                                            OSMESA_RGBA,
                                            OSMESA_DEPTH_BITS,
                                            0,
                                            OSMESA_STENCIL_BITS,
                                            0,
                                            OSMESA_ACCUM_BITS,
                                            0,
                                            OSMESA_PROFILE,
                                            OSMESA_CORE_PROFILE,
                                            OSMESA_CONTEXT_MAJOR_VERSION,
                                            4,
                                            OSMESA_CONTEXT_MINOR_VERSION,
                                            5,
                                            0};
    context_ = osmesa_.CreateContextAttribs(attributes.data(), nullptr);
    if (context_ == nullptr)
      return fail(
          ErrorKind::Backend,
          fmt::format("OSMesaCreateContextAttribs in '{}' cannot make an OpenGL 4.5 core context (Mesa's llvmpipe is "
                      "needed; install the Debian package {})",
                      library, kDebianPackage));
    if (!make_current())
      return fail(ErrorKind::Backend,
                  fmt::format("OSMesaMakeCurrent in '{}' failed for a new 4.5 core context", library));
    return {};
  }

  void* proc_address(const char* name) const override {
    // A function pointer travels through void* here, as with dlsym; POSIX guarantees this works.
    return reinterpret_cast<void*>(osmesa_.GetProcAddress(name));
  }
  std::string_view route() const override { return "OSMesa"; }
  std::string_view packages() const override { return kDebianPackage; }

 protected:
  bool bind() override {
    return osmesa_.MakeCurrent(context_, dummy_buffer_.data(), GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE;
  }

 private:
  SharedLibrary library_;
  OsmesaFunctions osmesa_;
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> dummy_buffer_{};  // the 1x1 RGBA buffer the context is bound to
};

}  // namespace

Result<std::unique_ptr<GlContext>> create_osmesa_context(const std::string& library) {
  auto context = std::make_unique<OsmesaContext>();
  if (auto ok = context->init(library); !ok) return fail(ok.error());
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace xshade::harness
