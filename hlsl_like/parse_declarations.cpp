// The parser's declarations: file scope, functions, structs, typedefs, cbuffers, variables and
// their declarators (dimensions, semantics, registers, packoffsets, annotations), attributes,
// types and qualifiers.
// Why this file is long: a declaration is most of HLSL's grammar (types, declarators and their
// annotations); split further, a declarator's parts would sit apart from the one that reads them.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl::parser_detail {
namespace {

std::optional<uint32_t> register_number(std::string_view digits) {
  if (digits.empty() || digits.size() > 9) return std::nullopt;
  uint32_t value = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + uint32_t(c - '0');
  }
  return value;
}

}  // namespace

// -------------------------------------------------------------------------------------------
// Types

// A template's closing '>'; the first half of a '>>' counts, for Texture2D<vector<float, 4>>.
bool Parser::expect_closing_angle(size_t open_index) {
  if (is(">")) {
    advance();
    return true;
  }
  if (is(">>")) {
    if (split_angle_) {
      advance();
    } else {
      split_angle_ = true;
    }
    return true;
  }
  error_unmatched(">", open_index);
  return false;
}

// A small integer in a template argument list: vector<float, 3>.
std::optional<uint64_t> Parser::parse_template_number() {
  if (cur().kind != TokenKind::IntLiteral) {
    error_here("expected a number");
    return std::nullopt;
  }
  const IntValue value = parse_int_spelling(cur().text);
  if (!value.valid || value.too_large) {
    error_here("invalid integer literal " + in_quotes(cur().text));
    return std::nullopt;
  }
  advance();
  return value.value;
}

// The scalar argument of vector<...> and matrix<...>.
std::optional<ScalarType> Parser::parse_template_scalar() {
  const BuiltinType* builtin = find_builtin_type(pos_);
  if (!builtin || !builtin->type.is_scalar() ||
      (builtin->word != TypeWord::Plain && builtin->word != TypeWord::Double)) {
    error_here("expected a scalar type");
    return std::nullopt;
  }
  if (builtin->word == TypeWord::Double) error_here("double is not supported");
  advance();
  return builtin->type.scalar_type();
}

// vector<T, N> and matrix<T, R, C>, after the word.
std::optional<Type> Parser::parse_shape_template(bool matrix) {
  const size_t open = pos_;
  advance();
  const std::optional<ScalarType> scalar = parse_template_scalar();
  if (!scalar) return std::nullopt;
  uint64_t dims[2] = {1, 1};
  for (int i = 0; i < (matrix ? 2 : 1); ++i) {
    if (!accept(",")) {
      error_unmatched(">", open);
      return std::nullopt;
    }
    const size_t at = pos_;
    const std::optional<uint64_t> n = parse_template_number();
    if (!n) return std::nullopt;
    if (*n < 1 || *n > 4) {
      error_at(at, matrix ? "matrix dimensions must be between 1 and 4" : "vector size must be between 1 and 4");
      return std::nullopt;
    }
    dims[i] = *n;
  }
  if (!expect_closing_angle(open)) return std::nullopt;
  if (matrix) return Type::matrix(*scalar, uint32_t(dims[0]), uint32_t(dims[1]));
  return Type::vector(*scalar, uint32_t(dims[0]));
}

