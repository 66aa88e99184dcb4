// The GLSL emitter's inside: one StageEmitter writes one stage of one module, after the lowering
// passes (lower/) have decided what it is to write. Its parts live in glsl_emitter.cpp
// (declarations, stage interface, main), emit_statements.cpp (functions and statements),
// emit_expressions.cpp (expressions and conversions), emit_textures.cpp and emit_buffers.cpp
// (resources), emit_trace.cpp (the tracing variant) and intrinsic_mapping.cpp (the HLSL intrinsic
// -> GLSL table and the xs_* helper functions).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "base/result.h"
#include "base/string_index.h"
#include "glsl/flavour.h"
#include "glsl/glsl_emitter.h"
#include "glsl/lower/compared_textures.h"
#include "glsl/lower/flatten_resources.h"
#include "glsl/lower/half_emulation.h"
#include "glsl/lower/rename.h"
#include "glsl/lower/split_constant_buffers.h"
#include "glsl/lower/trace_sites.h"
#include "glsl/lower/unroll_offset_loops.h"
#include "glsl/lower/used_declarations.h"
#include "hlsl_like/compiler.h"
#include "hlsl_like/intrinsics.h"

namespace xshade::glsl::detail {

using lower::Names;
using lower::type_key;

using hlsl::Expr;
using hlsl::FunctionDecl;
using hlsl::Loc;
using hlsl::Stmt;
using hlsl::Type;

// A vector's components in order, for swizzles.
inline constexpr const char* kComponents = "xyzw";

// C's (and GLSL's) operator precedence, lowest first: an operand is parenthesized when its
// precedence is too low for the place it goes.
enum Prec : int {
  kComma = 1,
  kAssign,
  kConditional,
  kLogicalOr,
  kLogicalXor,
  kLogicalAnd,
  kBitOr,
  kBitXor,
  kBitAnd,
  kEquality,
  kRelational,
  kShift,
  kAdditive,
  kMultiplicative,
  kUnary,
  kPostfix,
  kPrimary,
};

// A piece of GLSL expression text and the precedence of its outermost operator.
struct Code {
  std::string text;
  int prec = kPrimary;
};

// `code` as an operand that needs at least precedence `prec`.
std::string operand(const Code& code, int prec);
// The same, taking the text over instead of copying it: expressions are built bottom-up, and
// most operands are used once, by the expression around them.
std::string operand(Code&& code, int prec);
// Appends `code` as an operand to `out`, without a text of its own in between.
void append_operand(std::string& out, const Code& code, int prec);

std::string replace_all(std::string text, std::string_view from, const std::string& to);

// Text with its line count, and `#line` directives that map the lines that follow back to the
// author's source.
class Writer {
 public:
  void line(const std::string& text);  // one indented line
  // One indented line of these parts, so that a line is not put together in a string first.
  void line(std::initializer_list<std::string_view> parts);
  // Before a construct at `loc`: a `#line` directive unless the next line already maps there.
  void mark(Loc loc);
  const std::string& text() const { return text_; }
  int indent = 0;

 private:
  std::string text_;
  bool mapped_ = false;
  uint32_t file_ = 0;
  uint32_t next_line_ = 0;
};

// The xs_* helper functions a stage uses, each defined once, in the order of first use.
class Helpers {
 public:
  // Adds `definition` unless one with the same `signature` is there.
  void add(const std::string& signature, const std::string& definition);
  std::string text() const;
  bool empty() const { return order_.empty(); }

 private:
  std::vector<std::string> order_;
  std::unordered_map<std::string, std::string> definitions_;
};

class StageEmitter {
 public:
  StageEmitter(const hlsl::Module& module, const EmitOptions& options, const Names& names, bool vertex);
  // The stage's complete GLSL text; check error() afterwards.
  std::string run();
  const std::optional<Error>& error() const { return error_; }
  // The tracing variant's sites and calls, after run().
  NonfiniteTrace take_trace() { return std::move(trace_table_); }

  // --- diagnostics: the first error wins; emission goes on so that it ends cleanly.
  void fail(Loc loc, const std::string& message);
  // A tree the front end should not have let through: xshade's fault (ErrorKind::Internal).
  void fail_internal(Loc loc, const std::string& what);

  // --- types (emit_expressions.cpp)
  // GLSL's name for `type`; reports what GLSL cannot hold. Resources: the flavour's opaque types.
  std::string type_name(const Type& type, Loc loc);
  // `vec2 name[4]`.
  std::string declarator(const Type& type, const std::string& name, Loc loc);
  // Both types are the same GLSL type (half is float, float1 is float).
  bool same_glsl(const Type& a, const Type& b);
  // The GLSL type of a vector of `count` booleans (`bool` for 1).
  static std::string bool_type(uint32_t count);

