// Visiting every expression of a statement tree, and the functions an entry point reaches.
#pragma once

#include <functional>
#include <vector>

#include "hlsl_like/ast.h"
#include "hlsl_like/sema.h"

namespace xshade::hlsl {

// Calls `visit` on every expression in `stmt` (or `expr`), parents before children. Null
// children, which a tree with parse errors may have, are skipped.
void walk_expressions(const Stmt* stmt, const std::function<void(const Expr&)>& visit);
void walk_expressions(const Expr* expr, const std::function<void(const Expr&)>& visit);

// The user functions `entry` calls, directly or not, callees before callers, `entry` last: the
// order a GLSL file must define them in.
std::vector<const FunctionDecl*> reachable_functions(const FunctionDecl* entry);

}  // namespace xshade::hlsl