// A type at the current token. nullopt (reported) when there is no type at all; the Error
// type (reported) when a type was written but cannot be used, so the declaration goes on.
std::optional<Type> Parser::parse_type(bool allow_void) {
  const Token& token = cur();
  if (token.kind != TokenKind::Identifier || is_reserved(pos_)) {
    error_here("expected a type");
    return std::nullopt;
  }
  const Word& w = word_at(pos_);
  if (w.names_user_type()) {
    advance();
    return user_types_[size_t(w.user_type)];
  }
  const BuiltinType* builtin = w.info->builtin;
  if (!builtin) {
    if (!report_hidden_type(pos_)) error_here(in_quotes(token.text) + " is not a type");
    advance();
    return Type::error();
  }
  const size_t word_index = pos_;
  switch (builtin->word) {
    case TypeWord::Plain: advance(); return builtin->type;
    case TypeWord::Double:
      error_here("double is not supported");
      advance();
      return builtin->type;
    case TypeWord::Void:
      advance();
      if (allow_void) return builtin->type;
      error_at(word_index, "'void' is only valid as a function return type");
      return Type::error();
    case TypeWord::Vector:
    case TypeWord::Matrix:
      advance();
      if (!is("<")) return builtin->type;
      return parse_shape_template(builtin->word == TypeWord::Matrix);
    case TypeWord::Texture: {
      advance();
      if (!is("<")) return builtin->type;
      // Texture2D<float>, Texture2DMS<float4, 8>: the texel type, and a multisampled texture's
      // sample count (which only the API side needs).
      const size_t open = pos_;
      advance();
      const size_t texel_index = pos_;
      std::optional<Type> texel;
      {
        DepthGuard guard(*this);
        if (!guard.ok()) return std::nullopt;
        texel = parse_type(false);
      }
      if (!texel) return std::nullopt;
      if (is_multisampled(builtin->type.texture_shape()) && accept(",") && !parse_template_number())
        return std::nullopt;
      if (!expect_closing_angle(open)) return std::nullopt;
      if (texel->is_error()) return Type::error();
      if (!texel->is_scalar() && !texel->is_vector()) {
        error_at(texel_index, "the texel type of " + in_quotes(tok(word_index).text) +
                                  " must be a scalar or vector, not " + in_quotes(texel->name()));
        return Type::error();
      }
      return Type::texture(builtin->type.texture_shape(), *texel);
    }
    case TypeWord::Buffer: {
      advance();
      const BufferKind kind = builtin->type.buffer_kind();
      const bool byte_address = kind == BufferKind::ByteAddressBuffer || kind == BufferKind::RWByteAddressBuffer;
      const bool structured = kind == BufferKind::StructuredBuffer || kind == BufferKind::RWStructuredBuffer ||
                              kind == BufferKind::AppendStructuredBuffer || kind == BufferKind::ConsumeStructuredBuffer;
      if (byte_address || !is("<")) {
        if (structured) {
          error_here("expected '<' after " + in_quotes(tok(word_index).text) +
                     ": a structured buffer needs an element type");
          return Type::error();
        }
        return builtin->type;
      }
      const size_t open = pos_;
      advance();
      std::optional<Type> element;
      {
        DepthGuard guard(*this);
        if (!guard.ok()) return std::nullopt;
        element = parse_type(false);
      }
      if (!element || !expect_closing_angle(open)) return std::nullopt;
      return Type::buffer(kind, *element);
    }
    case TypeWord::ConstantBuffer: {
      advance();
      if (!is("<")) {
        error_here("expected '<' after 'ConstantBuffer': it holds a struct, as in ConstantBuffer<PerFrame>");
        return Type::error();
      }
      const size_t open = pos_;
      advance();
      const size_t struct_index = pos_;
      std::optional<Type> structure;
      {
        DepthGuard guard(*this);
        if (!guard.ok()) return std::nullopt;
        structure = parse_type(false);
      }
      if (!structure || !expect_closing_angle(open)) return std::nullopt;
      if (structure->is_error()) return Type::error();
      if (structure->kind() != TypeKind::Struct) {
        error_at(struct_index, "ConstantBuffer holds a struct, not " + in_quotes(structure->name()));
        return Type::error();
      }
      return Type::constant_buffer(*structure);
    }
    case TypeWord::Unsupported:
      error_here(in_quotes(token.text) + " is not supported");
      advance();
      if (is("<") && !skip_angles()) return std::nullopt;
      return Type::error();
  }
  return std::nullopt;
}

// Past a <...> that will not be read (an unsupported type's arguments).
bool Parser::skip_angles() {
  const size_t open = pos_;
  advance();
  for (size_t n = 0; n < kMaxTemplateLookahead && !at_end(); ++n) {
    if (is(">") || is(">>")) return expect_closing_angle(open);
    if (is(";") || is("{") || is("}")) break;
    advance();
  }
  error_unmatched(">", open);
  return false;
}

// -------------------------------------------------------------------------------------------
// Qualifiers

