// For the emitter's tests: the GLSL of one source's fragment stage.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/compiler.h"

namespace xshade::glsl {

// The fragment stage of `source` in `flavour`; a front-end or emitter error fails the test.
inline std::string emitted_fragment(const std::string& source, Flavour flavour) {
  auto module = hlsl::compile_text("test.hlsl", source, {});
  if (!module->ok()) {
    ADD_FAILURE() << module->diagnostics.render_all();
    return "";
  }
  auto program = emit(*module, {flavour});
  if (!program || !program->fragment) {
    ADD_FAILURE() << (program ? "no fragment stage" : program.error().to_string());
    return "";
  }
  return program->fragment->text;
}

}  // namespace xshade::glsl
