// Turning glslang's info log into diagnostics.
#pragma once

#include <string_view>
#include <vector>

#include "base/result.h"

namespace xshade::spirv {

// glslang writes "ERROR: name:12: 'x' : undeclared identifier" (and WARNING:); each such line
// becomes a diagnostic at name:12. Lines without a location keep the whole text as the message.
std::vector<Diagnostic> parse_glslang_log(std::string_view log);

}  // namespace xshade::spirv