void Parser::parse_specifiers(DeclContext context, Specifiers& spec) {
  while (is_specifier_at(pos_)) {
    const std::string_view word = cur().text;
    spec.any = true;
    const bool param = context == DeclContext::Param;
    if (const auto interpolation = info(pos_).interpolation) {
      spec.interpolation = *interpolation;
    } else if (word == "in" || word == "out" || word == "inout") {
      if (!param) {
        error_here(in_quotes(word) + " is only allowed on parameters");
      } else if (word == "in") {
        spec.explicit_in = true;
      } else {
        spec.direction = word == "out" ? ParamDirection::Out : ParamDirection::InOut;
      }
    } else if (word == "static") {
      if (context == DeclContext::Global || context == DeclContext::Local) {
        spec.storage = StorageClass::Static;
      } else {
        error_here("'static' is not allowed here");
      }
    } else if (word == "uniform") {
      if (param) {
        spec.is_uniform = true;
      } else if (context == DeclContext::Global || context == DeclContext::CBufferMember) {
        spec.storage = StorageClass::Uniform;
      } else {
        error_here("'uniform' is not allowed here");
      }
    } else if (word == "groupshared") {
      if (context == DeclContext::Global) {
        spec.storage = StorageClass::GroupShared;
      } else {
        error_here("'groupshared' is not allowed here");
      }
    } else if (word == "const") {
      spec.is_const = true;
    } else if (word == "row_major") {
      spec.packing = MatrixPacking::RowMajor;
    } else if (word == "column_major") {
      spec.packing = MatrixPacking::ColumnMajor;
    }
    // extern, volatile, precise, inline, shared, snorm, unorm: accepted and ignored.
    advance();
  }
}

// -------------------------------------------------------------------------------------------
// Declarator pieces

// [N][M]... after a name. An unsized first dimension gives length 0 and sets *unsized.
std::optional<Type> Parser::parse_array_dims(const Type& base, bool allow_unsized, bool* unsized) {
  std::vector<uint32_t> lengths;
  if (unsized) *unsized = false;
  while (is("[")) {
    const size_t open = pos_;
    advance();
    if (is("]")) {
      if (!allow_unsized || !lengths.empty()) {
        error_here("expected an array size");
        return std::nullopt;
      }
      *unsized = true;
      lengths.push_back(0);
      advance();
      continue;
    }
    const size_t size_index = pos_;
    ExprPtr size;
    {
      DepthGuard guard(*this);
      if (!guard.ok()) return std::nullopt;
      size = parse_conditional();
    }
    if (!size) return std::nullopt;
    if (!is("]")) {
      error_unmatched("]", open);
      return std::nullopt;
    }
    advance();
    const std::optional<int64_t> value = evaluate_int(*size);
    uint32_t length = 1;
    if (!value) {
      if (const NameExpr* uniform = find_uniform_constant(*size))
        error_at(size_index, "array size must be an integer constant; " + in_quotes(uniform->name) +
                                 " is a uniform (a file-scope const without static); declare it 'static const'");
      else
        error_at(size_index, "array size must be an integer constant");
    } else if (*value <= 0) {
      error_at(size_index, "array size must be positive");
    } else if (*value > kMaxArrayLength) {
      error_at(size_index, "array size is too large (more than " + std::to_string(kMaxArrayLength) + ")");
    } else {
      length = uint32_t(*value);
    }
    lengths.push_back(length);
  }
  Type type = base;
  for (size_t i = lengths.size(); i-- > 0;) type = Type::array(type, lengths[i]);
  return type;
}

// : SEMANTIC, : register(...), : packoffset(...), any number of them. A null `binding` means
// a register is not allowed here, a null `packoffset` a packoffset.
bool Parser::parse_colon_clauses(std::string* semantic, Loc* semantic_loc, RegisterBinding* binding,
                                 VarDecl* packoffset) {
  while (is(":")) {
    advance();
    if (is_word("register")) {
      const size_t at = pos_;
      RegisterBinding parsed;
      if (!parse_register(parsed)) return false;
      if (binding) {
        *binding = parsed;
      } else {
        error_at(at, "register bindings are only allowed on global variables and cbuffers");
      }
    } else if (is_word("packoffset")) {
      if (!packoffset) error_here("packoffset is only allowed on the members of a cbuffer");
      const Loc loc = cur().loc;
      advance();
      std::optional<uint32_t> offset = parse_packoffset();
      if (!offset) return false;
      if (packoffset) {
        packoffset->packoffset = offset;
        packoffset->packoffset_loc = loc;
      }
    } else if (cur().kind == TokenKind::Identifier && !is_reserved(pos_)) {
      if (semantic) {
        *semantic = std::string(cur().text);
        *semantic_loc = cur().loc;
      } else {
        error_here("a semantic is not allowed here");
      }
      advance();
    } else {
      error_here("expected a semantic or register after ':'");
      return false;
    }
  }
  return true;
}

