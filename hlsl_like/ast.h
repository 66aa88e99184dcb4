// The syntax tree of hlsl_like. The parser builds it; semantic analysis fills in the fields
// marked "sema" (types, resolved names and calls, implicit conversions); the GLSL emitter and
// reflection read it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hlsl_like/ast_arena.h"
#include "hlsl_like/source_manager.h"
#include "hlsl_like/types.h"

namespace xshade::hlsl {

struct Decl;
struct FunctionDecl;
struct Expr;
struct Stmt;
using ExprPtr = std::unique_ptr<Expr>;
using StmtPtr = std::unique_ptr<Stmt>;

// [unroll], [loop(4)], [branch], [flatten], [numthreads(...)]: kept, not interpreted.
struct Attribute {
  std::string name;
  std::vector<ExprPtr> args;
  Loc loc;
};

// Vulkan's attributes on a declaration, as DXC's SPIR-V back end reads them
// (`[[vk::location(0)]] float2 uv : TEXCOORD0`, `[[vk::binding(1, 0)]] Texture2D t`).
struct VulkanAttributes {
  std::optional<uint32_t> location;     // vk::location(N): a stage input's or output's location
  std::optional<uint32_t> binding;      // vk::binding(N[, set]): a resource's binding
  uint32_t set = 0;                     // its descriptor set
  bool push_constant = false;           // vk::push_constant: a struct variable or ConstantBuffer<S>
  std::optional<uint32_t> constant_id;  // vk::constant_id(N): a specialization constant
  std::string builtin;                  // vk::builtin("PointSize"): an output SPIR-V names itself
  // vk::input_attachment_index(N): a SubpassInput's input attachment of the subpass
  std::optional<uint32_t> input_attachment_index;
  // vk::combinedImageSampler: a texture and a SamplerState at one vk::binding read as one combined
  // image sampler there
  bool combined_image_sampler = false;
  std::optional<uint32_t> offset;  // vk::offset(N): a constant-buffer member's byte offset
  Loc loc;                         // of the first attribute
  bool any() const {
    return location || binding || push_constant || constant_id || !builtin.empty() || input_attachment_index ||
           combined_image_sampler || offset;
  }
};

// ---------------------------------------------------------------------------------------------
// Expressions

enum class ExprKind : uint8_t {
  IntLiteral,
  FloatLiteral,
  BoolLiteral,
  Name,
  Unary,
  Binary,
  Assign,
  Conditional,
  Call,
  Member,
  Index,
  Cast,
  InitList,
  Conversion,
};

struct Expr : AstNodeMemory {
  ExprKind kind;
  Loc loc;
  Type type;  // sema

