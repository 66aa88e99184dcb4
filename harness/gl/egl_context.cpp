// The EGL surfaceless route to an OpenGL 4.5 core context on llvmpipe: Mesa's
// EGL_MESA_platform_surfaceless display, a context without a config
// (EGL_KHR_no_config_context), made current without a surface (EGL_KHR_surfaceless_context);
// the backend draws into framebuffer objects only. libEGL.so.1 (glvnd) is opened at run time and
// finds Mesa through its vendor library (libegl-mesa0), which loads swrast_dri.so
// (libgl1-mesa-dri). This route works on every Mesa, including 25.1 and later, which have no OSMesa.
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "harness/gl/gl_context.h"
#include "harness/gl/gl_functions.h"
#include "harness/gl/shared_library.h"
// USE_X11 is not defined, so eglplatform.h declares its native types without X11's headers.
#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace xshade::harness {
namespace {

constexpr const char* kLoaderPackage = "libegl1";          // libEGL.so.1, glvnd's dispatcher
constexpr const char* kVendorPackage = "libegl-mesa0";     // Mesa's EGL, which glvnd finds
constexpr const char* kDriverPackage = "libgl1-mesa-dri";  // swrast_dri.so: llvmpipe for EGL

struct EglFunctions {
  PFNEGLGETPROCADDRESSPROC GetProcAddress = nullptr;
  PFNEGLGETERRORPROC GetError = nullptr;
  PFNEGLQUERYSTRINGPROC QueryString = nullptr;
  PFNEGLINITIALIZEPROC Initialize = nullptr;
  PFNEGLBINDAPIPROC BindAPI = nullptr;
  PFNEGLCREATECONTEXTPROC CreateContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC DestroyContext = nullptr;
  PFNEGLMAKECURRENTPROC MakeCurrent = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC GetCurrentContext = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplayEXT = nullptr;  // through GetProcAddress
};

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
  }
  return fmt::format("EGL error 0x{:04X}", error);
}

// Whether the space-separated extension list names `extension` exactly.
bool has_extension(const char* list, std::string_view extension) {
  if (list == nullptr) return false;
  std::string_view rest(list);
  while (!rest.empty()) {
    const size_t end = std::min(rest.find(' '), rest.size());
    if (rest.substr(0, end) == extension) return true;
    rest.remove_prefix(std::min(end + 1, rest.size()));
  }
  return false;
}

std::string environment_value(const char* name) {
  const char* value = std::getenv(name);
  return value ? fmt::format("{}={}", name, value) : fmt::format("{} unset", name);
}

class EglContext final : public GlContext {
 public:
  ~EglContext() override {
    if (context_ == EGL_NO_CONTEXT) return;
    // A context EGL holds current is only marked for deletion; released, it goes now.
    if (egl_.GetCurrentContext() == context_)
      egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    egl_.DestroyContext(display_, context_);
    // The display stays initialized (no eglTerminate): it is one per process and shared by every
    // EGL context; terminating it would destroy the others' contexts, and initializing it again
    // would unload and reload swrast_dri.so for nothing.
  }

  Result<void> init(const std::string& requested) {
    disable_shader_cache();
    // llvmpipe, never the GPU the machine happens to have: the gl lane's goldens are llvmpipe's.
    // On the surfaceless platform Mesa tries the hardware driver of each render node first, and
    // only LIBGL_ALWAYS_SOFTWARE makes it skip them for the software driver (swrast, or kms_swrast
    // on vgem/virtio-gpu), whose gallium driver GALLIUM_DRIVER names (llvmpipe, not softpipe or
    // zink). Both are read by eglInitialize, so they are set before it. A user's own setting is kept
    // (as OSMesa, which reads GALLIUM_DRIVER too, keeps it) and the renderer is checked below: a
    // setting that leads elsewhere fails with the variables named, instead of being overridden
    // behind the user's back.
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    setenv("GALLIUM_DRIVER", "llvmpipe", 0);

    const std::string library = library_name(requested, "XSHADE_EGL_LIBRARY", "libEGL.so.1");
    auto opened = SharedLibrary::open(library);
    if (!opened)
      return fail(ErrorKind::Backend, fmt::format("cannot open EGL library '{}' ({}); install the Debian package {}",
                                                  library, opened.error().message, kLoaderPackage));
    library_ = std::move(*opened);

    std::vector<std::string> missing;
    library_.load(egl_.GetProcAddress, "eglGetProcAddress", missing);
    library_.load(egl_.GetError, "eglGetError", missing);
    library_.load(egl_.QueryString, "eglQueryString", missing);
    library_.load(egl_.Initialize, "eglInitialize", missing);
    library_.load(egl_.BindAPI, "eglBindAPI", missing);
    library_.load(egl_.CreateContext, "eglCreateContext", missing);
    library_.load(egl_.DestroyContext, "eglDestroyContext", missing);
    library_.load(egl_.MakeCurrent, "eglMakeCurrent", missing);
    library_.load(egl_.GetCurrentContext, "eglGetCurrentContext", missing);
    if (!missing.empty())
      return fail(ErrorKind::Backend, fmt::format("'{}' lacks {}; install the Debian package {}", library,
                                                  fmt::join(missing, ", "), kLoaderPackage));

    // Client extensions: what the installed vendors offer before any display exists.
    const char* client = egl_.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    for (const char* needed : {"EGL_EXT_platform_base", "EGL_MESA_platform_surfaceless"})
      if (!has_extension(client, needed))
        return fail(ErrorKind::Backend,
                    fmt::format("EGL in '{}' does not offer {} (client extensions: {}); Mesa's EGL provides it: "
                                "install the Debian package {}",
                                library, needed, client ? client : "none", kVendorPackage));
    egl_.GetPlatformDisplayEXT =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl_.GetProcAddress("eglGetPlatformDisplayEXT"));
    if (egl_.GetPlatformDisplayEXT == nullptr)
      return fail(ErrorKind::Backend,
                  fmt::format("EGL in '{}' lists EGL_EXT_platform_base but has no eglGetPlatformDisplayEXT", library));