// (c3), (c3.z): register 3, component z, as a byte offset (16 * 3 + 4 * 2). After the word.
std::optional<uint32_t> Parser::parse_packoffset() {
  if (!is("(")) {
    error_here("expected '(' after 'packoffset'");
    return std::nullopt;
  }
  const size_t open = pos_;
  advance();
  const Token& name = cur();
  const std::optional<uint32_t> index =
      name.kind == TokenKind::Identifier && name.text.size() > 1 && (name.text[0] | 0x20) == 'c'
          ? register_number(name.text.substr(1))
          : std::nullopt;
  if (!index || *index >= 4096) {
    error_here("invalid packoffset " + in_quotes(name.text) + "; write packoffset(cN) or packoffset(cN.y)");
    return std::nullopt;
  }
  uint32_t offset = *index * 16;
  advance();
  if (accept(".")) {
    const std::string_view component = cur().kind == TokenKind::Identifier ? cur().text : std::string_view();
    const size_t at = std::string_view("xyzw").find(component);
    if (component.size() != 1 || at == std::string_view::npos) {
      error_here("invalid packoffset component " + in_quotes(cur().text) + "; use x, y, z or w");
      return std::nullopt;
    }
    offset += uint32_t(at) * 4;
    advance();
  }
  if (!is(")")) {
    error_unmatched(")", open);
    return std::nullopt;
  }
  advance();
  return offset;
}

// register(t0), register(s1, space2), register(b0). At the word `register`.
bool Parser::parse_register(RegisterBinding& binding) {
  binding.loc = cur().loc;
  advance();
  if (!is("(")) {
    error_here("expected '(' after 'register'");
    return false;
  }
  const size_t open = pos_;
  advance();
  // An optional shader profile first: register(ps_5_0, t0).
  if (cur().kind == TokenKind::Identifier && tok(pos_ + 1).is_punct(",") &&
      cur().text.find('_') != std::string_view::npos) {
    advance();
    advance();
  }
  const Token& name = cur();
  const std::optional<uint32_t> index = name.kind == TokenKind::Identifier
                                            ? register_number(name.text.substr(std::min<size_t>(1, name.text.size())))
                                            : std::nullopt;
  const char letter = name.text.empty() ? 0 : char(name.text[0] | 0x20);
  if (!index || (letter != 't' && letter != 's' && letter != 'b' && letter != 'u')) {
    error_here("invalid register " + in_quotes(name.text));
    return false;
  }
  binding.register_class = letter;
  binding.index = *index;
  advance();
  if (accept(",")) {
    const Token& space = cur();
    std::optional<uint32_t> number;
    if (space.kind == TokenKind::Identifier && space.text.size() > 5 && space.text.substr(0, 5) == "space")
      number = register_number(space.text.substr(5));
    if (!number) {
      error_here("invalid register space " + in_quotes(space.text));
      return false;
    }
    binding.space = *number;
    advance();
  }
  if (!is(")")) {
    error_unmatched(")", open);
    return false;
  }
  advance();
  return true;
}

// <string UIName = "Metallic"; float UIMin = 0.0;>. On a malformed entry the rest of the
// annotation block is skipped to its '>' and the declaration goes on without it.
void Parser::parse_annotations(std::vector<Annotation>* out) {
  const size_t open = pos_;
  advance();
  while (!is(">") && !is(">>")) {
    if (at_end() || !parse_annotation(out)) {
      // Token by token: no bracket belongs in an annotation, so one in a broken entry is not
      // taken to hide the block's '>'.
      if (skip_until({.stops = kSkipCloseAngle, .barriers = kSkipOpenBrace | kSkipCloseBrace, .flat = true}) ==
          SkipEnd::Stop)
        expect_closing_angle(open);
      return;
    }
  }
  expect_closing_angle(open);
}

