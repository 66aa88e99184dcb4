// What the semantic analysis tests share: source text through the real preprocessor, parser and
// analyze(), and the analyzed tree read back (its diagnostics, its declarations, an expression's
// type and shape).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "hlsl_like/parser.h"
#include "hlsl_like/preprocessor.h"
#include "hlsl_like/sema.h"

namespace xshade::hlsl::sema_test {

using Strings = std::vector<std::string>;

// Source text through the real preprocessor and parser into analyze(). `#pragma vertex NAME`
// and `#pragma fragment NAME` name the entry points, as the compiler driver does.
struct Analyzed {
  SourceManager sources;
  DiagnosticEngine diagnostics{sources};
  std::unique_ptr<Preprocessor> preprocessor;
  std::vector<Token> tokens;
  TranslationUnit unit;
  EntryPoints entry_points;

  // "line:col: severity: message" for every diagnostic, in order.
  Strings messages() const {
    Strings out;
    for (const Diagnostic& d : diagnostics.diagnostics()) {
      std::string text = d.to_string();
      const std::string prefix = "test.hlsl:";
      if (text.rfind(prefix, 0) == 0) text = text.substr(prefix.size());
      out.push_back(text);
    }
    return out;
  }

  const FunctionDecl& function(const std::string& name) const {
    for (const auto& decl : unit.decls) {
      if (decl && decl->kind == DeclKind::Function && decl->name == name &&
          static_cast<const FunctionDecl&>(*decl).body) {
        return static_cast<const FunctionDecl&>(*decl);
      }
    }
    throw std::runtime_error("no function " + name);
  }
  const VarDecl& global(const std::string& name) const {
    for (const auto& decl : unit.decls) {
      if (decl && decl->kind == DeclKind::Var && decl->name == name) return static_cast<const VarDecl&>(*decl);
    }
    throw std::runtime_error("no global " + name);
  }
  // The statement at `index` of the body of `name`.
  const Stmt& statement(const std::string& name, size_t index) const {
    return *function(name).body->statements.at(index);
  }
  const Expr& expression(const std::string& name, size_t index) const {
    const Stmt& stmt = statement(name, index);
    if (stmt.kind == StmtKind::Expr) return *static_cast<const ExprStmt&>(stmt).expr;
    if (stmt.kind == StmtKind::Return) return *static_cast<const ReturnStmt&>(stmt).value;
    if (stmt.kind == StmtKind::Decl) return *static_cast<const DeclStmt&>(stmt).vars.at(0)->initializer;
    throw std::runtime_error("no expression");
  }
  const VarDecl& local(const std::string& name, size_t index) const {
    return *static_cast<const DeclStmt&>(statement(name, index)).vars.at(0);
  }
};

std::unique_ptr<Analyzed> analyze_source(const std::string& text);
Strings messages_of(const std::string& text);

// An expression tree as an S-expression; implicit conversions show as (to TYPE operand).
std::string dump(const Expr* e);

// `expr` as the only statement of a function after `globals`: its type, its tree and the
// diagnostics. Globals are on line 1, the function on line 2: "void t() { " is 11 columns.
struct Probe {
  std::string type;
  std::string tree;
  Strings messages;
};

Probe probe(const std::string& globals, const std::string& expr);
// probe()'s type, expecting no diagnostics.
std::string type_of(const std::string& globals, const std::string& expr);

}  // namespace xshade::hlsl::sema_test
