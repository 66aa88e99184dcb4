// Semantic analysis, private: the Sema class shared by sema*.cpp, and HLSL's conversion rules.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "base/string_index.h"
#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/intrinsics.h"
#include "hlsl_like/sema.h"
#include "hlsl_like/semantics.h"

namespace xshade::hlsl::sema_detail {

// ---------------------------------------------------------------------------------------------
// Conversions (sema_conversions.cpp)

// How good an implicit conversion is, for overload resolution: lower is better. HLSL's order:
// exact, then a change of scalar type (a promotion, half -> float or bool -> int, before any
// other), then a splat, then a truncation; a change of scalar type on top of a splat or a
// truncation ranks just below the same shape change without it.
inline constexpr int kRankExact = 0;
inline constexpr int kRankPromotion = 1;
inline constexpr int kRankTypeChange = 2;
inline constexpr int kRankSplat = 3;
inline constexpr int kRankTruncation = 6;

class TypeFacts;

struct Conversion {
  bool valid = false;
  bool truncation = false;  // implicit: reported as a warning
  int rank = 0;
};

// HLSL's implicit conversion from `from` to `to`. Error types convert to anything silently.
Conversion classify_implicit(const Type& from, const Type& to);

// The cost DXC gives passing an argument of type `from` to a parameter of type `to`, for
// choosing between a user function's overloads: lower is better, and the candidate with the
// lowest sum over its arguments wins (equal lowest sums are ambiguous). `literal` is a literal
// argument (`1`, `1.0`), which DXC types apart: 1.0 fits any float exactly. See
// sema_conversions.cpp for the weights. Nothing when the conversion is not allowed.
std::optional<uint64_t> overload_cost(const Type& from, bool literal, const Type& to);
// An explicit cast `(to)x`; `literal_scalar` allows `(S)0` for structs of numeric fields.
bool explicit_cast_allowed(const Type& from, const Type& to, bool literal_scalar, TypeFacts& facts);
// "implicit truncation of vector type from 'float4' to 'float3'"
std::string truncation_message(const Type& from, const Type& to);

// The shape both operands of a component-wise operation take: a scalar takes the other's shape,
// vectors the shorter length, matrices the smaller dimensions. Empty when they cannot combine
// (a vector with a matrix). The element type of the result is `scalar`.
std::optional<Type> combine_shapes(const Type& a, const Type& b, ScalarType scalar);

// HLSL's order of scalar types: bool < int < uint < half < float.
inline int scalar_rank(ScalarType scalar) { return int(scalar); }
inline ScalarType higher_scalar(ScalarType a, ScalarType b) { return scalar_rank(a) >= scalar_rank(b) ? a : b; }

// A Float literal without the h suffix (possibly negated): it takes a half operand's type, so
// that `h * 0.5` stays half, as DXC's literal types do.
bool is_weak_float_literal(const Expr* expr);
// A numeric literal, possibly negated.
bool is_literal(const Expr* expr);

// Facts about types that walk their structs, memoized per struct: a struct may hold another
// many times over (and that one another), and walking them afresh would take exponential time.
class TypeFacts {
 public:
  // The number of numeric components of a value (numeric types, structs and arrays of them), or
  // nothing for resources, void and errors.
  std::optional<uint64_t> component_count(const Type& type, int depth = 0);
  bool contains_resource(const Type& type, int depth = 0);

 private:
  std::unordered_map<const StructDecl*, std::optional<uint64_t>> counts_;
  std::unordered_map<const StructDecl*, bool> resources_;
};

// ---------------------------------------------------------------------------------------------
// The analyzer

struct BinaryTyping {
  Type operand;  // both operands are converted to this
  Type result;
};

struct Symbol {
  enum class Kind : uint8_t { Variable, Struct, Typedef, Function };
  Kind kind = Kind::Variable;
  const Decl* decl = nullptr;  // a VarDecl or ParamDecl; the struct, typedef or first function
};

// The names in scope. One table serves every scope: each name knows its innermost binding,
// each binding remembers the one it shadows, and leaving a scope unwinds the bindings it made.
// A lookup is one hash probe however deeply scopes nest, and once the arrays have grown,
// declaring allocates nothing (a map per scope allocated a node per declaration). The names are
// views of the tree's declarations, which outlive the analysis.
class SymbolTable {
 public:
  void push_scope() { scope_starts_.push_back(uint32_t(bindings_.size())); }
  void pop_scope();
  bool empty() const { return scope_starts_.empty(); }
  size_t depth() const { return scope_starts_.size(); }
  // The innermost binding of `name`, or null.
  const Symbol* lookup(std::string_view name) const;
  // Binds `name` in the innermost scope; when that scope binds it already, returns that
  // binding instead (and binds nothing), unless a variable hides a type there.
  const Symbol* add(std::string_view name, Symbol symbol);
  // Calls visit(name, symbol) for each binding of scope `depth` (0 the outermost), in the order
  // they were declared.
  template <class Visit>
  void for_each_in_scope(size_t depth, Visit&& visit) const {
    const size_t end = depth + 1 < scope_starts_.size() ? scope_starts_[depth + 1] : bindings_.size();
    for (size_t i = scope_starts_[depth]; i < end; ++i) visit(bindings_[i].name, bindings_[i].symbol);
  }

