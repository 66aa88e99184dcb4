// HLSL intrinsics in GLSL: one table (kMappings), a few constructs with code of their own (mul,
// clip, sincos), the expansion of templates (which the texture functions of emit_textures.cpp
// share), and the library of xs_* helper functions for what GLSL has no built-in for with HLSL's
// exact meaning.
#include <algorithm>
#include <array>
#include <iterator>
#include <string_view>

#include "glsl/stage_emitter.h"

namespace xshade::glsl::detail {

using namespace hlsl;

namespace {

using I = IntrinsicId;

// Which rows apply: by the element type and shape of the first numeric operand.
enum class Elem : uint8_t { Any, Float, Int, Uint, Bool };
enum class Shape : uint8_t { Any, Scalar, Vector };

// One way to write an intrinsic. Templates:
//   $0..$9   the operands: the call's arguments; for a method, $0 is the texture and the
//            arguments follow ($1 = the SamplerState of Sample)
//   $R       the GLSL type of the result
//   $B0      the GLSL bool type with operand 0's shape
//   xs_name( a helper function from the library below, defined for the operands' types
//   @name    a construct with code of its own
// An operand written twice is evaluated twice; when it is not a simple expression, the whole
// template becomes a helper function, so that it is evaluated once.
struct Mapping {
  I id;
  const char* text;
  Elem elem = Elem::Any;
  Shape shape = Shape::Any;
  bool matrices = false;  // right for matrix operands too (else a matrix operand is an error)
};

constexpr Mapping m(I id, const char* text, Elem elem = Elem::Any, Shape shape = Shape::Any) {
  return {id, text, elem, shape, false};
}
constexpr Mapping matrix(I id, const char* text) { return {id, text, Elem::Any, Shape::Any, true}; }

// The HLSL -> GLSL intrinsic table. For each intrinsic, the first row that applies is used.
constexpr Mapping kMappings[] = {
    m(I::Abs, "$0", Elem::Uint),  // GLSL has no abs(uint)
    m(I::Abs, "abs($0)"),
    m(I::Acos, "acos($0)"),
    m(I::All, "all($0)", Elem::Bool, Shape::Vector),
    m(I::All, "all($B0($0))", Elem::Any, Shape::Vector),
    m(I::All, "$0", Elem::Bool, Shape::Scalar),
    m(I::All, "bool($0)", Elem::Any, Shape::Scalar),
    m(I::Any, "any($0)", Elem::Bool, Shape::Vector),
    m(I::Any, "any($B0($0))", Elem::Any, Shape::Vector),
    m(I::Any, "$0", Elem::Bool, Shape::Scalar),
    m(I::Any, "bool($0)", Elem::Any, Shape::Scalar),
    m(I::Asfloat, "$0", Elem::Float),
    m(I::Asfloat, "intBitsToFloat($0)", Elem::Int),
    m(I::Asfloat, "uintBitsToFloat($0)", Elem::Uint),
    m(I::Asin, "asin($0)"),
    m(I::Asint, "$0", Elem::Int),
    m(I::Asint, "$R($0)", Elem::Uint),
    m(I::Asint, "floatBitsToInt($0)", Elem::Float),
    m(I::Asuint, "$0", Elem::Uint),
    m(I::Asuint, "$R($0)", Elem::Int),
    m(I::Asuint, "floatBitsToUint($0)", Elem::Float),
    m(I::Atan, "atan($0)"),
    m(I::Atan2, "atan($0, $1)"),
    m(I::Ceil, "ceil($0)"),
    m(I::Clamp, "clamp($0, $1, $2)"),
    m(I::Clip, "@clip"),
    m(I::Cos, "cos($0)"),
    m(I::Cosh, "cosh($0)"),
    m(I::Countbits, "$R(bitCount($0))"),
    m(I::Cross, "cross($0, $1)"),
    m(I::Ddx, "dFdx($0)"),  // the same sign: both are d/dx of window x, which points right
    m(I::Ddy, "dFdy($0)"),  // both y-down here (glClipControl upper-left, Vulkan's negative viewport)
    m(I::Degrees, "degrees($0)"),
    matrix(I::Determinant, "determinant($0)"),
    m(I::Distance, "distance($0, $1)"),
    m(I::Dot, "dot($0, $1)", Elem::Float),
    m(I::Dot, "xs_dot($0, $1)"),  // GLSL's dot is for floats only
    m(I::Exp, "exp($0)"),
    m(I::Exp2, "exp2($0)"),
    m(I::F16tof32, "unpackHalf2x16($0).x", Elem::Any, Shape::Scalar),
    m(I::F16tof32, "xs_f16tof32($0)"),
    m(I::F32tof16, "packHalf2x16(vec2($0, 0.0))", Elem::Any, Shape::Scalar),
    m(I::F32tof16, "xs_f32tof16($0)"),
    m(I::Faceforward, "faceforward($0, $1, $2)"),
    m(I::Floor, "floor($0)"),
    m(I::Fma, "fma($0, $1, $2)"),
    m(I::Fmod, "xs_fmod($0, $1)"),  // HLSL truncates; GLSL's mod floors
    m(I::Frac, "fract($0)"),
    m(I::Fwidth, "fwidth($0)"),
    m(I::Isfinite, "xs_isfinite($0)"),
    m(I::Isinf, "isinf($0)"),
    m(I::Isnan, "isnan($0)"),
    m(I::Ldexp, "($0 * exp2($1))"),  // HLSL's exponent is a float; GLSL's ldexp takes an int
    m(I::Length, "length($0)"),
    m(I::Lerp, "mix($0, $1, $2)"),
    m(I::Lit, "xs_lit($0, $1, $2)"),
    m(I::Log, "log($0)"),
    m(I::Log10, "(log2($0) * 0.30102999566398120)"),
    m(I::Log2, "log2($0)"),
    m(I::Mad, "($0 * $1 + $2)"),
    m(I::Max, "max($0, $1)"),
    m(I::Min, "min($0, $1)"),
    m(I::Modf, "modf($0, $1)"),
    matrix(I::Mul, "@mul"),
    m(I::Normalize, "normalize($0)"),
    m(I::Pow, "pow($0, $1)"),
    m(I::Radians, "radians($0)"),
    m(I::Rcp, "(1.0 / $0)"),
    m(I::Reflect, "reflect($0, $1)"),
    m(I::Refract, "refract($0, $1, $2)"),
    m(I::Reversebits, "bitfieldReverse($0)"),
    m(I::Round, "roundEven($0)"),  // HLSL rounds halves to even
    m(I::Rsqrt, "inversesqrt($0)"),
    m(I::Saturate, "clamp($0, 0.0, 1.0)"),
    m(I::Select, "($0 ? $1 : $2)", Elem::Any, Shape::Scalar),
    m(I::Select, "mix($2, $1, $0)"),
    m(I::Sign, "$R(min($0, 1u))", Elem::Uint),
    m(I::Sign, "sign($0)", Elem::Int),
    m(I::Sign, "$R(sign($0))"),  // HLSL's sign is an int
    m(I::Sin, "sin($0)"),
    m(I::Sincos, "@sincos"),
    m(I::Sinh, "sinh($0)"),
    m(I::Smoothstep, "smoothstep($0, $1, $2)"),
    m(I::Sqrt, "sqrt($0)"),
    m(I::Step, "step($0, $1)"),
    m(I::Tan, "tan($0)"),
    m(I::Tanh, "tanh($0)"),
    matrix(I::Transpose, "transpose($0)"),
    m(I::Trunc, "trunc($0)"),
};

bool elem_matches(Elem elem, const Type& type) {
  switch (elem) {
    case Elem::Any: return true;
    case Elem::Float: return type.is_floating();
    case Elem::Int: return type.is_numeric() && type.scalar_type() == ScalarType::Int;
    case Elem::Uint: return type.is_numeric() && type.scalar_type() == ScalarType::Uint;
    case Elem::Bool: return type.is_bool();
  }
  return false;
}

bool shape_matches(Shape shape, const Type& type) {
  switch (shape) {
    case Shape::Any: return true;
    case Shape::Scalar: return type.component_count() == 1;
    case Shape::Vector: return type.component_count() > 1 && !type.is_matrix();
  }
  return false;
}

const Mapping* find_mapping(I id, const Type* first_numeric) {
  // Where each intrinsic's first row is, so that a lookup does not pass every row before it.
  // (An id past every row's has none.)
  constexpr size_t kIds = [] {
    size_t count = 0;
    for (const Mapping& mapping : kMappings) count = std::max(count, size_t(mapping.id) + 1);
    return count;
  }();
  static const std::array<size_t, kIds> kFirstRow = [] {
    std::array<size_t, kIds> first;
    first.fill(std::size(kMappings));
    for (size_t row = std::size(kMappings); row-- > 0;) first[size_t(kMappings[row].id)] = row;
    return first;
  }();
  if (size_t(id) >= kIds) return nullptr;
  for (size_t row = kFirstRow[size_t(id)]; row < std::size(kMappings); ++row) {
    const Mapping& mapping = kMappings[row];
    if (mapping.id != id) continue;
    if (!first_numeric) return &mapping;
    if (elem_matches(mapping.elem, *first_numeric) && shape_matches(mapping.shape, *first_numeric)) return &mapping;
  }
  return nullptr;
}

// Operand `index` of the call is an out parameter of the intrinsic.
bool is_out_operand(const IntrinsicInfo& info, size_t index, bool method, size_t arg_count) {
  if (method) {
    if (index == 0) return false;
    --index;
  }
  for (const IntrinsicSignature& signature : info.signatures)
    if (signature.param_count == arg_count && index < arg_count && signature.params[index].out) return true;
  return false;
}

// A template that is one call or parenthesized group, with postfix parts (`f(x).x`), is a
// primary expression; anything else is parenthesized where it goes.
int template_prec(const std::string& text) {
  size_t i = 0;
  auto skip_group = [&](char open, char close) {
    int depth = 0;
    for (; i < text.size(); ++i) {
      if (text[i] == open) ++depth;
      if (text[i] == close && --depth == 0) {
        ++i;
        return true;
      }
    }
    return false;
  };
  auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '$'; };
  if (i < text.size() && text[i] == '(') {
    if (!skip_group('(', ')')) return kComma;
  } else {
    const size_t start = i;
    while (i < text.size() && is_word(text[i])) ++i;
    if (i == start || i >= text.size() || text[i] != '(' || !skip_group('(', ')')) return kComma;
  }
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
      while (i < text.size() && is_word(text[i])) ++i;
    } else if (text[i] == '[') {
      if (!skip_group('[', ']')) return kComma;
    } else {
      return kComma;
    }
  }
  return kPostfix;
}

