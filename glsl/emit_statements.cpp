// Functions and statements. Every branch and loop body is braced; `#line` directives keep the
// driver's messages on the author's lines.
#include "glsl/stage_emitter.h"
#include "hlsl_like/ast_walk.h"

#include <cstdlib>

namespace xshade::glsl::detail {

using namespace hlsl;

namespace {

// [unroll], [loop(4)]: GLSL has no attributes; kept as a comment.
std::string attributes_comment(StageEmitter& emitter, const std::vector<Attribute>& attributes) {
  std::string text;
  for (const Attribute& attribute : attributes) {
    text += "/* [" + attribute.name;
    if (!attribute.args.empty()) {
      text += "(";
      for (size_t i = 0; i < attribute.args.size(); ++i)
        text += (i ? ", " : "") + emitter.expr(attribute.args[i].get()).text;
      text += ")";
    }
    text += "] */ ";
  }
  return text;
}

}  // namespace

void StageEmitter::function(const FunctionDecl& f) {
  out_.mark(f.loc);
  if (!resource_paths(f.return_type).empty())
    fail(f.loc, "function " + in_quotes(f.name) + " cannot return " + in_quotes(f.return_type.name()) +
                    ", which holds resources; pass them as parameters");
  current_function_ = f.name;
  std::string signature = type_name(f.return_type, f.loc) + " " + function_name(&f) + "(";
  bool first = true;
  for (const auto& param : f.params) {
    if (!param) continue;
    for (const std::string& declaration : parameter_declarations(*param)) {
      if (!first) signature += ", ";
      first = false;
      signature += declaration;
    }
  }
  if (in_traced_copy_) signature += first ? "uint xs_path" : ", uint xs_path";  // emit_trace.cpp
  out_.line(signature + ") {");
  body(f.body.get());
  out_.line("}");
  current_function_ = "main";
}

std::vector<std::string> StageEmitter::parameter_declarations(const ParamDecl& param) {
  const std::vector<std::vector<uint32_t>> paths = resource_paths(param.type);
  if (paths.empty()) {
    const char* direction = param.direction == ParamDirection::Out     ? "out "
                            : param.direction == ParamDirection::InOut ? "inout "
                                                                       : "";
    std::vector<std::string> declaration(1, direction);
    declaration[0] += declarator(param.type, names_.variable(&param), param.loc);
    return declaration;
  }
  if (param.type.kind() == TypeKind::Struct) check_struct_of_resources(param.type, param.loc);
  // A resource, or a struct of resources: one GLSL parameter per resource (none for a
  // SamplerState on gl, whose state belongs to the texture unit).
  std::vector<std::string> out;
  for (const lower::FlattenedParameter& flat : lower::flattened_parameters(param, names_, flavour_))
    out.push_back(resource_type(*flat.type, &param, param.loc) + " " + flat.name);
  return out;
}

void StageEmitter::body(const Stmt* stmt) {
  ++out_.indent;
  if (stmt && stmt->kind == StmtKind::Block) {
    for (const StmtPtr& child : static_cast<const BlockStmt*>(stmt)->statements) statement(child.get());
  } else {
    statement(stmt);
  }
  --out_.indent;
}

std::string StageEmitter::initializer(const VarDecl& var) { return operand(expr(var.initializer.get()), kAssign); }

namespace {

// `[const] T name[N] = init`, without the semicolon.
std::string variable_text(StageEmitter& emitter, const VarDecl& var, const Names& names) {
  std::string text;
  std::string init;
  if (var.initializer) {
    init = emitter.initializer(var);
    // GLSL's const needs a constant expression; HLSL's only forbids writes.
    if (var.is_const && emitter.is_constant(var.initializer.get())) {
      emitter.const_decls_.insert(&var);
      text = "const ";
    }
  }
  if (!init.empty() && text.empty() && !lower::is_tested(var.initializer.get()))
    init =
        emitter.traced({std::move(init), kAssign}, var.type, TraceSite::Kind::Initialization, var.loc, var.name).text;
  text += emitter.declarator(var.type, names.variable(&var), var.loc);
  if (!init.empty()) {
    text += " = ";
    text += init;
  }
  return text;
}

}  // namespace

void StageEmitter::local_variable(const VarDecl& var) {
  // A local resource (or struct of them) is another name for a global or a parameter, which
  // every read of it prints instead (resource_origins.h): GLSL has no opaque locals.
  if (!resource_paths(var.type).empty()) {
    if (var.type.kind() == TypeKind::Struct) check_struct_of_resources(var.type, var.loc);
    return;
  }
  if (var.storage == StorageClass::GroupShared) {
    fail(var.loc, "groupshared variables are not supported on this target");
    return;
  }
  if (var.storage == StorageClass::Static && !var.is_const) {
    fail(var.loc, "static local variable " + in_quotes(var.name) +
                      " keeps its value between calls, which this target does not support; declare it at global scope");
    return;
  }
  out_.mark(var.loc);
  out_.line({variable_text(*this, var, names_), ";"});
}

void StageEmitter::statement(const Stmt* stmt) {
  if (!stmt) return;
  const std::string prefix = attributes_comment(*this, stmt->attributes);
  switch (stmt->kind) {
    case StmtKind::Block: {
      out_.mark(stmt->loc);
      out_.line(prefix + "{");
      body(stmt);
      out_.line("}");
      break;
    }
    case StmtKind::Expr: {
      const Expr* e = static_cast<const ExprStmt*>(stmt)->expr.get();
      if (!e) break;
      // Giving a local its resource happens when compiling (resource_origins.h).
      if (e->kind == ExprKind::Assign && !resource_paths(static_cast<const AssignExpr*>(e)->target->type).empty())
        break;
      out_.mark(stmt->loc);
      if (clip_statement(e)) break;
      if (flavour_ == Flavour::Gl && e->kind == ExprKind::Call &&
          static_cast<const CallExpr*>(e)->call_kind == CallKind::Printf) {
        out_.line({prefix, "// printf: OpenGL has no debug printf"});
        break;
      }
      value_discarded_ = e;
      out_.line({prefix, expr(e).text, ";"});
      value_discarded_ = nullptr;
      break;
    }
    case StmtKind::Decl:
      for (const auto& var : static_cast<const DeclStmt*>(stmt)->vars)
        if (var) local_variable(*var);
      break;
    case StmtKind::If: {
      const auto* branch = static_cast<const IfStmt*>(stmt);
      out_.mark(stmt->loc);
      out_.line({prefix, "if (", expr(branch->condition.get()).text, ") {"});
      body(branch->then_branch.get());
      const Stmt* rest = branch->else_branch.get();
      while (rest && rest->kind == StmtKind::If && rest->attributes.empty()) {
        const auto* next = static_cast<const IfStmt*>(rest);
        out_.mark(rest->loc);
        out_.line({"} else if (", expr(next->condition.get()).text, ") {"});
        body(next->then_branch.get());
        rest = next->else_branch.get();
      }
      if (rest) {
        out_.line("} else {");
        body(rest);
      }
      out_.line("}");
      break;
    }
    case StmtKind::For: {
      const auto* loop = static_cast<const ForStmt*>(stmt);
      out_.mark(stmt->loc);
      // A loop whose variable is a texel offset is unrolled, as fxc does: GLSL's *Offset
      // functions take constant expressions only, which `const int i = k;` in each copy is.
      if (auto unrolled = unrolled_loops_.find(loop); unrolled != unrolled_loops_.end()) {
        const std::vector<int64_t>* values = &unrolled->second;
        const VarDecl& var = *static_cast<const DeclStmt&>(*loop->init).vars[0];
        const_decls_.insert(&var);
        for (int64_t value : *values) {
          out_.line(prefix + "{  // unrolled: " + names_.variable(&var) + " = " + std::to_string(value));
          ++out_.indent;
          out_.line("const " + type_name(var.type, var.loc) + " " + names_.variable(&var) + " = " +
                    std::to_string(value) + (var.type.scalar_type() == ScalarType::Uint ? "u;" : ";"));
          --out_.indent;
          body(loop->body.get());
          out_.line("}");
        }
        break;
      }
      // `for (int i = 0, j = 0; ...)` needs one GLSL type; anything else moves before the loop,
      // in a block of its own since the variables belong to the loop.
      std::string init;
      bool hoisted = false;
      if (loop->init && loop->init->kind == StmtKind::Decl) {
        const auto& vars = static_cast<const DeclStmt&>(*loop->init).vars;
        bool one_type = !vars.empty();
        for (const auto& var : vars) {
          if (!var || var->type.kind() == TypeKind::Array || !(var->type == vars[0]->type) ||
              var->storage != StorageClass::Default || var->is_const)
            one_type = false;
        }
        if (one_type) {
          for (size_t i = 0; i < vars.size(); ++i) {
            const VarDecl& var = *vars[i];
            if (i == 0)
              init = type_name(var.type, var.loc) + " ";
            else
              init += ", ";
            init += names_.variable(&var);
            if (var.initializer) init += " = " + initializer(var);
          }
        } else {
          hoisted = true;
          out_.line(prefix + "{");
          ++out_.indent;
          statement(loop->init.get());
        }
      } else if (loop->init && loop->init->kind == StmtKind::Expr) {
        if (const Expr* e = static_cast<const ExprStmt&>(*loop->init).expr.get()) init = expr(e).text;
      }
      const std::string condition = loop->condition ? expr(loop->condition.get()).text : "";
      value_discarded_ = loop->step.get();
      const std::string step = loop->step ? expr(loop->step.get()).text : "";
      value_discarded_ = nullptr;
      out_.line((hoisted ? "" : prefix) + "for (" + init + "; " + condition + "; " + step + ") {");
      body(loop->body.get());
      out_.line("}");
      if (hoisted) {
        --out_.indent;
        out_.line("}");
      }
      break;
    }
    case StmtKind::While: {
      const auto* loop = static_cast<const WhileStmt*>(stmt);
      out_.mark(stmt->loc);
      out_.line({prefix, "while (", expr(loop->condition.get()).text, ") {"});
      body(loop->body.get());
      out_.line("}");
      break;
    }
    case StmtKind::DoWhile: {
      const auto* loop = static_cast<const DoWhileStmt*>(stmt);
      out_.mark(stmt->loc);
      out_.line(prefix + "do {");
      body(loop->body.get());
      out_.line("} while (" + expr(loop->condition.get()).text + ");");
      break;
    }
    case StmtKind::Switch: {
      const auto* sw = static_cast<const SwitchStmt*>(stmt);
      out_.mark(stmt->loc);
      out_.line(prefix + "switch (" + expr(sw->condition.get()).text + ") {");
      for (size_t i = 0; i < sw->cases.size(); ++i) {
        const SwitchCase& c = sw->cases[i];
        // Labels take the condition's type: GLSL does not convert them.
        out_.line(c.value ? "case " + convert_expr(c.value.get(), sw->condition->type).text + ":" : "default:");
        ++out_.indent;
        for (const StmtPtr& child : c.statements) statement(child.get());
        // GLSL wants statements after the last label.
        if (i + 1 == sw->cases.size() && c.statements.empty()) out_.line("break;");
        --out_.indent;
      }
      out_.line("}");
      break;
    }
    case StmtKind::Return: {
      const Expr* value = static_cast<const ReturnStmt*>(stmt)->value.get();
      out_.mark(stmt->loc);
      if (value && !lower::is_tested(value))
        out_.line({"return ",
                   traced(expr(value), value->type, TraceSite::Kind::Return, stmt->loc, current_function_).text, ";"});
      else if (value)
        out_.line({"return ", expr(value).text, ";"});
      else
        out_.line("return;");
      break;
    }
    case StmtKind::Break:
      out_.mark(stmt->loc);
      out_.line("break;");
      break;
    case StmtKind::Continue:
      out_.mark(stmt->loc);
      out_.line("continue;");
      break;
    case StmtKind::Discard:
      out_.mark(stmt->loc);
      out_.line("discard;");
      break;
    case StmtKind::Empty: break;
  }
}

}  // namespace xshade::glsl::detail
