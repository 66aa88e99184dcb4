// OpenGL 4.5 core through Mesa's OSMesa (llvmpipe), headless.
#pragma once

#include <memory>
#include <string>

#include "harness/backend.h"

namespace xshade::harness {

struct OsmesaOptions {
  // The library opened at run time; the environment variable XSHADE_OSMESA_LIBRARY overrides it.
  // Opening at run time keeps the Vulkan lane usable on a machine without OSMesa.
  std::string library = "libOSMesa.so.8";
};

// Fails with a message naming the Debian package (libosmesa6) when OSMesa cannot be opened, and
// with the driver's words when no 4.5 core context can be made.
Result<std::unique_ptr<Backend>> create_osmesa_backend(const OsmesaOptions& options = {});

}  // namespace xshade::harness
