#include "harness/gl/gl_context.h"

#include <atomic>
#include <cstdlib>

#include <fmt/format.h>

#include "harness/gl/shared_library.h"

namespace xshade::harness {
namespace {

// The id of the context the harness made current on this thread last; 0: none, or unknown.
thread_local uint64_t current_context = 0;
std::atomic<uint64_t> next_context_id{1};

}  // namespace

std::string_view gl_platform_name(GlPlatform platform) {
  switch (platform) {
    case GlPlatform::Auto: return "auto";
    case GlPlatform::Osmesa: return "osmesa";
    case GlPlatform::Egl: return "egl";
  }
  return "?";
}

std::optional<GlPlatform> parse_gl_platform(std::string_view name) {
  for (GlPlatform platform : {GlPlatform::Auto, GlPlatform::Osmesa, GlPlatform::Egl})
    if (gl_platform_name(platform) == name) return platform;
  return std::nullopt;
}

GlContext::GlContext() : id_(next_context_id.fetch_add(1)) {}

GlContext::~GlContext() {
  // The route's destructor has released and destroyed its context by now, which may have moved
  // the dispatch whichever context it pointed at.
  forget_current();
}

bool GlContext::make_current() {
  if (current_context == id_) return true;
  if (!bind()) {
    forget_current();  // a failed switch leaves the dispatch unknown
    return false;
  }
  current_context = id_;
  return true;
}

bool GlContext::is_current() const { return current_context == id_; }

void GlContext::forget_current() { current_context = 0; }

void GlContext::disable_shader_cache() { setenv("MESA_SHADER_CACHE_DISABLE", "true", 0); }

Result<std::unique_ptr<GlContext>> create_gl_context(const GlContextOptions& options) {
  switch (options.platform) {
    case GlPlatform::Osmesa: return create_osmesa_context(options.osmesa_library);
    case GlPlatform::Egl: return create_egl_context(options.egl_library);
    case GlPlatform::Auto: break;
  }
  auto osmesa = create_osmesa_context(options.osmesa_library);
  if (osmesa) return osmesa;
  // An OSMesa that is installed but fails is a problem to see, not a reason to change route.
  if (SharedLibrary::open(library_name(options.osmesa_library, "XSHADE_OSMESA_LIBRARY", "libOSMesa.so.8")))
    return osmesa;
  auto egl = create_egl_context(options.egl_library);
  if (egl) return egl;
  return fail(
      ErrorKind::Backend,
      fmt::format("no OpenGL 4.5 core context: tried OSMesa: {}; then tried EGL surfaceless: {}. Install the Debian "
                  "package libosmesa6 (Mesa before 25.1), or libegl1, libegl-mesa0 and libgl1-mesa-dri (any Mesa), "
                  "or choose a route with --gl-platform",
                  osmesa.error().message, egl.error().message));
}

}  // namespace xshade::harness
