// Which textures OpenGL declares as shadow samplers (compared_textures.h).
#include "glsl/lower/compared_textures.h"

#include "hlsl_like/ast_walk.h"

namespace xshade::glsl::lower {

using namespace hlsl;

bool is_comparison_method(IntrinsicId id) {
  using I = IntrinsicId;
  return id == I::SampleCmp || id == I::SampleCmpLevelZero || (id >= I::GatherCmp && id <= I::GatherCmpAlpha);
}

const Decl* named_decl(const Expr* e) {
  while (e && e->kind == ExprKind::Conversion) e = static_cast<const ConversionExpr*>(e)->operand.get();
  return e && e->kind == ExprKind::Name ? static_cast<const NameExpr*>(e)->decl : nullptr;
}

std::unordered_set<const Decl*> compared_textures(const Module& module) {
  std::unordered_set<const Decl*> compared;
  // The objects of comparison methods, then, back through the calls, what is passed for a
  // compared parameter, until nothing changes (a call chain passes the texture down). Over both
  // stages' functions: a texture is one uniform of one type in the linked program, so one the
  // fragment stage compares is a shadow sampler in the vertex stage too.
  std::vector<const FunctionDecl*> program_functions;
  for (const FunctionDecl* entry : {module.entry_points.vertex, module.entry_points.fragment})
    if (entry)
      for (const FunctionDecl* function : hlsl::reachable_functions(entry)) program_functions.push_back(function);
  for (bool changed = true; changed;) {
    changed = false;
    for (const FunctionDecl* function : program_functions) {
      hlsl::walk_expressions(function->body.get(), [&](const Expr& e) {
        if (e.kind != ExprKind::Call) return;
        const auto& call = static_cast<const CallExpr&>(e);
        if (call.call_kind == CallKind::Method && is_comparison_method(IntrinsicId(call.intrinsic))) {
          if (const Decl* decl = named_decl(call.object.get())) changed |= compared.insert(decl).second;
        } else if (call.call_kind == CallKind::Function && call.function) {
          for (size_t i = 0; i < call.args.size() && i < call.function->params.size(); ++i)
            if (compared.count(call.function->params[i].get()))
              if (const Decl* decl = named_decl(call.args[i].get())) changed |= compared.insert(decl).second;
        }
      });
    }
  }
  return compared;
}

}  // namespace xshade::glsl::lower