    display_ = egl_.GetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY)
      return fail(ErrorKind::Backend,
                  fmt::format("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA) in '{}' gives no display "
                              "({}); install the Debian package {}",
                              library, egl_error_name(egl_.GetError()), kVendorPackage));
    EGLint major = 0, minor = 0;
    if (egl_.Initialize(display_, &major, &minor) != EGL_TRUE)
      return fail(ErrorKind::Backend,
                  fmt::format("eglInitialize of the surfaceless display failed ({}): Mesa's software driver "
                              "swrast_dri.so is needed; install the Debian package {}",
                              egl_error_name(egl_.GetError()), kDriverPackage));

    const char* extensions = egl_.QueryString(display_, EGL_EXTENSIONS);
    for (const char* needed : {"EGL_KHR_create_context", "EGL_KHR_no_config_context", "EGL_KHR_surfaceless_context"})
      if (!has_extension(extensions, needed))
        return fail(ErrorKind::Backend,
                    fmt::format("the EGL surfaceless display (EGL {}.{}, '{}') lacks {}; install a newer Debian "
                                "package {}",
                                major, minor, library, needed, kVendorPackage));
    if (egl_.BindAPI(EGL_OPENGL_API) != EGL_TRUE)
      return fail(ErrorKind::Backend,
                  fmt::format("eglBindAPI(EGL_OPENGL_API) failed ({}): this EGL offers no desktop OpenGL",
                              egl_error_name(egl_.GetError())));

    // As the OSMesa route: no debug flag (KHR_debug output is enabled on the context instead).
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = egl_.CreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT)
      return fail(ErrorKind::Backend,
                  fmt::format("eglCreateContext cannot make an OpenGL 4.5 core context on the surfaceless display "
                              "({}); Mesa's llvmpipe is needed ({}, {}: xshade sets LIBGL_ALWAYS_SOFTWARE=1 and "
                              "GALLIUM_DRIVER=llvmpipe when they are unset): install the Debian package {}",
                              egl_error_name(egl_.GetError()), environment_value("LIBGL_ALWAYS_SOFTWARE"),
                              environment_value("GALLIUM_DRIVER"), kDriverPackage));
    if (!make_current())
      return fail(ErrorKind::Backend, fmt::format("eglMakeCurrent failed for a new 4.5 core context ({})",
                                                  egl_error_name(egl_.GetError())));

    const auto get_string = reinterpret_cast<PFNGLGETSTRINGPROC>(proc_address("glGetString"));
    const GLubyte* text = get_string ? get_string(GL_RENDERER) : nullptr;
    const std::string renderer = text ? reinterpret_cast<const char*>(text) : "";
    // "llvmpipe (LLVM 15.0.6, 256 bits)"; zink on lavapipe says "zink (llvmpipe (...))".
    if (!renderer.starts_with("llvmpipe"))
      return fail(ErrorKind::Backend,
                  fmt::format("EGL surfaceless gives the renderer '{}', not llvmpipe, which the gl lane's goldens "
                              "come from ({}, {}: xshade sets LIBGL_ALWAYS_SOFTWARE=1 and GALLIUM_DRIVER=llvmpipe "
                              "when they are unset); install the Debian package {}",
                              renderer.empty() ? "(none)" : renderer, environment_value("LIBGL_ALWAYS_SOFTWARE"),
                              environment_value("GALLIUM_DRIVER"), kDriverPackage));
    return {};
  }

  void* proc_address(const char* name) const override {
    // A function pointer travels through void* here, as with dlsym; POSIX guarantees this works.
    return reinterpret_cast<void*>(egl_.GetProcAddress(name));
  }
  std::string_view route() const override { return "EGL surfaceless"; }
  std::string_view packages() const override { return "libegl1, libegl-mesa0 and libgl1-mesa-dri"; }

 protected:
  bool bind() override {
    // After another route's MakeCurrent took Mesa's dispatch, EGL still believes this context is
    // current, and eglMakeCurrent of the context EGL believes current returns without binding
    // anything. Released first, it is bound for real.
    if (egl_.GetCurrentContext() == context_ &&
        egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT) != EGL_TRUE)
      return false;
    return egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE;
  }

 private:
  SharedLibrary library_;
  EglFunctions egl_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

Result<std::unique_ptr<GlContext>> create_egl_context(const std::string& library) {
  auto context = std::make_unique<EglContext>();
  if (auto ok = context->init(library); !ok) return fail(ok.error());
  return std::unique_ptr<GlContext>(std::move(context));
}

}  // namespace xshade::harness