 private:
  struct Binding {
    std::string_view name;
    Symbol symbol;
    uint32_t name_number;  // in names_
    uint32_t shadowed;     // 1 + the index of the binding this one hides, or 0
    uint32_t depth;
  };

  StringIndex names_{256};  // every name bound so far, in any scope (a unit and its includes declare a few hundred)
  std::vector<uint32_t> innermost_;  // per name: 1 + the index of its innermost binding; 0 when out of scope
  std::vector<Binding> bindings_;
  std::vector<uint32_t> scope_starts_;
};

// One function signature: its first declaration stands for all its declarations.
struct FunctionInfo {
  const FunctionDecl* canonical = nullptr;
  const FunctionDecl* definition = nullptr;
  std::vector<Type> param_types;
  struct Call {
    const FunctionDecl* callee;  // canonical
    Loc loc;
  };
  std::vector<Call> calls;
  struct Use {
    std::string what;  // "'ddx'", "'discard'"
    Loc loc;
  };
  std::vector<Use> fragment_only_uses;
  bool called = false;
  Loc first_call;
  // check_recursion's depth-first search: 0 not reached, 1 on the path, 2 done.
  uint8_t recursion_mark = 0;
};

// Nesting deeper than this in expressions, statements or types is reported, not recursed into.
inline constexpr int kMaxNesting = 512;

class Sema {
 public:
  explicit Sema(DiagnosticEngine& diagnostics) : diag_(diagnostics) {}
  EntryPoints run(TranslationUnit& unit, const EntryPointNames& names);

  // --- sema.cpp: declarations, statements, entry points
  void declare_struct(StructDecl& decl);
  void declare_typedef(TypedefDecl& decl);
  void declare_global_var(VarDecl& decl, bool in_cbuffer);
  void declare_cbuffer(CBufferDecl& decl);
  void declare_function(FunctionDecl& decl);
  void analyze_local_var(VarDecl& decl);
  void analyze_var_initializer(VarDecl& decl);
  void analyze_stmt(Stmt* stmt);
  void analyze_block(BlockStmt& block, bool new_scope);
  void analyze_attributes(std::vector<Attribute>& attributes);
  void analyze_condition(ExprPtr& condition);
  // `what` is reported as kind + in_quotes(name) ("variable 'x'"), built only for a diagnostic.
  // `allow_resource_array`: a global, which may be an array of textures, samplers or constant buffers.
  bool check_type_usable(const Type& type, std::string_view kind, std::string_view name, Loc loc, bool allow_resource,
                         bool allow_resource_array = false);
  void check_recursion();
  void fix_up_calls();
  const FunctionDecl* find_entry_point(const std::string& name, Loc pragma_loc, const char* stage);
  void check_entry_point(const FunctionDecl& function, bool vertex);
  void check_fragment_only_reachable(const FunctionDecl& vertex_entry);

  // Scopes
  void push_scope() { scopes_.push_scope(); }
  void pop_scope() { scopes_.pop_scope(); }
  // Adds a name to the innermost scope; reports a redefinition (and returns false) if present.
  bool declare(const std::string& name, Symbol symbol, Loc loc);
  const Symbol* lookup(const std::string& name) const;
  std::string suggestion(const std::string& name, bool functions) const;

  // --- sema_expressions.cpp
  // Analyzes `expr` (may be null) and sets its type; returns it.
  Type analyze(Expr* expr);
  // Converts `slot` implicitly to `to`, wrapping it in a ConversionExpr when the type changes.
  // Reports truncation warnings and conversion errors; returns false on an error.
  bool coerce(ExprPtr& slot, const Type& to);
  // Wraps without checks (the caller has checked); nothing when the type is already `to`.
  void wrap_conversion(ExprPtr& slot, const Type& to);
  // The reason `expr` cannot be assigned to, or nothing (also for expressions that already failed).
  std::optional<std::pair<Loc, std::string>> not_assignable(const Expr* expr) const;
  void require_assignable(const Expr* expr);
  bool facts_contain_resource(const Type& type) const;
  // A local variable or one of its fields (not an index): where a resource may be assigned.
  bool rooted_in_local(const Expr* expr) const;
  void analyze_initializer(ExprPtr& init, Type& declared_type, const std::string& var_name);
  std::optional<int64_t> fold_int(const Expr* expr, int depth = 0) const;
  ScalarType common_scalar(std::span<const Expr* const> operands) const;