bool Parser::parse_annotation(std::vector<Annotation>* out) {
  Annotation annotation;
  bool is_string = false;
  if (is_word("string")) {
    is_string = true;
    advance();
  } else {
    const std::optional<Type> type = parse_type(false);
    if (!type) return false;
    annotation.type = *type;
  }
  if (cur().kind != TokenKind::Identifier) {
    error_here("expected a name");
    return false;
  }
  annotation.name = std::string(cur().text);
  annotation.loc = cur().loc;
  advance();
  if (!accept("=")) {
    error_here("expected '=' in annotation");
    return false;
  }
  if (cur().kind == TokenKind::StringLiteral) {
    std::string_view text = cur().text;
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
    annotation.text = std::string(text);
    if (!is_string) {
      error_here("a string value needs the type 'string'");
      return false;
    }
    advance();
  } else {
    if (is_string) {
      error_here("expected a string");
      return false;
    }
    annotation.value = parse_annotation_literal();
    if (!annotation.value) return false;
  }
  if (!accept(";")) {
    error_after_previous("expected ';' after annotation");
    return false;
  }
  if (out) out->push_back(std::move(annotation));
  return true;
}

// A literal, possibly signed: 1, -0.5, true.
ExprPtr Parser::parse_annotation_literal() {
  if (is("-") || is("+")) {
    const Loc loc = cur().loc;
    const UnaryOp op = is("-") ? UnaryOp::Minus : UnaryOp::Plus;
    advance();
    if (cur().kind != TokenKind::IntLiteral && cur().kind != TokenKind::FloatLiteral) {
      error_here("expected a literal in annotation");
      return nullptr;
    }
    auto unary = make<UnaryExpr>(loc, op);
    unary->operand = parse_primary();
    if (!unary->operand) return nullptr;
    return unary;
  }
  if (cur().kind == TokenKind::IntLiteral || cur().kind == TokenKind::FloatLiteral || is_word("true") ||
      is_word("false"))
    return parse_primary();
  error_here("expected a literal in annotation");
  return nullptr;
}

// One variable declarator after its name: dimensions, annotations, semantics and registers,
// and an initializer.
std::unique_ptr<VarDecl> Parser::parse_var_declarator(const Specifiers& spec, const Type& base, size_t name_index,
                                                      DeclContext context) {
  auto var = make<VarDecl>(tok(name_index).loc);
  var->name = std::string(tok(name_index).text);
  var->storage = spec.storage;
  var->is_const = spec.is_const;
  var->packing = spec.packing;
  var->interpolation = spec.interpolation;
  var->is_global = context == DeclContext::Global || context == DeclContext::CBufferMember;
  bool unsized = false;
  const std::optional<Type> type = parse_array_dims(base, true, &unsized);
  if (!type) return nullptr;
  var->type = *type;
  hide_type_name(name_index);  // C's point of declaration: the initializer sees the variable
  if (is("<")) parse_annotations(&var->annotations);
  const bool allow_register = context == DeclContext::Global;
  if (!parse_colon_clauses(&var->semantic, &var->semantic_loc, allow_register ? &var->binding : nullptr,
                           context == DeclContext::CBufferMember ? var.get() : nullptr))
    return nullptr;
  if (is("<")) parse_annotations(&var->annotations);
  if (is("=")) {
    advance();
    var->initializer = is("{") ? parse_init_list() : parse_assignment();
    if (!var->initializer) return nullptr;
  }
  if (unsized) {
    if (var->type.element().is_resource()) {
      error_at(name_index, "'" + var->name +
                               "' is an unsized array of resources (descriptor indexing), which GLSL for "
                               "OpenGL cannot declare: give it the size the application binds");
      var->type = Type::array(var->type.element(), 1);
    } else if (!var->initializer || var->initializer->kind != ExprKind::InitList) {
      error_at(name_index, "an unsized array needs an initializer list");
      var->type = Type::array(var->type.element(), 1);
    } else if (static_cast<const InitListExpr&>(*var->initializer).elements.empty()) {
      error_at(name_index, "an unsized array needs a non-empty initializer list");
      var->type = Type::array(var->type.element(), 1);
    }
    // Otherwise the length stays 0: semantic analysis counts the list's components the way
    // HLSL flattens initializers, which needs the elements' types.
  }
  if (var->is_const && var->type.is_scalar() && var->type.is_integer() && var->initializer) {
    // A file-scope const without static is a uniform in $Globals, as in DXC: the host may
    // upload another value, so it is no compile-time constant (glslang's HLSL front end folds
    // it, DXC does not; xshade takes DXC's side and says how to write a constant).
    if (var->is_global && var->storage != StorageClass::Static) {
      int_constants_.erase(var->name);
      uniform_constants_.insert(var->name);
    } else if (const std::optional<int64_t> value = evaluate_int(*var->initializer)) {
      int_constants_[var->name] = *value;
      uniform_constants_.erase(var->name);
    }
  }
  return var;
}

