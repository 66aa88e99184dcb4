// Lowering: the tracing variant's sites (EmitOptions::trace_nonfinite; emit_trace.cpp says how the
// variant works). Which values of the traced copy are tested and as what kind of site, and which
// reads pass through xs_opaque. The printer numbers the sites as it writes them.
#pragma once

#include <optional>
#include <string>

#include "glsl/glsl_emitter.h"
#include "hlsl_like/ast.h"

namespace xshade::glsl::lower {

// Float and half scalars, vectors and matrices: what can hold a NaN or an infinity.
bool traceable(const hlsl::Type& type);

// A site tested where its value is computed, and what the report calls it.
struct ExpressionSite {
  TraceSite::Kind kind;
  std::string what;  // the place assigned (`color.rgb`) or the intrinsic called (`pow`)
};
// `e` as a site of its own: an assignment of float type (Assignment, CompoundAssignment), unless
// it assigns a value tested already (`x = f(y)` fails where f(y) does), or an intrinsic's or
// method's result of float type (Call). The author's functions are tested at their returns,
// where the value is born; their call would name the same value a second time.
std::optional<ExpressionSite> expression_site(const hlsl::Expr* e);

// The value of `e` is tested before it is assigned, initialises a variable or is returned: it is
// a site, or a call of the author's function. Such a value is not tested again.
bool is_tested(const hlsl::Expr* e);

// A uniform the traced copy reads, which passes through xs_opaque: a global that is neither
// static nor groupshared, or an element or member of one.
bool reads_uniform(const hlsl::Expr* e);

// The assigned place as the author wrote it, for the report: `color.rgb`, `weights[...]`.
std::string place_name(const hlsl::Expr* e);

}  // namespace xshade::glsl::lower