// The placeholders of a template, in order, with the text around them.
struct Piece {
  std::string text;      // literal text before the operand
  int operand = -1;      // -1 for the trailing text
  int needed = kAssign;  // the precedence the operand needs where it stands
};

std::vector<Piece> split_template(const std::string& text) {
  std::vector<Piece> pieces;
  pieces.reserve(4);
  size_t literal_start = 0;  // the literal text runs from here to the next operand
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '$' || i + 1 >= text.size() || !std::isdigit(static_cast<unsigned char>(text[i + 1]))) continue;
    std::string literal = text.substr(literal_start, i - literal_start);
    const int index = text[i + 1] - '0';
    const size_t after = i + 2;
    size_t prev = i;
    while (prev > 0 && text[prev - 1] == ' ') --prev;
    const char before_char = prev > 0 ? text[prev - 1] : '\0';
    size_t next = after;
    while (next < text.size() && text[next] == ' ') ++next;
    const char after_char = next < text.size() ? text[next] : '\0';
    int needed = kUnary;
    if (after < text.size() && (text[after] == '.' || text[after] == '['))
      needed = kPostfix;
    else if ((before_char == '(' || before_char == ',') && (after_char == ')' || after_char == ','))
      needed = kAssign;
    pieces.push_back({std::move(literal), index, needed});
    ++i;
    literal_start = i + 1;
  }
  pieces.push_back({text.substr(literal_start), -1, kAssign});
  return pieces;
}