// name declarator (, name declarator)* ; — the first name already consumed.
bool Parser::parse_declarators(const Specifiers& spec, const Type& base, size_t first_name, DeclContext context,
                               AstVector<std::unique_ptr<VarDecl>>& out) {
  size_t name_index = first_name;
  for (;;) {
    std::unique_ptr<VarDecl> var = parse_var_declarator(spec, base, name_index, context);
    if (!var) return false;
    out.push_back(std::move(var));
    if (!accept(",")) break;
    const std::optional<size_t> next = expect_name();
    if (!next) return false;
    name_index = *next;
  }
  return expect_semicolon("declaration");
}

// A variable's type must not be void; reported at the type.
Type Parser::checked_var_type(const Type& type, size_t type_index) {
  if (!type.is_void()) return type;
  error_at(type_index, "'void' is only valid as a function return type");
  return Type::error();
}

// -------------------------------------------------------------------------------------------
// File scope

bool Parser::parse_top_level() {
  if (accept(";")) return true;
  if (is("}")) {
    error_here("unexpected '}'");
    advance();
    return true;
  }
  std::vector<Attribute> attributes;
  VulkanAttributes vk;
  while (is("[")) {
    if (at_vulkan_attribute() ? !parse_vulkan_attributes(vk) : !parse_attributes(attributes)) return false;
  }
  const Token& token = cur();
  if (token.kind == TokenKind::Identifier) {
    if (token.text == "struct" || token.text == "typedef" || token.text == "cbuffer") {
      if (!attributes.empty()) error_at(attribute_index_, "attributes are only allowed on functions and statements");
      if (vk.any() && token.text != "cbuffer")
        diagnostics_.error(vk.loc, "a Vulkan attribute applies to a variable, parameter, field or cbuffer");
      if (token.text == "struct") return parse_struct();
      if (token.text == "typedef") return parse_typedef();
      return parse_cbuffer(vk);
    }
    if (info(pos_).unsupported) {
      error_here(in_quotes(token.text) + " is not supported");
      return false;
    }
    // An unknown word followed by a name is a declaration with a misspelt type; anything else
    // that is neither a qualifier nor a type cannot start a declaration.
    if (is_specifier_at(pos_) || is_type_start(pos_) || (!is_reserved(pos_) && is_name(pos_ + 1)))
      return parse_global(std::move(attributes), vk);
  }
  error_here("expected a declaration");
  return false;
}

// A global variable or a function.
bool Parser::parse_global(std::vector<Attribute> attributes, VulkanAttributes vk) {
  Specifiers spec;
  parse_specifiers(DeclContext::Global, spec);
  const size_t type_index = pos_;
  std::optional<Type> type = parse_type(true);
  if (!type) return false;
  const std::optional<size_t> name = expect_name();
  if (!name) return false;
  if (is("(")) {
    if (vk.any()) diagnostics_.error(vk.loc, "a Vulkan attribute applies to a variable, parameter, field or cbuffer");
    return parse_function(std::move(attributes), *type, *name);
  }
  if (!attributes.empty()) error_at(attribute_index_, "attributes are only allowed on functions and statements");
  // DXC reads a push-constant struct variable as a block of its fields: ConstantBuffer<S>.
  if (vk.push_constant && type->kind() == TypeKind::Struct) type = Type::constant_buffer(*type);
  AstVector<std::unique_ptr<VarDecl>> vars;
  const bool ok = parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::Global, vars);
  for (auto& var : vars) {
    var->vk = vk;
    // A specialization constant: a constant to everything but the SPIR-V, whose host may give
    // another value (its default is not folded into array sizes).
    if (vk.constant_id && (!var->is_const || !var->type.is_scalar() || !var->initializer))
      diagnostics_.error(vk.loc, "vk::constant_id applies to a `const` scalar with an initializer");
    else if (vk.constant_id)
      var->storage = StorageClass::Static;
    unit_.decls.push_back(std::move(var));
  }
  return ok;
}