  // --- expressions (emit_expressions.cpp; expr() itself in emit_trace.cpp)
  // An expression; in the tracing variant a site's value is tested on its way.
  Code expr(const Expr* e);
  Code expr_untraced(const Expr* e);
  // The same before rounding: what expr_untraced rounds when half_ says `e` makes a half value.
  Code expr_unrounded(const Expr* e);
  // `value` of type `from` as type `to`, GLSL converting explicitly.
  Code convert(Code value, const Type& from, const Type& to, Loc loc);
  Code convert_components(Code value, const Type& from, const Type& to, Loc loc);
  // An expression converted to `to`; literals are folded (`1` as a float is `1.0`).
  Code convert_expr(const Expr* e, const Type& to);
  // `value` of `type` rounded to fp16 when half_ says a value of that type is (xs_half, or a
  // literal rounded here); expr_untraced rounds each result half_ says is made there.
  Code half_value(Code value, const Type& type);
  // ++ or -- on `target` (e's operand, printed): GLSL's own, or with half emulation the rounded
  // new value written back (lower::HalfEmulation::rounds_increment).
  Code increment(const hlsl::UnaryExpr& e, const Code& target);
  // The expression whose value a statement discards (an expression statement, a for loop's step):
  // its h++ is written as ++h would be, without a helper to keep the old value.
  const Expr* value_discarded_ = nullptr;
  // The value of a static const or other constant initializer could be a GLSL constant expression.
  bool is_constant(const Expr* e);
  // A name, literal, field, swizzle or constant index of those: cheap and free of side effects,
  // so that it may be written twice.
  static bool is_simple(const Expr* e);
  // Assignments, increments and calls (other than constructors) inside `e`.
  static bool has_side_effects(const Expr* e);
  // A ?: with a scalar condition, && or || inside `e`: what glslang compiles to branches.
  static bool branches(const Expr* e);
  // An argument passed to an out or inout parameter: the assignable expression itself.
  Code out_argument(const Expr* arg);
  // A struct or array with every component set from the scalar literal `scalar` (`(S)0`).
  Code splat_aggregate(const Expr* scalar, const Type& to, Loc loc);

  // --- intrinsics (intrinsic_mapping.cpp)
  Code intrinsic_call(const hlsl::CallExpr& call);
  // A template of intrinsic_mapping.cpp's kind ($0.., $R, $B0, xs_ helpers) over `operands`;
  // `out` marks the operands passed to out parameters. An operand used twice that is not a
  // simple expression makes the template a helper function, so that it is evaluated once;
  // `always_helper` makes it one whatever its operands.
  Code expand_template(std::string_view text, const hlsl::CallExpr& call, const std::vector<const Expr*>& operands,
                       const std::vector<bool>& out, bool always_helper = false);
  // A component-wise intrinsic with matrix operands, which GLSL's built-ins do not take: a helper
  // that applies the vector form to each column (all/any and clip combine the columns' results).
  Code matrix_intrinsic_call(const hlsl::CallExpr& call, const std::vector<const Expr*>& operands);
  // `clip(x);` as a statement: `if (x < 0.0) discard;`. False if `expr` is not a clip call.
  bool clip_statement(const Expr* expr);
  // A helper from the library (xs_fmod, xs_idiv, ...) for these operand types; returns its name.
  std::string require_helper(const std::string& name, const std::vector<Type>& operands, Loc loc);

  // --- textures (emit_textures.cpp)
  // A texture method (Sample, Load, Gather, GetDimensions, ...) or a DX9 tex* function.
  Code texture_call(const hlsl::CallExpr& call);
  // t[p] on a texture: a texel of mip 0.
  Code texture_index(const hlsl::IndexExpr& index);
  // --- read-only buffers (emit_buffers.cpp)
  // buf[i], buf.Load(i), a ByteAddressBuffer's Load2..4, GetDimensions.
  Code buffer_index(const hlsl::IndexExpr& index);
  Code buffer_call(const hlsl::CallExpr& call);
  std::string buffer_declaration(const hlsl::StorageBufferResource& buffer) const;
  // The buffer a global names; null (with an error) for anything else.
  const hlsl::StorageBufferResource* buffer_of(const Expr* object, Loc loc);
  // The helper that assembles an element (or `words` words of a ByteAddressBuffer); its name.
  std::string buffer_element_helper(const hlsl::StorageBufferResource& buffer, uint32_t words, Loc loc);

  // The GLSL type of a texture, sampler or other resource; `decl` is the variable or parameter
  // declared with it (a texture compared on OpenGL is a shadow sampler), or null.
  std::string resource_type(const Type& type, const hlsl::Decl* decl, Loc loc);

