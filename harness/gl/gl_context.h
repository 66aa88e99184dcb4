// An OpenGL 4.5 core context on Mesa's llvmpipe, apart from what is drawn with it: the OpenGL
// backend (gl_backend.h) draws, a GlContext only says how the context was made. Two routes make
// one, each opening its library at run time (dlopen) so that the binary links neither:
//
//   OSMesa           libOSMesa.so.8 (Debian: libosmesa6); Mesa removed it in 25.1
//   EGL surfaceless  libEGL.so.1 (libegl1, glvnd) with Mesa's vendor library (libegl-mesa0) and
//                    its software driver swrast_dri.so (libgl1-mesa-dri); forced to llvmpipe
//
// Both routes bind their contexts through Mesa's one glapi dispatch, so neither platform's own
// "current context" query can be trusted once the other has made a context current
// (eglGetCurrentContext still names the EGL context after OSMesaMakeCurrent took the dispatch).
// What the harness made current last on each thread is recorded here instead, and is the answer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"

namespace xshade::harness {

// How the gl lane gets its context. Auto: OSMesa when its library opens, else EGL surfaceless.
enum class GlPlatform { Auto, Osmesa, Egl };

std::string_view gl_platform_name(GlPlatform platform);  // "auto", "osmesa", "egl"
std::optional<GlPlatform> parse_gl_platform(std::string_view name);

class GlContext {
 public:
  virtual ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread, unless the harness already made it the
  // current one there last. False when the platform refuses.
  bool make_current();
  // Whether this is the context the harness made current on the calling thread last.
  bool is_current() const;

  // The address of an OpenGL entry point by its full name ("glClear"), or null.
  virtual void* proc_address(const char* name) const = 0;
  // The route, as DriverInfo::api names it: "OSMesa" or "EGL surfaceless".
  virtual std::string_view route() const = 0;
  // The Debian packages that provide this route's driver, for messages ("libosmesa6").
  virtual std::string_view packages() const = 0;

 protected:
  GlContext();
  // The platform's own make-current call for this context.
  virtual bool bind() = 0;
  // After a platform call that may have moved Mesa's dispatch (releasing or destroying a
  // context): the next make_current of any context binds it again.
  static void forget_current();
  // Mesa's on-disk shader cache skips compiling shaders it has seen, and with the compile go its
  // warnings: results would depend on earlier runs. Called before a route's first context; a
  // setting already made is kept (the user's, or create_backend's when it gives the cache a
  // folder and keeps the warnings, harness/render/lanes.h).
  static void disable_shader_cache();

 private:
  uint64_t id_;  // unique in the process, so that a new context never inherits a dead one's record
};

struct GlContextOptions {
  GlPlatform platform = GlPlatform::Auto;
  // The libraries opened at run time. Empty: $XSHADE_OSMESA_LIBRARY / $XSHADE_EGL_LIBRARY when
  // set, else libOSMesa.so.8 / libEGL.so.1.
  std::string osmesa_library{};
  std::string egl_library{};
  // Where the backend keeps the compile messages Mesa's shader cache would lose
  // (compile_messages.h); empty when the cache is off.
  std::filesystem::path compile_messages{};
};

// A context by the route asked for. Auto tries OSMesa, and EGL when OSMesa's library does not
// open (an OSMesa that opens but fails is reported, not hidden); when no route works, one error
// says what was tried and which packages to install.
Result<std::unique_ptr<GlContext>> create_gl_context(const GlContextOptions& options = {});

// One route each (osmesa_context.cpp, egl_context.cpp). `library` as in GlContextOptions. Each
// fails with a message naming the Debian package to install when something is missing, and
// returns the context current on the calling thread.
Result<std::unique_ptr<GlContext>> create_osmesa_context(const std::string& library = {});
Result<std::unique_ptr<GlContext>> create_egl_context(const std::string& library = {});

}  // namespace xshade::harness
