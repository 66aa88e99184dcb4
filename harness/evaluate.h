// Running one fragment shader as a full-screen pass on a lane: what `xshade eval` and the
// semantics conformance tests do.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "harness/backend.h"
#include "harness/lanes.h"
#include "harness/shader_program.h"
#include "hlsl_like/compiler.h"

namespace xshade::harness {

// The bytes of a constant buffer with every member at its property's default value (zero when
// it has none), laid out at the HLSL offsets reflection gives.
std::vector<std::byte> default_constant_buffer(const hlsl::ConstantBuffer& buffer,
                                               const std::vector<hlsl::Property>& properties);

// Renders the module's fragment entry over a width x height RGBA32F target on `backend`, which
// must run `lane`. The shader reads uv (TEXCOORD0, (0,0) at the top-left) and the pixel position
// (SV_Position); constant buffers hold their defaults and every texture is one white texel.
// `constant_buffers` replaces the defaults of the buffers it names (by their HLSL name).
Result<FloatImage> evaluate(const hlsl::Module& module, Lane lane, Backend& backend, uint32_t width,
                            uint32_t height,
                            const std::map<std::string, std::vector<std::byte>>& constant_buffers = {},
                            const ProgramOptions& options = {});

}  // namespace xshade::harness
