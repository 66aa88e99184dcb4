// glslang keeps process-wide tables that must be set up once before any shader is parsed.
#pragma once

namespace xshade::spirv {

void ensure_glslang_initialized();

}  // namespace xshade::spirv
