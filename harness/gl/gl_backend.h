// OpenGL 4.5 core on Mesa's llvmpipe, headless: the gl lane's backend, on a context made by
// either route of gl_context.h (OSMesa or EGL surfaceless). DriverInfo::api names the route.
#pragma once

#include <memory>

#include "harness/backend/backend.h"
#include "harness/gl/gl_context.h"

namespace xshade::harness {

// Makes a context by the options' route, then the backend on it. Fails with a message naming
// the Debian package to install when a driver is missing, and with the driver's words when no
// 4.5 core context can be made.
Result<std::unique_ptr<Backend>> create_gl_backend(const GlContextOptions& options = {});

// The backend on a context made elsewhere; it owns the context from now on. `compile_messages`
// as in GlContextOptions.
Result<std::unique_ptr<Backend>> create_gl_backend(std::unique_ptr<GlContext> context,
                                                   const std::filesystem::path& compile_messages = {});

}  // namespace xshade::harness