bool Parser::parse_function(std::vector<Attribute> attributes, const Type& return_type, size_t name_index) {
  auto function = make<FunctionDecl>(tok(name_index).loc);
  function->name = std::string(tok(name_index).text);
  function->return_type = return_type;
  function->attributes = std::move(attributes);
  NameScope parameters(*this);  // the parameters' names, through the body
  const size_t open = pos_;
  advance();
  if (is_word("void") && tok(pos_ + 1).is_punct(")")) advance();  // f(void)
  if (!is(")")) {
    for (;;) {
      std::unique_ptr<ParamDecl> param = parse_param();
      if (!param) return false;
      function->params.push_back(std::move(param));
      if (accept(",")) continue;
      if (is(")")) break;
      error_unmatched(")", open);
      return false;
    }
  }
  advance();
  if (!parse_colon_clauses(&function->semantic, &function->semantic_loc, nullptr)) return false;
  if (accept(";")) {
    unit_.decls.push_back(std::move(function));
    return true;
  }
  if (!is("{")) {
    error_here("expected a function body or ';'");
    return false;
  }
  function->body = parse_block();
  unit_.decls.push_back(std::move(function));
  return true;
}

std::unique_ptr<ParamDecl> Parser::parse_param() {
  VulkanAttributes vk;
  if (at_vulkan_attribute() && !parse_vulkan_attributes(vk)) return nullptr;
  Specifiers spec;
  parse_specifiers(DeclContext::Param, spec);
  const size_t type_index = pos_;
  const std::optional<Type> type = parse_type(false);
  if (!type) return nullptr;
  Loc loc = tok(type_index).loc;
  std::string name;
  if (is_declared_name(pos_)) {
    loc = cur().loc;
    name = std::string(cur().text);
    hide_type_name(pos_);
    advance();
  } else if (!is(",") && !is(")")) {
    error_here("expected a name");
    return nullptr;
  }
  auto param = make<ParamDecl>(loc);
  param->vk = vk;
  param->name = std::move(name);
  param->direction = spec.direction;
  param->explicit_in = spec.explicit_in;
  param->is_uniform = spec.is_uniform;
  param->interpolation = spec.interpolation;
  const std::optional<Type> full = parse_array_dims(*type, false, nullptr);
  if (!full) return nullptr;
  param->type = *full;
  if (!parse_colon_clauses(&param->semantic, &param->semantic_loc, nullptr)) return nullptr;
  if (accept("=")) {
    param->default_value = parse_assignment();
    if (!param->default_value) return nullptr;
  }
  return param;
}

bool Parser::parse_struct() {
  advance();
  const std::optional<size_t> name = expect_type_name();
  if (!name) return false;
  auto decl = make<StructDecl>(tok(*name).loc);
  decl->name = std::string(tok(*name).text);
  if (!is("{")) {
    error_here("expected '{' after struct name");
    return false;
  }
  // Declared from here on, and the declaration is kept on every path below: the type table
  // points at it.
  declare_type(*name, Type::structure(decl.get()));
  const size_t open = pos_;
  advance();
  while (!is("}") && !at_end()) {
    const size_t before = pos_;
    if (!parse_field(*decl)) recover_statement();  // inside a struct body: as after a statement
    if (pos_ == before && !is("}") && !at_end()) advance();
  }
  const bool closed = accept("}");
  if (!closed) error_unmatched("}", open);
  unit_.decls.push_back(std::move(decl));
  if (closed) expect_semicolon("struct declaration");
  return true;
}

bool Parser::parse_field(StructDecl& decl) {
  VulkanAttributes vk;
  if (at_vulkan_attribute() && !parse_vulkan_attributes(vk)) return false;
  Specifiers spec;
  parse_specifiers(DeclContext::Field, spec);
  const size_t type_index = pos_;
  const std::optional<Type> type = parse_type(false);
  if (!type) return false;
  for (;;) {
    const std::optional<size_t> name = expect_name();
    if (!name) return false;
    if (is("(")) {
      error_here("struct methods are not supported");
      return false;
    }
    FieldDecl field;
    field.vk = vk;
    field.name = std::string(tok(*name).text);
    field.loc = tok(*name).loc;
    field.interpolation = spec.interpolation;
    const std::optional<Type> full = parse_array_dims(*type, false, nullptr);
    if (!full) return false;
    field.type = checked_var_type(*full, type_index);
    if (is("<")) parse_annotations(nullptr);
    if (!parse_colon_clauses(&field.semantic, &field.semantic_loc, nullptr)) return false;
    if (is("=")) {
      error_here("struct fields cannot have initializers");
      return false;
    }
    decl.fields.push_back(std::move(field));
    if (!accept(",")) break;
  }
  return expect_semicolon("declaration");
}