  // --- resources held in locals and struct fields (emit_textures.cpp)
  // The GLSL text of the resource `leaf` (a field path) of the value `e` (lower::resource_name).
  Code resource_text(const Expr* e, const std::vector<uint32_t>& leaf);
  // Fails at `loc` when `type` is a struct of resources that holds a value too
  // (lower::mixed_struct_message).
  void check_struct_of_resources(const Type& type, Loc loc);

  // --- functions and statements (emit_statements.cpp)
  void function(const FunctionDecl& function);
  // What one HLSL parameter declares in GLSL: itself, or one parameter per resource it holds.
  std::vector<std::string> parameter_declarations(const hlsl::ParamDecl& param);
  void statement(const Stmt* stmt);
  void body(const Stmt* stmt);  // the statements of a braced body
  void local_variable(const hlsl::VarDecl& var);
  std::string initializer(const hlsl::VarDecl& var);

  // --- the tracing variant (emit_trace.cpp)
  // `value` (of `type`) tested as the site `kind` at `loc`, when tracing and the type is float.
  Code traced(Code value, const Type& type, TraceSite::Kind kind, Loc loc, std::string what);
  // The value of the call path a call of the author's function at `loc` passes on: the caller's
  // path with this call's number in its low bits.
  std::string trace_call_path(const std::string& callee, Loc loc);
  // main(): the fragment inputs tested as they arrive, the colour outputs tested as they leave,
  // and the record written to location 1.
  void trace_input(Writer& main, const std::string& path, const Type& type, const std::string& semantic, Loc loc);
  void trace_output(Writer& main, const std::string& path, const Type& type, const std::string& semantic, Loc loc);
  void trace_record(Writer& main, Writer& interface);
  // The traced copy's functions, after the plain ones.
  void traced_functions();
  // The GLSL name of the author's function in the copy being emitted.
  std::string function_name(const FunctionDecl* function) const;
  // A uniform read in the traced copy, through xs_opaque (emit_trace.cpp says why); other code as it is.
  Code opaque_if_uniform(const Expr* e, Code code);
  // main()'s traced part: the entry point's traced copy on the same inputs, made opaque, with
  // the inputs and outputs tested and the record written.
  struct TracedItem {
    std::string path;  // in the plain copy: xs_arg0.uv, xs_result
    Type type;
    std::string semantic;
    Loc loc;
  };
  void traced_main(Writer& main, Writer& interface, const std::vector<TracedItem>& inputs,
                   const std::vector<TracedItem>& outputs);
  TraceSite site_at(TraceSite::Kind kind, Loc loc, std::string what) const;
  // Adds `site` to the table; its number as the record holds it.
  uint32_t add_site(TraceSite site, Loc loc);

  // --- the stage (glsl_emitter.cpp)
  std::string declarations();
  // main(); the stage's in and out variables go to interface_text_.
  std::string interface_and_main();

  const hlsl::Module& module_;
  const hlsl::Reflection& reflection_;
  const Flavour flavour_;
  const lower::HalfEmulation half_;  // which half values are rounded to fp16
  const bool filter_comparisons_;
  const std::map<uint32_t, double> specialization_;
  const Names& names_;
  const bool vertex_;
  const FunctionDecl* entry_ = nullptr;

  Writer out_;  // functions
  Helpers helpers_;
  // The helper function expand_template made of each distinct template body, by its definition
  // without a name, and how many each intrinsic's name has: xs_Sample, xs_Sample_2, ...
  std::unordered_map<std::string, std::string> template_helpers_;
  std::unordered_map<std::string, int> template_helper_count_;
  std::optional<Error> error_;
  // The #extension lines the stage needs (vk: GL_EXT_samplerless_texture_functions for
  // texelFetch/textureSize on a texture2D, ...), written after #version in name order.
  std::set<std::string> extensions_;
  void require_extension(const std::string& name) { extensions_.insert(name); }
  // What the lowering passes (lower/) decided, which the rest prints.
  std::unordered_set<const hlsl::Decl*> compared_;  // lower::compared_textures (OpenGL only)
  std::vector<const FunctionDecl*> functions_;      // lower::used_declarations
  std::vector<const hlsl::VarDecl*> statics_;
  std::unordered_set<const hlsl::StructDecl*> used_structs_;
  lower::ConstantBufferMembers constant_buffer_members_;  // lower::split_constant_buffers
  lower::UnrolledLoops unrolled_loops_;                   // lower::unroll_offset_loops
  std::vector<std::string> main_prologue_;                // statements that initialize statics in main()
  std::string interface_text_;
  std::unordered_set<const hlsl::Decl*> const_decls_;  // emitted as GLSL `const`

  const bool trace_;             // the tracing variant: every function twice, the second copy traced
  bool in_traced_copy_ = false;  // emitting the traced copy (emit_trace.cpp)
  const uint32_t trace_program_;
  std::string current_function_ = "main";
  NonfiniteTrace trace_table_;
};

}  // namespace xshade::glsl::detail