  explicit Expr(ExprKind k, Loc l) : kind(k), loc(l) {}
  virtual ~Expr() = default;
};

struct IntLiteralExpr : Expr {
  uint64_t value = 0;
  bool is_unsigned = false;  // a u suffix
  IntLiteralExpr(Loc l) : Expr(ExprKind::IntLiteral, l) {}
};

struct FloatLiteralExpr : Expr {
  double value = 0.0;
  std::string spelling;      // as written, without suffix: the emitter prints it back unchanged
  bool half_suffix = false;  // 1.5h
  FloatLiteralExpr(Loc l) : Expr(ExprKind::FloatLiteral, l) {}
};

struct BoolLiteralExpr : Expr {
  bool value = false;
  BoolLiteralExpr(Loc l) : Expr(ExprKind::BoolLiteral, l) {}
};

struct NameExpr : Expr {
  std::string name;
  const Decl* decl = nullptr;  // sema: a VarDecl or ParamDecl
  NameExpr(Loc l) : Expr(ExprKind::Name, l) {}
};

enum class UnaryOp : uint8_t { Plus, Minus, Not, BitNot, PreIncrement, PreDecrement, PostIncrement, PostDecrement };

struct UnaryExpr : Expr {
  UnaryOp op;
  ExprPtr operand;
  UnaryExpr(Loc l, UnaryOp o) : Expr(ExprKind::Unary, l), op(o) {}
};

enum class BinaryOp : uint8_t {
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Shl,
  Shr,
  BitAnd,
  BitOr,
  BitXor,
  LogicalAnd,
  LogicalOr,
  Less,
  Greater,
  LessEqual,
  GreaterEqual,
  Equal,
  NotEqual,
  Comma,
};

struct BinaryExpr : Expr {
  BinaryOp op;
  ExprPtr lhs;
  ExprPtr rhs;
  BinaryExpr(Loc l, BinaryOp o) : Expr(ExprKind::Binary, l), op(o) {}
};

// `=` is AssignOp::Assign; compound forms carry their arithmetic operator.
enum class AssignOp : uint8_t { Assign, Add, Sub, Mul, Div, Mod, Shl, Shr, BitAnd, BitOr, BitXor };

// The arithmetic of a compound assignment: AssignOp::Add -> BinaryOp::Add; nothing for `=`.
inline std::optional<BinaryOp> compound_operator(AssignOp op) {
  switch (op) {
    case AssignOp::Assign: return std::nullopt;
    case AssignOp::Add: return BinaryOp::Add;
    case AssignOp::Sub: return BinaryOp::Sub;
    case AssignOp::Mul: return BinaryOp::Mul;
    case AssignOp::Div: return BinaryOp::Div;
    case AssignOp::Mod: return BinaryOp::Mod;
    case AssignOp::Shl: return BinaryOp::Shl;
    case AssignOp::Shr: return BinaryOp::Shr;
    case AssignOp::BitAnd: return BinaryOp::BitAnd;
    case AssignOp::BitOr: return BinaryOp::BitOr;
    case AssignOp::BitXor: return BinaryOp::BitXor;
  }
  return std::nullopt;
}

struct AssignExpr : Expr {
  AssignOp op;
  ExprPtr target;
  ExprPtr value;
  AssignExpr(Loc l, AssignOp o) : Expr(ExprKind::Assign, l), op(o) {}
};

// c ? a : b. HLSL evaluates it component-wise when c is a vector (both sides are evaluated).
struct ConditionalExpr : Expr {
  ExprPtr condition;
  ExprPtr then_value;
  ExprPtr else_value;
  ConditionalExpr(Loc l) : Expr(ExprKind::Conditional, l) {}
};

enum class CallKind : uint8_t {
  Unresolved,   // before sema
  Function,     // a user function: `function`
  Intrinsic,    // a built-in function: `intrinsic`
  Constructor,  // float3(...), float2x2(...): `type` is the constructed type
  Method,       // object.Sample(...): `object` and `intrinsic`
  // printf("format", args...) as DXC reads it for Vulkan (GL_EXT_debug_printf): `format` holds
  // the string literal as written, quotes and escapes included; `args` the values.
  Printf,
};

struct CallExpr : Expr {
  std::string callee;  // the name as written (for a method, the method's name)
  ExprPtr object;      // a method's object, else null
  AstVector<ExprPtr> args;
  Type constructed;                           // parser: the type of a constructor call
  CallKind call_kind = CallKind::Unresolved;  // parser sets Constructor; sema the rest
  const FunctionDecl* function = nullptr;     // sema
  uint16_t intrinsic = 0;                     // sema: an IntrinsicId (intrinsics.h)
  std::string format;                         // Printf's
  CallExpr(Loc l) : Expr(ExprKind::Call, l) {}
};

// The components a swizzle picks, at most 4, held in its node: a swizzle is among the commonest
// expressions, and a vector would be one heap allocation each.
class Swizzle {
 public:
  static constexpr size_t kMaxComponents = 4;
  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  void clear() { count_ = 0; }
  // The parsers of swizzles check the count first; a fifth component is dropped, not written past the end.
  void push_back(uint8_t component) {
    if (count_ < kMaxComponents) components_[count_++] = component;
  }
  uint8_t operator[](size_t i) const { return components_[i]; }
  const uint8_t* begin() const { return components_; }
  const uint8_t* end() const { return components_ + count_; }