bool Parser::parse_typedef() {
  advance();
  Specifiers spec;
  parse_specifiers(DeclContext::Typedef, spec);
  const size_t type_index = pos_;
  const std::optional<Type> type = parse_type(false);
  if (!type) return false;
  const std::optional<size_t> name = expect_type_name();
  if (!name) return false;
  const std::optional<Type> full = parse_array_dims(*type, false, nullptr);
  if (!full) return false;
  auto decl = make<TypedefDecl>(tok(*name).loc);
  decl->name = std::string(tok(*name).text);
  decl->type = checked_var_type(*full, type_index);
  declare_type(*name, decl->type);
  unit_.decls.push_back(std::move(decl));
  return expect_semicolon("typedef");
}

bool Parser::parse_cbuffer(VulkanAttributes vk) {
  advance();
  const std::optional<size_t> name = expect_name();
  if (!name) return false;
  auto decl = make<CBufferDecl>(tok(*name).loc);
  decl->name = std::string(tok(*name).text);
  decl->vk = vk;
  while (is(":")) {
    advance();
    if (is_word("register")) {
      if (!parse_register(decl->binding)) return false;
    } else if (is_word("packoffset")) {
      error_here("packoffset is not supported");
      return false;
    } else {
      error_here("expected 'register' after ':'");
      return false;
    }
  }
  if (!is("{")) {
    error_here("expected '{' after cbuffer name");
    return false;
  }
  const size_t open = pos_;
  advance();
  while (!is("}") && !at_end()) {
    const size_t before = pos_;
    if (!parse_cbuffer_member(*decl)) recover_statement();  // as in a struct body
    if (pos_ == before && !is("}") && !at_end()) advance();
  }
  if (!accept("}")) error_unmatched("}", open);
  accept(";");
  unit_.decls.push_back(std::move(decl));
  return true;
}

bool Parser::parse_cbuffer_member(CBufferDecl& decl) {
  VulkanAttributes vk;
  if (at_vulkan_attribute() && !parse_vulkan_attributes(vk)) return false;
  Specifiers spec;
  parse_specifiers(DeclContext::CBufferMember, spec);
  const size_t type_index = pos_;
  const std::optional<Type> type = parse_type(false);
  if (!type) return false;
  const std::optional<size_t> name = expect_name();
  if (!name) return false;
  const size_t first = decl.members.size();
  const bool ok =
      parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::CBufferMember, decl.members);
  for (size_t i = first; i < decl.members.size(); ++i) decl.members[i]->vk = vk;
  return ok;
}

// [unroll], [loop], [unroll(4)], [numthreads(8, 8, 1)]: any number in a row.
bool Parser::parse_attributes(std::vector<Attribute>& out) {
  attribute_index_ = pos_;
  while (is("[")) {
    const size_t open = pos_;
    advance();
    if (cur().kind != TokenKind::Identifier) {
      error_here("expected an attribute name");
      return false;
    }
    Attribute attribute;
    attribute.name = std::string(cur().text);
    attribute.loc = cur().loc;
    advance();
    if (is("(")) {
      const size_t paren = pos_;
      advance();
      DepthGuard guard(*this);
      if (!guard.ok()) return false;
      bool has_string = false;
      if (!is(")")) {
        for (;;) {
          // [RootSignature("..."), [domain("tri")]: strings only an API or another stage reads.
          if (cur().kind == TokenKind::StringLiteral) {
            has_string = true;
            while (cur().kind == TokenKind::StringLiteral) advance();  // "a" "b": one string, as in C
          } else {
            ExprPtr arg = parse_assignment();
            if (!arg) return false;
            attribute.args.push_back(std::move(arg));
          }
          if (accept(",")) continue;
          if (is(")")) break;
          error_unmatched(")", paren);
          return false;
        }
      }
      advance();
      if (has_string) diagnostics_.note(attribute.loc, "attribute " + in_quotes(attribute.name) + " is ignored");
    }
    if (!is("]")) {
      error_unmatched("]", open);
      return false;
    }
    advance();
    out.push_back(std::move(attribute));
  }
  return true;
}

}  // namespace xshade::hlsl::parser_detail