struct SplitTemplate {
  std::vector<Piece> pieces;
  int prec = kComma;  // template_prec of the text
};

// A template split once per thread: templates come from a small fixed set (kMappings and the
// texture forms, with GLSL type names for $R and $B0), and each is expanded again and again.
// Looked up by view: the text is mostly a template of kMappings itself, not a string of its own.
struct TemplateHash {
  using is_transparent = void;
  size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
};

const SplitTemplate& split_template_once(std::string_view text) {
  thread_local std::unordered_map<std::string, SplitTemplate, TemplateHash, std::equal_to<>> split;
  auto it = split.find(text);
  if (it == split.end()) {
    const std::string key(text);
    it = split.emplace(key, SplitTemplate{split_template(key), template_prec(key)}).first;
  }
  return it->second;
}

}  // namespace

std::string replace_all(std::string text, std::string_view from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// ---------------------------------------------------------------------------------------------
// The helper library

std::string StageEmitter::require_helper(const std::string& name, const std::vector<Type>& operands, Loc loc) {
  if (operands.empty()) {
    fail_internal(loc, "helper " + in_quotes(name) + " without operands");
    return name;
  }
  const Type& type = operands[0];
  const uint32_t n = type.component_count();
  const std::string t = type_name(type, loc);
  const std::string ns = std::to_string(n);
  const std::string signature = name + "(" + t + ")";
  std::string definition;
  if (name == "xs_fmod") {
    definition = t + " xs_fmod(" + t + " a, " + t + " b) {\n  return a - b * trunc(a / b);\n}\n";
  } else if (name == "xs_idiv") {
    // HLSL's signed division truncates toward zero; GLSL leaves negative operands undefined.
    if (n == 1)
      definition =
          "int xs_idiv(int a, int b) {\n  int q = int(uint(abs(a)) / uint(abs(b)));\n"
          "  return (a < 0) != (b < 0) ? -q : q;\n}\n";
    else
      definition = t + " xs_idiv(" + t + " a, " + t + " b) {\n  " + t + " q = " + t + "(uvec" + ns + "(abs(a)) / uvec" +
                   ns + "(abs(b)));\n  return mix(q, -q, notEqual(lessThan(a, " + t + "(0)), lessThan(b, " + t +
                   "(0))));\n}\n";
  } else if (name == "xs_imod") {
    // HLSL's remainder has the sign of the dividend.
    if (n == 1)
      definition =
          "int xs_imod(int a, int b) {\n  int r = int(uint(abs(a)) % uint(abs(b)));\n"
          "  return a < 0 ? -r : r;\n}\n";
    else
      definition = t + " xs_imod(" + t + " a, " + t + " b) {\n  " + t + " r = " + t + "(uvec" + ns + "(abs(a)) % uvec" +
                   ns + "(abs(b)));\n  return mix(r, -r, lessThan(a, " + t + "(0)));\n}\n";
  } else if (name == "xs_isfinite") {
    if (n == 1)
      definition = "bool xs_isfinite(float a) {\n  return !isinf(a) && !isnan(a);\n}\n";
    else
      definition = "bvec" + ns + " xs_isfinite(" + t + " a) {\n  return not(bvec" + ns + "(uvec" + ns +
                   "(isinf(a)) | uvec" + ns + "(isnan(a))));\n}\n";
  } else if (name == "xs_dot") {
    const std::string scalar = type_name(Type::scalar(type.scalar_type()), loc);
    std::string sum;
    for (uint32_t i = 0; i < n; ++i) sum += std::string(i ? " + " : "") + "p." + "xyzw"[i];
    definition = scalar + " xs_dot(" + t + " a, " + t + " b) {\n  " + t + " p = a * b;\n  return " + sum + ";\n}\n";
  } else if (name == "xs_f16tof32" || name == "xs_f32tof16") {
    const bool to_float = name == "xs_f16tof32";
    const std::string result = (to_float ? "vec" : "uvec") + ns;
    std::string parts;
    for (uint32_t i = 0; i < n; ++i) {
      const std::string c = std::string("a.") + "xyzw"[i];
      parts += (i ? ", " : "") + (to_float ? "unpackHalf2x16(" + c + ").x" : "packHalf2x16(vec2(" + c + ", 0.0))");
    }
    definition = result + " " + name + "(" + t + " a) {\n  return " + result + "(" + parts + ");\n}\n";
  } else if (name == "xs_compare_bilinear") {
    // The four comparisons textureGather returns, (i0, j1), (i1, j1), (i1, j0), (i0, j0), weighted
    // as a bilinear read of the texel coordinate weights its four texels.
    definition =
        "float xs_compare_bilinear(vec4 compared, vec2 texel) {\n  vec2 f = fract(texel - 0.5);\n"
        "  return mix(mix(compared.w, compared.z, f.x), mix(compared.x, compared.y, f.x), f.y);\n}\n";
    helpers_.add(name, definition);  // one definition, whatever the operands' types
    return name;
  } else if (name == "xs_lit") {
    // HLSL's documented lit(): ambient 1, diffuse max(n.l, 0), specular (n.h)^m unless either
    // dot product is negative, w 1. Its arguments are float scalars, whatever was passed.
    definition =
        "vec4 xs_lit(float n_dot_l, float n_dot_h, float m) {\n"
        "  float specular = (n_dot_l < 0.0 || n_dot_h < 0.0) ? 0.0 : pow(n_dot_h, m);\n"
        "  return vec4(1.0, max(n_dot_l, 0.0), specular, 1.0);\n}\n";
    helpers_.add(name, definition);
    return name;
  } else if (name == "xs_clip") {
    if (n == 1)
      definition = "void xs_clip(float a) {\n  if (a < 0.0) discard;\n}\n";
    else
      definition = "void xs_clip(" + t + " a) {\n  if (any(lessThan(a, " + t + "(0.0)))) discard;\n}\n";
  } else {
    fail_internal(loc, "no helper " + in_quotes(name));
    return name;
  }
  helpers_.add(signature, definition);
  return name;
}

// ---------------------------------------------------------------------------------------------
// Calls

bool StageEmitter::clip_statement(const Expr* e) {
  if (!e || e->kind != ExprKind::Call) return false;
  const auto* call = static_cast<const CallExpr*>(e);
  if (call->call_kind != CallKind::Intrinsic || IntrinsicId(call->intrinsic) != I::Clip || call->args.size() != 1)
    return false;
  const Expr* x = call->args[0].get();
  const Type& type = x->type;
  if (type.is_matrix()) {
    out_.line(matrix_intrinsic_call(*call, {x}).text + ";");
    return true;
  }
  const Code value = expr(x);
  if (type.component_count() == 1)
    out_.line("if (" + operand(value, kRelational) + " < 0.0) discard;");
  else
    out_.line("if (any(lessThan(" + operand(value, kAssign) + ", " + type_name(type, e->loc) + "(0.0)))) discard;");
  return true;
}

Code StageEmitter::intrinsic_call(const CallExpr& call) {
  const auto id = IntrinsicId(call.intrinsic);
  const IntrinsicInfo& info = intrinsic_info(id);
  const bool method = call.call_kind == CallKind::Method;
  if (method || is_dx9_sampling(id)) return texture_call(call);
  std::vector<const Expr*> operands;
  if (method) operands.push_back(call.object.get());
  for (const ExprPtr& arg : call.args) operands.push_back(arg.get());
  for (const Expr* e : operands) {
    if (!e) {
      fail_internal(call.loc, "an argument of " + in_quotes(info.name) + " is missing");
      return {"0"};
    }
  }
  const Type* first_numeric = nullptr;
  for (const Expr* e : operands) {
    if (e->type.is_numeric()) {
      first_numeric = &e->type;
      break;
    }
  }
  const Mapping* mapping = find_mapping(id, first_numeric);
  if (!mapping || !mapping->matrices) {
    for (const Expr* e : operands)
      if (e->type.is_matrix()) return matrix_intrinsic_call(call, operands);
  }
  if (!mapping) {
    fail(call.loc, in_quotes(info.name) + " is not supported on this target");
    return {"0"};
  }

  const std::string_view text = mapping->text;
  if (text == "@mul") {
    const Expr* a = operands[0];
    const Expr* b = operands[1];
    const Code l = expr(a);
    const Code r = expr(b);
    if (a->type.component_count() == 1 || b->type.component_count() == 1)
      return {operand(l, kMultiplicative) + " * " + operand(r, kMultiplicative + 1), kMultiplicative};
    if (!a->type.is_matrix() && !b->type.is_matrix()) {
      const std::string dot = a->type.is_floating() ? "dot" : require_helper("xs_dot", {a->type}, call.loc);
      return {dot + "(" + operand(l, kAssign) + ", " + operand(r, kAssign) + ")", kPostfix};
    }
    // With G = M^T: mul(v, M) = G * v, mul(M, v) = v * G, mul(A, B) = G_B * G_A.
    return {operand(r, kMultiplicative) + " * " + operand(l, kMultiplicative + 1), kMultiplicative};
  }
  if (text == "@clip") {
    const std::string name = require_helper("xs_clip", {operands[0]->type}, call.loc);
    return {name + "(" + operand(expr(operands[0]), kAssign) + ")", kPostfix};
  }
  if (text == "@sincos") {
    const Expr* x = operands[0];
    const Code value = expr(x);
    if (!is_simple(x)) {
      // Once, in a helper: its out parameters need the argument types exactly.
      const std::string t = type_name(x->type, call.loc);
      helpers_.add("xs_sincos(" + t + ")", "void xs_sincos(" + t + " a, out " + t + " s, out " + t +
                                               " c) {\n  s = sin(a);\n  c = cos(a);\n}\n");
      return {"xs_sincos(" + operand(value, kAssign) + ", " + operand(out_argument(operands[1]), kAssign) + ", " +
                  operand(out_argument(operands[2]), kAssign) + ")",
              kPostfix};
    }
    std::string parts;
    for (size_t i = 1; i <= 2; ++i) {
      const Expr* target = operands[i];
      const Type& param_type = target->type;
      if (target->kind == ExprKind::Conversion) target = static_cast<const ConversionExpr*>(target)->operand.get();
      const Code result{std::string(i == 1 ? "sin(" : "cos(") + operand(value, kAssign) + ")", kPostfix};
      parts += (i == 1 ? "" : ", ") + operand(expr(target), kUnary) + " = " +
               operand(convert(half_value(result, param_type), param_type, target->type, call.loc), kAssign);
    }
    return {"(" + parts + ")"};
  }
  std::vector<bool> out(operands.size(), false);
  for (size_t i = 0; i < operands.size(); ++i) out[i] = is_out_operand(info, i, method, call.args.size());
  return expand_template(text, call, operands, out);
}

Code StageEmitter::expand_template(std::string_view text, const CallExpr& call,
                                   const std::vector<const Expr*>& operands, const std::vector<bool>& out,
                                   bool always_helper) {
  const IntrinsicInfo& info = intrinsic_info(IntrinsicId(call.intrinsic));
  const std::string result_type = type_name(call.type, call.loc);  // also reports a type GLSL lacks
  // Most templates have no $R or $B0: they are expanded as they stand, without a copy.
  std::string filled_in;
  std::string_view expanded = text;
  const bool has_result_type = text.find("$R") != std::string_view::npos;
  if (has_result_type || text.find("$B0") != std::string_view::npos) {
    filled_in = text;
    if (has_result_type) filled_in = replace_all(std::move(filled_in), "$R", result_type);
    if (filled_in.find("$B0") != std::string::npos)
      filled_in = replace_all(std::move(filled_in), "$B0", bool_type(operands[0]->type.component_count()));
    expanded = filled_in;
  }
  std::vector<Type> numeric_types;  // made only for a template that calls a helper
  for (size_t at = expanded.find("xs_"); at != std::string_view::npos; at = expanded.find("xs_", at + 3)) {
    if (numeric_types.empty())
      for (const Expr* e : operands)
        if (e->type.is_numeric()) numeric_types.push_back(e->type);
    const size_t open = expanded.find('(', at);
    if (open != std::string_view::npos)
      require_helper(std::string(expanded.substr(at, open - at)), numeric_types, call.loc);
  }

  const SplitTemplate& split = split_template_once(expanded);
  const std::vector<Piece>& pieces = split.pieces;
  std::vector<int> uses(operands.size(), 0);
  for (const Piece& piece : pieces) {
    if (piece.operand < 0) continue;
    if (size_t(piece.operand) >= operands.size()) {
      fail_internal(call.loc, "the template of " + in_quotes(info.name) + " names a missing operand");
      return {"0"};
    }
    ++uses[size_t(piece.operand)];
  }
  bool needs_helper = always_helper;
  for (size_t i = 0; i < operands.size(); ++i)
    if (uses[i] > 1 && !is_simple(operands[i])) needs_helper = true;
  // vk: glslang makes a combined sampler ($0, $1) before it evaluates the later arguments, and
  // one that branches would leave the OpSampledImage in another block than the call consuming
  // it, which SPIR-V forbids. In a helper the arguments are evaluated first, in the caller.
  if (flavour_ == Flavour::Vk && expanded.find("($0, $1)") != std::string::npos)
    for (size_t i = 2; i < operands.size(); ++i)
      if (uses[i] > 0 && branches(operands[i])) needs_helper = true;

  std::vector<std::optional<Code>> codes(operands.size());
  auto code_of = [&](size_t i) -> const Code& {
    if (!codes[i]) codes[i] = out[i] ? out_argument(operands[i]) : expr(operands[i]);
    return *codes[i];
  };

  if (needs_helper) {
    // xs_<intrinsic>(operands...) { return <template>; }, numbered when one intrinsic needs
    // helpers of different bodies or result types for the same parameter types.
    std::string params, args, body;
    for (size_t i = 0; i < operands.size(); ++i) {
      if (uses[i] == 0) continue;
      const Type& operand_type = operands[i]->type;
      const std::string type = operand_type.is_resource()
                                   ? resource_type(operand_type, lower::named_decl(operands[i]), call.loc)
                                   : type_name(operand_type, call.loc);
      params += (params.empty() ? "" : ", ") + std::string(out[i] ? "out " : "") + type + " a" + std::to_string(i);
      args += (args.empty() ? "" : ", ") + operand(code_of(i), kAssign);
    }
    for (const Piece& piece : pieces) {
      body += piece.text;
      if (piece.operand >= 0) body += "a" + std::to_string(piece.operand);
    }
    const std::string result = type_name(call.type, call.loc);
    const std::string unnamed =
        result + " (" + params + ") {\n  " + (call.type.is_void() ? "" : "return ") + body + ";\n}\n";
    std::string& name = template_helpers_[unnamed];
    if (name.empty()) {
      const std::string base = "xs_" + std::string(info.name);
      const int count = ++template_helper_count_[base];
      name = count == 1 ? base : base + "_" + std::to_string(count);
      helpers_.add(name + "(" + params + ")", result + " " + name + unnamed.substr(result.size() + 1));
    }
    return {name + "(" + args + ")", kPostfix};
  }

  if (pieces.size() == 2 && pieces[0].text.empty() && pieces[1].text.empty()) return code_of(size_t(pieces[0].operand));
  std::string result;
  for (const Piece& piece : pieces) {
    result += piece.text;
    if (piece.operand >= 0) append_operand(result, code_of(size_t(piece.operand)), piece.needed);
  }
  return {std::move(result), split.prec};
}

Code StageEmitter::matrix_intrinsic_call(const CallExpr& call, const std::vector<const Expr*>& operands) {
  const auto id = IntrinsicId(call.intrinsic);
  const IntrinsicInfo& info = intrinsic_info(id);
  const Type* matrix = nullptr;
  for (const Expr* e : operands) {
    if (e->type.is_matrix()) {
      matrix = &e->type;
      break;
    }
  }
  if (!matrix) {
    fail_internal(call.loc, "" + in_quotes(info.name) + " has no matrix operand");
    return {"0"};
  }
  // GLSL holds HLSL's floatRxC as a matRxC: R columns of C components, each one HLSL row. A
  // component-wise operation does not care which way round it goes.
  const uint32_t columns = matrix->rows();
  const Type column = Type::vector(matrix->scalar_type(), matrix->cols());
  auto column_of = [](const Type& type) {
    return type.is_matrix() ? Type::vector(type.scalar_type(), type.cols()) : type;
  };
  // Operand k inside the helper, and its column i.
  auto operand_at = [&](size_t k, uint32_t i) {
    return "a" + std::to_string(k) + (operands[k]->type.is_matrix() ? "[" + std::to_string(i) + "]" : "");
  };

  std::vector<std::string> parts;  // one per column
  std::string result_type = type_name(call.type, call.loc);
  std::string body;
  if (id == I::Clip) {
    const std::string zero = type_name(column, call.loc) + "(0.0)";
    for (uint32_t i = 0; i < columns; ++i) parts.push_back("any(lessThan(" + operand_at(0, i) + ", " + zero + "))");
  } else if (id == I::Sincos) {
    for (uint32_t i = 0; i < columns; ++i)
      parts.push_back(operand_at(1, i) + " = sin(" + operand_at(0, i) + ");\n  " + operand_at(2, i) + " = cos(" +
                      operand_at(0, i) + ");");
  } else {
    const Mapping* mapping = find_mapping(id, &column);
    if (!mapping || mapping->text[0] == '@' || !(call.type.is_matrix() || id == I::All || id == I::Any)) {
      fail(call.loc, in_quotes(info.name) + " of a matrix is not supported on this target");
      return {"0"};
    }
    std::string expanded = replace_all(mapping->text, "$R", type_name(column_of(call.type), call.loc));
    expanded = replace_all(expanded, "$B0", bool_type(column.component_count()));
    std::vector<Type> column_types;
    for (const Expr* e : operands)
      if (e->type.is_numeric()) column_types.push_back(column_of(e->type));
    for (size_t at = expanded.find("xs_"); at != std::string::npos; at = expanded.find("xs_", at + 3)) {
      const size_t open = expanded.find('(', at);
      if (open != std::string::npos) require_helper(expanded.substr(at, open - at), column_types, call.loc);
    }
    const std::vector<Piece> pieces = split_template(expanded);
    for (uint32_t i = 0; i < columns; ++i) {
      std::string part;
      for (const Piece& piece : pieces) {
        part += piece.text;
        if (piece.operand < 0) continue;
        if (size_t(piece.operand) >= operands.size()) {
          fail_internal(call.loc, "the template of " + in_quotes(info.name) + " names a missing operand");
          return {"0"};
        }
        part += operand_at(size_t(piece.operand), i);
      }
      parts.push_back(std::move(part));
    }
  }
  auto joined = [&](const char* separator) {
    std::string text;
    for (size_t i = 0; i < parts.size(); ++i) text += (i ? separator : "") + parts[i];
    return text;
  };
  if (id == I::Clip)
    body = "if (" + joined(" || ") + ") discard;";
  else if (id == I::Sincos)
    body = joined("\n  ");
  else if (id == I::All)
    body = "return " + joined(" && ") + ";";
  else if (id == I::Any)
    body = "return " + joined(" || ") + ";";
  else
    body = "return " + result_type + "(" + joined(", ") + ");";

  const std::string name = "xs_" + std::string(info.name);
  std::string params, args;
  for (size_t k = 0; k < operands.size(); ++k) {
    const bool out = is_out_operand(info, k, false, call.args.size());
    params += (k ? ", " : "") + std::string(out ? "out " : "") + type_name(operands[k]->type, call.loc) + " a" +
              std::to_string(k);
    args += (k ? ", " : "") + operand(out ? out_argument(operands[k]) : expr(operands[k]), kAssign);
  }
  helpers_.add(name + "(" + params + ")", result_type + " " + name + "(" + params + ") {\n  " + body + "\n}\n");
  return {name + "(" + args + ")", kPostfix};
}

}  // namespace xshade::glsl::detail