  Type analyze_unary(UnaryExpr& expr);
  Type analyze_binary(BinaryExpr& expr);
  // The operand type both sides convert to and the result type of `lhs op rhs` (analyzed);
  // reports and returns nothing when the operator does not apply.
  std::optional<BinaryTyping> binary_typing(BinaryOp op, Loc loc, const Expr* lhs, const Expr* rhs);
  Type analyze_assign(AssignExpr& expr);
  Type analyze_conditional(ConditionalExpr& expr);
  Type analyze_member(MemberExpr& expr);
  Type analyze_index(IndexExpr& expr);
  Type analyze_cast(CastExpr& expr);
  Type analyze_name(NameExpr& expr);

  // --- sema_calls.cpp
  Type analyze_call(CallExpr& expr);
  Type analyze_constructor(CallExpr& expr);
  Type analyze_function_call(CallExpr& expr, const std::vector<const FunctionDecl*>& overloads);
  Type analyze_intrinsic_call(CallExpr& expr, IntrinsicId id);

  // --- sema_methods.cpp: texture and buffer methods, and indexing a texture or buffer
  // `expr.object` and the arguments are analyzed (and not in error).
  Type analyze_method_call(CallExpr& expr, const Type& object);
  Type analyze_resource_index(IndexExpr& expr, const Type& object);
  void note_fragment_only(std::string what, Loc loc);

  DiagnosticEngine& diag_;
  mutable TypeFacts facts_;  // memoizes; queried from const members too
  mutable std::unordered_map<const VarDecl*, std::optional<int64_t>> folded_;  // fold_int of constants
  SymbolTable scopes_;
  // Overload sets by name: canonical declarations, in order of declaration. Keyed by views of
  // the declarations' names (the tree outlives the analysis); the hash is std::string's, so the
  // order suggestions search the names in is that of a map keyed by strings.
  std::unordered_map<std::string_view, std::vector<const FunctionDecl*>> functions_;
  std::unordered_map<const FunctionDecl*, FunctionInfo> function_info_;  // by canonical
  std::unordered_map<const FunctionDecl*, const FunctionDecl*> canonical_of_;
  std::vector<CallExpr*> user_calls_;
  std::vector<FunctionDecl*> all_functions_;                 // every function declaration, in order
  std::unordered_set<std::string_view> all_function_names_;  // declared anywhere in the unit (the tree's names)
  FunctionInfo* current_info_ = nullptr;
  const FunctionDecl* current_function_ = nullptr;
  int loop_depth_ = 0;
  int switch_depth_ = 0;  // a `break` leaves a switch too
  int depth_ = 0;
  bool reported_depth_ = false;
  // Entry point diagnostics already given (a struct shared by two stages is checked twice).
  std::unordered_set<std::string> reported_;

  struct DepthGuard {
    Sema& sema;
    explicit DepthGuard(Sema& s) : sema(s) { ++sema.depth_; }
    ~DepthGuard() { --sema.depth_; }
    DepthGuard(const DepthGuard&) = delete;
    DepthGuard& operator=(const DepthGuard&) = delete;
  };
  // True (and reported once) when the current nesting is deeper than kMaxNesting. Inline: every
  // expression and statement asks.
  bool nesting_exceeded(Loc loc) { return depth_ > kMaxNesting && report_nesting(loc); }
  bool report_nesting(Loc loc);
};

std::string join_types(const AstVector<ExprPtr>& args);
// RWTexture2D, RWBuffer, RWStructuredBuffer...: their elements can be assigned (sema_methods.cpp).
bool is_writable_resource(const Type& type);
// "1 argument", "2 or 3 arguments": what a call with one of these arities takes.
std::string arity_list(std::vector<size_t> arities);
// Room for the parameters of any signature of an intrinsic or a resource method (SampleGrad with
// an offset and a clamp has 6) and for the signatures of any intrinsic (mul has 9): candidates
// are ranked in fixed arrays, since every call of a shader resolves its overloads.
inline constexpr size_t kMaxSignatureParams = 8;
inline constexpr size_t kMaxIntrinsicSignatures = 16;
// A candidate signature's conversion rank for each argument.
struct Ranks {
  int values[kMaxSignatureParams] = {};  // the first `count` are meaningful
  size_t count = 0;
  void push_back(int rank) { values[count++] = rank; }
};
// a dominates b: no argument converts worse (a higher rank), and one converts better.
bool dominates(const Ranks& a, const Ranks& b);
// The candidate that dominates every other one, or -1 (ambiguous).
int unique_best(std::span<const Ranks> ranks);
// Passes argument `index` to a parameter of type `type`: in parameters convert, out and inout
// parameters need an assignable argument; a ConversionExpr around an out argument means the
// value is converted back to the argument's type after the call.
void pass_argument(Sema& sema, ExprPtr& arg, const Type& type, ParamDirection direction, size_t index,
                   std::string_view callee);
std::string function_signature(const FunctionDecl& function);

}  // namespace xshade::hlsl::sema_detail