 private:
  uint8_t components_[kMaxComponents] = {};
  uint8_t count_ = 0;
};

// a.b: a struct field or a swizzle (xyzw / rgba, and _m00 / _11 on matrices).
struct MemberExpr : Expr {
  ExprPtr object;
  std::string member;
  int field_index = -1;  // sema: the field of a struct
  Swizzle swizzle;       // sema: component indices (for matrices: row * 4 + col)
  MemberExpr(Loc l) : Expr(ExprKind::Member, l) {}
};

struct IndexExpr : Expr {
  ExprPtr object;
  ExprPtr index;
  IndexExpr(Loc l) : Expr(ExprKind::Index, l) {}
};

// (float3)x: an explicit conversion.
struct CastExpr : Expr {
  Type target;
  ExprPtr operand;
  CastExpr(Loc l) : Expr(ExprKind::Cast, l) {}
};

// { a, b, c } in an initializer; sema gives it the declared type.
struct InitListExpr : Expr {
  AstVector<ExprPtr> elements;
  InitListExpr(Loc l) : Expr(ExprKind::InitList, l) {}
};

// An implicit conversion inserted by sema: `operand` converted to `type` (splat, truncation,
// scalar type change). The emitter writes it out explicitly, since GLSL converts far less.
struct ConversionExpr : Expr {
  ExprPtr operand;
  ConversionExpr(Loc l) : Expr(ExprKind::Conversion, l) {}
};

// ---------------------------------------------------------------------------------------------
// Statements

enum class StmtKind : uint8_t {
  Block,
  Expr,
  Decl,
  If,
  For,
  While,
  DoWhile,
  Switch,
  Break,
  Continue,
  Return,
  Discard,
  Empty,
};

struct Stmt : AstNodeMemory {
  StmtKind kind;
  Loc loc;
  std::vector<Attribute> attributes;
  explicit Stmt(StmtKind k, Loc l) : kind(k), loc(l) {}
  virtual ~Stmt() = default;
};

struct BlockStmt : Stmt {
  AstVector<StmtPtr> statements;
  BlockStmt(Loc l) : Stmt(StmtKind::Block, l) {}
};

struct ExprStmt : Stmt {
  ExprPtr expr;
  ExprStmt(Loc l) : Stmt(StmtKind::Expr, l) {}
};

struct VarDecl;
// float a = 1, b[2];
struct DeclStmt : Stmt {
  AstVector<std::unique_ptr<VarDecl>> vars;
  DeclStmt(Loc l) : Stmt(StmtKind::Decl, l) {}
};

struct IfStmt : Stmt {
  ExprPtr condition;
  StmtPtr then_branch;
  StmtPtr else_branch;  // may be null
  IfStmt(Loc l) : Stmt(StmtKind::If, l) {}
};

struct ForStmt : Stmt {
  StmtPtr init;       // a DeclStmt, an ExprStmt or null
  ExprPtr condition;  // may be null
  ExprPtr step;       // may be null
  StmtPtr body;
  ForStmt(Loc l) : Stmt(StmtKind::For, l) {}
};

struct WhileStmt : Stmt {
  ExprPtr condition;
  StmtPtr body;
  WhileStmt(Loc l) : Stmt(StmtKind::While, l) {}
};

struct DoWhileStmt : Stmt {
  StmtPtr body;
  ExprPtr condition;
  DoWhileStmt(Loc l) : Stmt(StmtKind::DoWhile, l) {}
};

// switch (c) { case 1: ... default: ... }: each label with the statements up to the next one
// (control falls through to them, as in C).
struct SwitchCase {
  ExprPtr value;  // null for `default`
  Loc loc;
  std::vector<StmtPtr> statements;
};

struct SwitchStmt : Stmt {
  ExprPtr condition;
  std::vector<SwitchCase> cases;
  SwitchStmt(Loc l) : Stmt(StmtKind::Switch, l) {}
};

struct ReturnStmt : Stmt {
  ExprPtr value;  // may be null
  ReturnStmt(Loc l) : Stmt(StmtKind::Return, l) {}
};

struct SimpleStmt : Stmt {  // break, continue, discard, ;
  using Stmt::Stmt;
};

// ---------------------------------------------------------------------------------------------
// Declarations

enum class DeclKind : uint8_t { Var, Param, Struct, Function, CBuffer, Typedef };

struct Decl : AstNodeMemory {
  DeclKind kind;
  Loc loc;  // of the name
  std::string name;
  explicit Decl(DeclKind k, Loc l) : kind(k), loc(l) {}
  virtual ~Decl() = default;
};

// A register binding as written: register(t3), register(s0, space1), register(b0).
struct RegisterBinding {
  char register_class = 0;  // 't', 's', 'b', 'u', or 0 when absent
  uint32_t index = 0;
  uint32_t space = 0;
  Loc loc;
};

// <string UIName = "Smoothness"; float UIMin = 0.0; float UIMax = 1.0;>
struct Annotation {
  Type type;
  std::string name;
  ExprPtr value;  // a literal, a string is kept as text in `text`
  std::string text;
  Loc loc;
};

enum class Interpolation : uint8_t { Default, Linear, Centroid, NoInterpolation, NoPerspective, Sample };

enum class StorageClass : uint8_t {
  Default,  // a local, or a global that is an implicit uniform ($Globals)
  Static,   // `static`: a private global, not a uniform
  Uniform,  // `uniform` written out
  GroupShared,
};

enum class MatrixPacking : uint8_t { Default, RowMajor, ColumnMajor };

struct VarDecl : Decl {
  Type type;
  StorageClass storage = StorageClass::Default;
  bool is_const = false;
  MatrixPacking packing = MatrixPacking::Default;
  Interpolation interpolation = Interpolation::Default;
  std::string semantic;  // : TEXCOORD0 (as written; empty if none)
  Loc semantic_loc;
  RegisterBinding binding;             // : register(t0)
  std::optional<uint32_t> packoffset;  // : packoffset(c1.y) of a cbuffer member, in bytes (20)
  Loc packoffset_loc;
  std::vector<Annotation> annotations;  // <...>
  ExprPtr initializer;
  bool is_global = false;  // parser: declared at file or cbuffer scope
  VulkanAttributes vk;     // [[vk::binding(...)]], [[vk::constant_id(...)]], ...
  VarDecl(Loc l) : Decl(DeclKind::Var, l) {}
};

enum class ParamDirection : uint8_t { In, Out, InOut };

struct ParamDecl : Decl {
  Type type;
  ParamDirection direction = ParamDirection::In;
  bool explicit_in = false;  // `in` written out
  bool is_uniform = false;   // `uniform` parameter of an entry point
  Interpolation interpolation = Interpolation::Default;
  std::string semantic;
  Loc semantic_loc;
  ExprPtr default_value;
  VulkanAttributes vk;  // [[vk::location(N)]], [[vk::builtin(...)]]
  ParamDecl(Loc l) : Decl(DeclKind::Param, l) {}
};

struct FieldDecl {
  Type type;
  std::string name;
  Interpolation interpolation = Interpolation::Default;
  std::string semantic;
  Loc loc;
  Loc semantic_loc;
  VulkanAttributes vk;  // [[vk::location(N)]], [[vk::builtin(...)]]
};

struct StructDecl : Decl {
  std::vector<FieldDecl> fields;
  StructDecl(Loc l) : Decl(DeclKind::Struct, l) {}
};

struct FunctionDecl : Decl {
  Type return_type;
  std::vector<std::unique_ptr<ParamDecl>> params;
  std::string semantic;  // of the return value: float4 frag(...) : SV_Target
  Loc semantic_loc;
  std::vector<Attribute> attributes;
  std::unique_ptr<BlockStmt> body;           // null for a prototype
  const FunctionDecl* definition = nullptr;  // sema: for a prototype, the function it declares
  FunctionDecl(Loc l) : Decl(DeclKind::Function, l) {}
};

struct CBufferDecl : Decl {
  RegisterBinding binding;
  VulkanAttributes vk;  // [[vk::binding(N[, set])]]
  AstVector<std::unique_ptr<VarDecl>> members;
  CBufferDecl(Loc l) : Decl(DeclKind::CBuffer, l) {}
};

struct TypedefDecl : Decl {
  Type type;
  TypedefDecl(Loc l) : Decl(DeclKind::Typedef, l) {}
};

struct TranslationUnit {
  // The memory of the tree's nodes (ast_arena.h). Declared first, so that it goes last.
  AstArena arena;
  std::vector<std::unique_ptr<Decl>> decls;  // in source order

  TranslationUnit() = default;
  TranslationUnit(TranslationUnit&&) noexcept = default;
  // The tree this unit held goes before the arena its nodes are in.
  TranslationUnit& operator=(TranslationUnit&& other) noexcept {
    if (this != &other) {
      decls.clear();
      decls = std::move(other.decls);
      arena = std::move(other.arena);
    }
    return *this;
  }
};

// Every node class fits the arena's alignment.
template <class... Nodes>
inline constexpr bool kNodesFitArena = ((alignof(Nodes) <= AstArena::kAlignment) && ...);
static_assert(
    kNodesFitArena<IntLiteralExpr, FloatLiteralExpr, BoolLiteralExpr, NameExpr, UnaryExpr, BinaryExpr, AssignExpr,
                   ConditionalExpr, CallExpr, MemberExpr, IndexExpr, CastExpr, InitListExpr, ConversionExpr, BlockStmt,
                   ExprStmt, DeclStmt, IfStmt, ForStmt, WhileStmt, DoWhileStmt, SwitchStmt, ReturnStmt, SimpleStmt,
                   VarDecl, ParamDecl, StructDecl, FunctionDecl, CBufferDecl, TypedefDecl>);

}  // namespace xshade::hlsl
