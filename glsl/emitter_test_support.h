// What the GLSL emitter's tests share: HLSL source through the real front end into emit(), and
// the emitted text read back.
#pragma once

#include <string>
#include <vector>

#include "glsl/glsl_emitter.h"

namespace xshade::glsl::emitter_test {

// The module's diagnostics, one a line.
std::string diagnostics_of(const hlsl::Module& module);
// `source` (test.hlsl) through the front end and emit(); a test failure if the front end refuses it.
Result<EmittedProgram> try_emit(const std::string& source, Flavour flavour = Flavour::Gl);
// The same, a test failure (and an empty program) if emit() fails.
EmittedProgram emit_ok(const std::string& source, Flavour flavour = Flavour::Gl);
// A fragment-only shader: `globals`, then frag() with `body` as its statements.
std::string fragment_source(const std::string& globals, const std::string& body);
// That shader's emitted fragment stage.
std::string fragment(const std::string& globals, const std::string& body, Flavour flavour = Flavour::Gl);
// The error emit() gives for `source`; a test failure if it gives none.
std::string emit_error(const std::string& source, Flavour flavour = Flavour::Gl);
std::string without_line_directives(const std::string& text);
std::vector<std::string> lines_of(const std::string& text);

// A vertex and fragment shader with interpolation qualifiers and a system value.
extern const char* const kVertexAndFragment;

}  // namespace xshade::glsl::emitter_test
