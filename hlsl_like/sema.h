// Semantic analysis: names, types, overloads, conversions, l-values and entry points.
#pragma once

#include <string>

#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"

namespace xshade::hlsl {

struct EntryPointNames {
  std::string vertex;  // from #pragma vertex; empty when the source has no vertex stage
  Loc vertex_loc;
  std::string fragment;  // from #pragma fragment
  Loc fragment_loc;
};

struct EntryPoints {
  const FunctionDecl* vertex = nullptr;
  const FunctionDecl* fragment = nullptr;
};

// Checks `unit` and annotates it in place (see the "sema" fields of ast.h): every expression gets
// its type, names their declarations, calls their function, intrinsic or constructor, and every
// implicit HLSL conversion becomes an explicit ConversionExpr. Errors and warnings go to
// `diagnostics`; analysis goes on after an error, giving failed expressions the Error type.
EntryPoints analyze(TranslationUnit& unit, const EntryPointNames& entry_points, DiagnosticEngine& diagnostics);

}  // namespace xshade::hlsl
