// A hand-written recursive-descent parser for the HLSL subset of hlsl_like.
//
// Shape of the code:
// - Declarations and statements are told apart C-style: the parser keeps a table of the struct
//   and typedef names declared so far, beside the built-in type names.
// - A failed parse function returns null without skipping; the nearest recovery point skips:
//   a statement in a block, a declaration at file scope, a struct field or cbuffer member, the
//   parenthesised header of if/while/for, and the outermost initializer list.
// - Every recursion that input can nest goes through a DepthGuard, so hostile nesting is an
//   error at kMaxParseDepth, never a stack overflow; all skipping is iterative.
#include "hlsl_like/parser.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace xshade::hlsl {
namespace {

constexpr size_t kNoIndex = static_cast<size_t>(-1);
// Array lengths above this are an error: nothing in a shader needs more, and later layers
// multiply lengths by element sizes.
constexpr int64_t kMaxArrayLength = 65536;
constexpr size_t kMaxTemplateLookahead = 64;

struct StringHash {
  using is_transparent = void;
  size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
};

// What a built-in type word needs beyond its Type.
// Texture: an optional <texel type> (Texture2DMS: <texel type, samples>); Buffer: <element>
// (none for the byte-address buffers); ConstantBuffer: <struct>.
enum class TypeWord : uint8_t { Plain, Void, Double, Vector, Matrix, Texture, Buffer, ConstantBuffer, Unsupported };

struct BuiltinType {
  Type type;
  TypeWord word = TypeWord::Plain;
};

using BuiltinTable = std::unordered_map<std::string, BuiltinType, StringHash, std::equal_to<>>;

BuiltinTable make_builtin_types() {
  BuiltinTable table;
  struct ScalarWord {
    const char* name;
    ScalarType scalar;
    bool shapes;  // has vector and matrix forms
    TypeWord word;
  };
  static constexpr ScalarWord kScalars[] = {
      {"bool", ScalarType::Bool, true, TypeWord::Plain},
      {"int", ScalarType::Int, true, TypeWord::Plain},
      {"uint", ScalarType::Uint, true, TypeWord::Plain},
      {"dword", ScalarType::Uint, false, TypeWord::Plain},
      {"half", ScalarType::Half, true, TypeWord::Plain},
      {"float", ScalarType::Float, true, TypeWord::Plain},
      {"min16float", ScalarType::Half, true, TypeWord::Plain},
      {"min10float", ScalarType::Half, true, TypeWord::Plain},
      {"min16int", ScalarType::Int, true, TypeWord::Plain},
      {"min12int", ScalarType::Int, true, TypeWord::Plain},
      {"min16uint", ScalarType::Uint, true, TypeWord::Plain},
      // Reported, then read as float so that the rest of the declaration still parses.
      {"double", ScalarType::Float, true, TypeWord::Double},
  };
  for (const ScalarWord& s : kScalars) {
    const std::string base = s.name;
    table[base] = {Type::scalar(s.scalar), s.word};
    if (!s.shapes) continue;
    for (uint32_t cols = 1; cols <= 4; ++cols) {
      table[base + std::to_string(cols)] = {Type::vector(s.scalar, cols), s.word};
      for (uint32_t rows = 1; rows <= 4; ++rows)
        table[base + std::to_string(rows) + "x" + std::to_string(cols)] = {Type::matrix(s.scalar, rows, cols), s.word};
    }
  }
  table["void"] = {Type::void_type(), TypeWord::Void};
  table["vector"] = {Type::vector(ScalarType::Float, 4), TypeWord::Vector};
  table["matrix"] = {Type::matrix(ScalarType::Float, 4, 4), TypeWord::Matrix};
  for (TextureShape shape : {TextureShape::Tex1D, TextureShape::Tex1DArray, TextureShape::Tex2D, TextureShape::Tex2DArray,
                             TextureShape::Tex2DMS, TextureShape::Tex2DMSArray, TextureShape::Tex3D, TextureShape::Cube,
                             TextureShape::CubeArray})
    table[texture_shape_name(shape)] = {Type::texture(shape, Type::vector(ScalarType::Float, 4)), TypeWord::Texture};
  table["SamplerState"] = {Type::sampler_state(), TypeWord::Plain};
  table["SamplerComparisonState"] = {Type::sampler_state(true), TypeWord::Plain};
  for (TextureShape shape : {TextureShape::Tex1D, TextureShape::Tex2D, TextureShape::Tex3D, TextureShape::Cube})
    table[texture_shape_name(shape, true)] = {Type::sampler(shape), TypeWord::Plain};
  table["sampler"] = {Type::sampler2d(), TypeWord::Plain};  // DX9: read as sampler2D
  for (BufferKind kind : {BufferKind::Buffer, BufferKind::RWBuffer, BufferKind::StructuredBuffer,
                          BufferKind::RWStructuredBuffer, BufferKind::ByteAddressBuffer, BufferKind::RWByteAddressBuffer,
                          BufferKind::AppendStructuredBuffer, BufferKind::ConsumeStructuredBuffer, BufferKind::RWTexture1D,
                          BufferKind::RWTexture1DArray, BufferKind::RWTexture2D, BufferKind::RWTexture2DArray,
                          BufferKind::RWTexture3D})
    table[buffer_kind_name(kind)] = {Type::buffer(kind, Type::vector(ScalarType::Float, 4)), TypeWord::Buffer};
  table["ConstantBuffer"] = {Type::error(), TypeWord::ConstantBuffer};
  for (const char* name : {"texture", "string"}) table[name] = {Type::error(), TypeWord::Unsupported};
  return table;
}

const BuiltinTable& builtin_types() {
  static const BuiltinTable table = make_builtin_types();
  return table;
}

// Everything the parser needs to know about a word, from one lookup.
struct WordInfo {
  const BuiltinType* builtin = nullptr;      // a built-in type name
  // A type only with template arguments: `ConstantBuffer<S>`; alone it is a name, as the D3D11
  // samples' `cbuffer ConstantBuffer : register(b0)` has it.
  bool template_only = false;
  bool reserved = false;                     // never a variable, function or field name
  bool hard_specifier = false;               // always a qualifier
  bool unsupported = false;                  // a reserved word of HLSL (or C) not supported
  std::optional<Interpolation> interpolation;  // a qualifier only in front of a type
};

using WordTable = std::unordered_map<std::string_view, WordInfo>;

WordTable make_word_table() {
  WordTable table;
  for (const auto& [name, builtin] : builtin_types()) table[name].builtin = &builtin;
  table["ConstantBuffer"].template_only = true;
  for (std::string_view word :
       {"struct", "typedef", "cbuffer", "tbuffer", "if", "else", "for", "while", "do", "break", "continue",
        "return", "discard", "switch", "case", "default", "goto", "true", "false", "register", "packoffset",
        "class", "interface", "namespace", "template", "typename", "enum", "technique", "technique10",
        "technique11", "sizeof", "this"})
    table[word].reserved = true;
  for (std::string_view word : {"class", "interface", "namespace", "template", "typename", "tbuffer", "enum",
                                "technique", "technique10", "technique11", "sizeof", "this"})
    table[word].unsupported = true;
  for (std::string_view word : {"static", "const", "uniform", "extern", "groupshared", "volatile", "precise",
                                "inline", "row_major", "column_major", "in", "out", "inout", "shared", "snorm",
                                "unorm"}) {
    table[word].reserved = true;
    table[word].hard_specifier = true;
  }
  // Interpolation modifiers stay usable as names: `float linear;`, `sample = tex.Sample(...)`.
  table["linear"].interpolation = Interpolation::Linear;
  table["centroid"].interpolation = Interpolation::Centroid;
  table["nointerpolation"].interpolation = Interpolation::NoInterpolation;
  table["noperspective"].interpolation = Interpolation::NoPerspective;
  table["sample"].interpolation = Interpolation::Sample;
  return table;
}

const WordInfo& lookup_word(std::string_view text) {
  static const WordTable table = make_word_table();
  static const WordInfo kPlain;
  const auto it = table.find(text);
  return it == table.end() ? kPlain : it->second;
}

// Where qualifiers are read: each place accepts a different set.
enum class DeclContext : uint8_t { Global, CBufferMember, Local, Param, Field, Typedef };

struct Specifiers {
  StorageClass storage = StorageClass::Default;
  bool is_const = false;
  MatrixPacking packing = MatrixPacking::Default;
  Interpolation interpolation = Interpolation::Default;
  ParamDirection direction = ParamDirection::In;
  bool explicit_in = false;
  bool is_uniform = false;
  bool any = false;
};

// Parses an integer literal's spelling: decimal, 0x hex or 0 octal, with u/l suffixes.
struct IntValue {
  uint64_t value = 0;
  bool is_unsigned = false;
  bool valid = true;
  bool too_large = false;
};

IntValue parse_int_spelling(std::string_view text) {
  IntValue result;
  while (!text.empty()) {
    const char c = text.back();
    if (c == 'u' || c == 'U') {
      result.is_unsigned = true;
    } else if (c != 'l' && c != 'L') {
      break;
    }
    text.remove_suffix(1);
  }
  uint64_t base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    base = 16;
    text.remove_prefix(2);
  } else if (text.size() > 1 && text[0] == '0') {
    base = 8;
    text.remove_prefix(1);
  }
  if (text.empty()) result.valid = false;
  for (char c : text) {
    uint64_t digit = 0;
    if (c >= '0' && c <= '9') {
      digit = uint64_t(c - '0');
    } else if (c >= 'a' && c <= 'f') {
      digit = uint64_t(c - 'a' + 10);
    } else if (c >= 'A' && c <= 'F') {
      digit = uint64_t(c - 'A' + 10);
    } else {
      result.valid = false;
      break;
    }
    if (digit >= base) {
      result.valid = false;
      break;
    }
    if (!result.too_large) {
      result.value = result.value * base + digit;
      if (result.value > 0xFFFFFFFFull) result.too_large = true;
    }
  }
  if (!result.valid || result.too_large) result.value = 0;
  return result;
}

template <class T, class... Args>
std::unique_ptr<T> make(Args&&... args) {
  return std::make_unique<T>(std::forward<Args>(args)...);
}

class Parser {
 public:
  Parser(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics)
      : tokens_(tokens), diagnostics_(diagnostics) {
    eof_.kind = TokenKind::EndOfFile;
    if (!tokens.empty()) eof_.loc = tokens.back().loc;
  }

  TranslationUnit run() {
    while (!at_end()) {
      const size_t before = pos_;
      if (!parse_top_level()) recover_top_level();
      if (pos_ == before && !at_end()) advance();  // never loop in place
    }
    return std::move(unit_);
  }

 private:
  // Counts one level of nesting for as long as it lives.
  class DepthGuard {
   public:
    explicit DepthGuard(Parser& parser) : parser_(parser) {
      ok_ = ++parser_.depth_ <= kMaxParseDepth;
      if (!ok_) parser_.report_too_deep();
    }
    ~DepthGuard() { --parser_.depth_; }
    DepthGuard(const DepthGuard&) = delete;
    DepthGuard& operator=(const DepthGuard&) = delete;
    bool ok() const { return ok_; }

   private:
    Parser& parser_;
    bool ok_ = true;
  };

  // A loop that makes the tree one level deeper per round (a + b + c, a.b.c, a, b, c): each
  // round counts as nesting, so that no tree is deeper than the limit and later passes, and the
  // tree's own destructors, can recurse over it safely.
  class ChainDepth {
   public:
    explicit ChainDepth(Parser& parser) : parser_(parser) {}
    ~ChainDepth() { parser_.depth_ -= added_; }
    ChainDepth(const ChainDepth&) = delete;
    ChainDepth& operator=(const ChainDepth&) = delete;
    bool push() {
      ++added_;
      if (++parser_.depth_ <= kMaxParseDepth) return true;
      parser_.report_too_deep();
      return false;
    }

   private:
    Parser& parser_;
    int added_ = 0;
  };

  void report_too_deep() {
    unwinding_too_deep_ = true;
    if (too_deep_reported_) return;
    too_deep_reported_ = true;
    error_here("nesting is too deep (more than " + std::to_string(kMaxParseDepth) + " levels)");
  }

  // -------------------------------------------------------------------------------------------
  // Tokens

  const Token& tok(size_t index) const { return index < tokens_.size() ? tokens_[index] : eof_; }
  const Token& cur() const { return tok(pos_); }
  bool at_end() const { return cur().kind == TokenKind::EndOfFile; }
  // `punct` is never empty; the first-character test keeps memcmp out of the common miss.
  bool is(std::string_view punct) const {
    const Token& token = cur();
    return token.kind == TokenKind::Punct && token.text.size() == punct.size() && token.text[0] == punct[0] &&
           (punct.size() == 1 || token.text == punct);
  }
  bool is_word(std::string_view word) const { return cur().is_identifier(word); }

  void advance() {
    const Token& token = cur();
    if (token.kind == TokenKind::EndOfFile) return;
    if (token.kind == TokenKind::Unknown) error_at(pos_, {});  // reports the character once
    ++pos_;
    split_angle_ = false;
  }

  bool accept(std::string_view punct) {
    if (!is(punct)) return false;
    advance();
    return true;
  }

  // -------------------------------------------------------------------------------------------
  // Diagnostics

  // At most one error per token position, and an Unknown token is always reported as the
  // character it is, once, whatever the parser expected there.
  bool error_at(size_t index, std::string message) {
    const Token& token = tok(index);
    if (token.kind == TokenKind::Unknown) {
      if (index < unknown_reported_until_) return false;
      unknown_reported_until_ = index + 1;
      message = "unknown character " + in_quotes(token.text);
    } else if (message.empty()) {
      return false;
    }
    if (index == last_error_index_) return false;
    last_error_index_ = index;
    diagnostics_.error(token.loc, std::move(message));
    return true;
  }
  bool error_here(std::string message) { return error_at(pos_, std::move(message)); }

  // A malformed literal (a bad number, an unterminated string) was reported by the lexer at the
  // token's start; the parser reports one only for a token stream that did not come from there.
  void literal_error(std::string message) {
    const Loc loc = cur().loc;
    for (const Diagnostic& d : diagnostics_.diagnostics())
      if (d.severity == Severity::Error && d.where.line == loc.line && d.where.column == loc.column) return;
    error_here(std::move(message));
  }

  // "expected ')' to match '('" at the current token, with a note at the opening bracket.
  void error_unmatched(std::string_view close, size_t open_index) {
    const std::string open(tok(open_index).text);
    if (error_here("expected '" + std::string(close) + "' to match '" + open + "'"))
      diagnostics_.note(tok(open_index).loc, "to match this '" + open + "'");
  }

  // A missing ';' is reported; when the next token starts a new line the statement is kept as
  // if the ';' were there, which is what the author most likely meant.
  bool expect_semicolon(std::string_view after) {
    if (accept(";")) return true;
    error_after_previous("expected ';' after " + std::string(after));
    return cur().at_line_start && cur().kind != TokenKind::Unknown && !is("}") && !at_end();
  }

  // Something missing between the previous token and this one is reported just past the end of
  // the previous token, where clang and DXC point: the next token may be lines further on.
  bool error_after_previous(std::string message) {
    if (pos_ == 0 || cur().kind == TokenKind::Unknown || pos_ == last_error_index_) return error_here(std::move(message));
    const std::optional<Loc> end = end_of(tok(pos_ - 1));
    if (!end) return error_here(std::move(message));
    last_error_index_ = pos_;
    diagnostics_.error(*end, std::move(message));
    return true;
  }

  // Where `token` ends in its file; nothing when its text is not the source at its location (a
  // token from a macro expansion is located at the macro's name, a spliced one was rebuilt).
  std::optional<Loc> end_of(const Token& token) const {
    if (token.loc.file == 0 || token.loc.column == 0) return std::nullopt;
    const std::string_view line = diagnostics_.sources().line_text(token.loc.file, token.loc.line);
    const size_t start = token.loc.column - 1;
    if (start > line.size() || line.data() + start != token.text.data()) return std::nullopt;
    if (token.text.size() > line.size() - start) return std::nullopt;
    return Loc{token.loc.file, token.loc.line, static_cast<uint32_t>(token.loc.column + token.text.size())};
  }

  // -------------------------------------------------------------------------------------------
  // Recovery (all iterative)

  static bool is_opener(const Token& token) {
    return token.kind == TokenKind::Punct && (token.text == "(" || token.text == "[" || token.text == "{");
  }
  static bool is_closer(const Token& token) {
    return token.kind == TokenKind::Punct && (token.text == ")" || token.text == "]" || token.text == "}");
  }

  // Inside a block: to just after the next ';' or to the '}' that closes the block, skipping
  // bracketed groups whole; stray ')' and ']' belong to the failed statement and are skipped.
  void recover_statement() {
    if (unwinding_too_deep_) {
      // Nesting too deep to read says nothing about where the failed statement ends (an
      // else-if chain goes on past any ';'): the rest of the block goes.
      skip_to_block_end();
      return;
    }
    size_t balance = 0;
    while (!at_end()) {
      const Token& token = cur();
      if (balance == 0 && token.is_punct(";")) {
        advance();
        return;
      }
      if (balance == 0 && token.is_punct("}")) return;
      if (is_opener(token)) {
        ++balance;
      } else if (is_closer(token) && balance > 0) {
        --balance;
      }
      advance();
    }
  }

  // To the '}' that closes the current block, not consuming it.
  void skip_to_block_end() {
    unwinding_too_deep_ = false;
    size_t balance = 0;
    while (!at_end()) {
      const Token& token = cur();
      if (balance == 0 && token.is_punct("}")) return;
      if (is_opener(token)) {
        ++balance;
      } else if (is_closer(token) && balance > 0) {
        --balance;
      }
      advance();
    }
  }

  // At file scope: to just after the next ';', or after the end of a {...} block (and a ';'
  // right after it).
  void recover_top_level() {
    unwinding_too_deep_ = false;
    size_t balance = 0;
    while (!at_end()) {
      const Token& token = cur();
      if (balance == 0 && token.is_punct(";")) {
        advance();
        return;
      }
      if (is_opener(token)) {
        ++balance;
      } else if (is_closer(token) && balance > 0) {
        --balance;
        if (balance == 0 && token.is_punct("}")) {
          advance();
          accept(";");
          return;
        }
      }
      advance();
    }
  }

  // From the opening bracket at `open`, moves to just past the bracket that closes it (true).
  // Stops early (false) at the end of the input, at a ';' unless `semicolons_inside`, and, for
  // a parenthesised group, at a brace: those cannot be inside, so the closer is missing.
  bool skip_group(size_t open, bool semicolons_inside) {
    unwinding_too_deep_ = false;
    pos_ = open;
    const bool parens = tok(open).is_punct("(") || tok(open).is_punct("[");
    advance();
    size_t balance = 0;
    while (!at_end()) {
      const Token& token = cur();
      if (token.is_punct(";") && !semicolons_inside) return false;
      if (parens && (token.is_punct("{") || token.is_punct("}"))) return false;
      if (is_opener(token)) {
        ++balance;
      } else if (is_closer(token)) {
        if (balance == 0) {
          advance();
          return true;
        }
        --balance;
      }
      advance();
    }
    return false;
  }

  // -------------------------------------------------------------------------------------------
  // Types

  // A word's classification and, once declared, its struct or typedef type: one hash lookup
  // per question, however many questions the look-ahead asks about the same word.
  struct Word {
    const WordInfo* info;
    std::optional<Type> user_type;
  };

  Word& word(std::string_view text) const {
    auto it = words_.find(text);
    if (it == words_.end()) it = words_.emplace(text, Word{&lookup_word(text), std::nullopt}).first;
    return it->second;
  }
  // The classification of the token at `index`; a plain word for anything but an identifier.
  const WordInfo& info(size_t index) const {
    const Token& token = tok(index);
    static const WordInfo kNone;
    return token.kind == TokenKind::Identifier ? *word(token.text).info : kNone;
  }
  const BuiltinType* find_builtin_type(size_t index) const { return info(index).builtin; }
  bool is_reserved(size_t index) const { return info(index).reserved; }

  bool is_type_start(size_t index) const {
    const Token& token = tok(index);
    if (token.kind != TokenKind::Identifier) return false;
    const Word& w = word(token.text);
    if (w.info->template_only && !tok(index + 1).is_punct("<")) return false;
    return w.info->builtin != nullptr || w.user_type.has_value();
  }

  // The index just past the type spelled at `index` (which is_type_start): the word and, for
  // the template-like words, a bounded <...>. Only a look ahead; parse_type reports errors.
  size_t type_end(size_t index) const {
    const size_t next = index + 1;
    if (!tok(next).is_punct("<")) return next;
    const BuiltinType* builtin = find_builtin_type(index);
    if (!builtin || builtin->word == TypeWord::Plain || builtin->word == TypeWord::Void ||
        builtin->word == TypeWord::Double)
      return next;
    int depth = 0;
    for (size_t i = next; i < next + kMaxTemplateLookahead; ++i) {
      const Token& token = tok(i);
      if (token.kind == TokenKind::EndOfFile) return next;
      if (token.kind != TokenKind::Punct) continue;
      if (token.text == "<") {
        ++depth;
      } else if (token.text == ">") {
        if (--depth <= 0) return i + 1;
      } else if (token.text == ">>") {
        depth -= 2;
        if (depth <= 0) return i + 1;
      } else if (token.text == ";" || token.text == "{" || token.text == "}" || token.text == "(" ||
                 token.text == ")" || token.text == "=") {
        return next;
      }
    }
    return next;
  }

  // A template's closing '>'; the first half of a '>>' counts, for Texture2D<vector<float, 4>>.
  bool expect_closing_angle(size_t open_index) {
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
  std::optional<uint64_t> parse_template_number() {
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
  std::optional<ScalarType> parse_template_scalar() {
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
  std::optional<Type> parse_shape_template(bool matrix) {
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
  std::optional<Type> parse_type(bool allow_void) {
    const Token& token = cur();
    if (token.kind != TokenKind::Identifier || is_reserved(pos_)) {
      error_here("expected a type");
      return std::nullopt;
    }
    const Word& w = word(token.text);
    if (w.user_type) {
      advance();
      return *w.user_type;
    }
    const BuiltinType* builtin = w.info->builtin;
    if (!builtin) {
      error_here(in_quotes(token.text) + " is not a type");
      advance();
      return Type::error();
    }
    const size_t word_index = pos_;
    switch (builtin->word) {
      case TypeWord::Plain:
        advance();
        return builtin->type;
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
        if (is_multisampled(builtin->type.texture_shape()) && accept(",") && !parse_template_number()) return std::nullopt;
        if (!expect_closing_angle(open)) return std::nullopt;
        if (texel->is_error()) return Type::error();
        if (!texel->is_scalar() && !texel->is_vector()) {
          error_at(texel_index, "the texel type of " + in_quotes(tok(word_index).text) + " must be a scalar or vector, not " +
                                    in_quotes(texel->name()));
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
            error_here("expected '<' after " + in_quotes(tok(word_index).text) + ": a structured buffer needs an element type");
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
  bool skip_angles() {
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

  bool is_specifier_at(size_t index) const {
    const WordInfo& here = info(index);
    if (here.hard_specifier) return true;
    if (!here.interpolation) return false;
    const WordInfo& next = info(index + 1);
    return next.hard_specifier || next.interpolation || is_type_start(index + 1);
  }

  void parse_specifiers(DeclContext context, Specifiers& spec) {
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
  // Names

  bool is_name(size_t index) const {
    const Token& token = tok(index);
    if (token.kind != TokenKind::Identifier) return false;
    const Word& w = word(token.text);
    if (w.info->template_only && !tok(index + 1).is_punct("<")) return !w.user_type;
    return !w.info->reserved && !w.info->builtin && !w.user_type;
  }

  // Consumes a declared name; reports "expected a name" when there is none.
  std::optional<size_t> expect_name() {
    if (!is_name(pos_)) {
      error_here("expected a name");
      return std::nullopt;
    }
    const size_t index = pos_;
    advance();
    return index;
  }

  // The name of a new struct or typedef: a type name already declared is let through, for
  // declare_type to report as a redefinition.
  std::optional<size_t> expect_type_name() {
    const Token& token = cur();
    if (token.kind != TokenKind::Identifier || is_reserved(pos_) || find_builtin_type(pos_)) {
      error_here("expected a name");
      return std::nullopt;
    }
    const size_t index = pos_;
    advance();
    return index;
  }

  // A struct or typedef name joins the type table (the first definition wins).
  void declare_type(size_t name_index, const Type& type) {
    const std::string_view name = tok(name_index).text;
    Word& w = word(name);
    if (w.user_type) {
      error_at(name_index, "redefinition of type " + in_quotes(name));
      return;
    }
    w.user_type = type;
  }

  // -------------------------------------------------------------------------------------------
  // Declarator pieces

  // [N][M]... after a name. An unsized first dimension gives length 0 and sets *unsized.
  std::optional<Type> parse_array_dims(const Type& base, bool allow_unsized, bool* unsized) {
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

  // The first name in `expr` that is a uniform const, which its author may have meant as a constant.
  const NameExpr* find_uniform_constant(const Expr& expr) const {
    switch (expr.kind) {
      case ExprKind::Name: {
        const auto& name = static_cast<const NameExpr&>(expr);
        return uniform_constants_.count(name.name) ? &name : nullptr;
      }
      case ExprKind::Unary: return find_uniform_constant(*static_cast<const UnaryExpr&>(expr).operand);
      case ExprKind::Binary: {
        const auto& binary = static_cast<const BinaryExpr&>(expr);
        if (const NameExpr* found = find_uniform_constant(*binary.lhs)) return found;
        return find_uniform_constant(*binary.rhs);
      }
      default: return nullptr;
    }
  }

  // Integer constant expressions for array sizes: literals, arithmetic, and names of constant
  // integers declared with a constant initializer.
  std::optional<int64_t> evaluate_int(const Expr& expr) const {
    switch (expr.kind) {
      case ExprKind::IntLiteral: return int64_t(static_cast<const IntLiteralExpr&>(expr).value);
      case ExprKind::BoolLiteral: return static_cast<const BoolLiteralExpr&>(expr).value ? 1 : 0;
      case ExprKind::Name: {
        const auto it = int_constants_.find(static_cast<const NameExpr&>(expr).name);
        if (it == int_constants_.end()) return std::nullopt;
        return it->second;
      }
      case ExprKind::Unary: {
        const auto& unary = static_cast<const UnaryExpr&>(expr);
        const std::optional<int64_t> value = evaluate_int(*unary.operand);
        if (!value) return std::nullopt;
        switch (unary.op) {
          case UnaryOp::Plus: return *value;
          case UnaryOp::Minus: return -*value;
          case UnaryOp::BitNot: return ~*value;
          case UnaryOp::Not: return *value == 0 ? 1 : 0;
          default: return std::nullopt;
        }
      }
      case ExprKind::Binary: {
        const auto& binary = static_cast<const BinaryExpr&>(expr);
        const std::optional<int64_t> a = evaluate_int(*binary.lhs);
        const std::optional<int64_t> b = evaluate_int(*binary.rhs);
        if (!a || !b) return std::nullopt;
        int64_t result = 0;
        switch (binary.op) {
          case BinaryOp::Add:
            if (__builtin_add_overflow(*a, *b, &result)) return std::nullopt;
            return result;
          case BinaryOp::Sub:
            if (__builtin_sub_overflow(*a, *b, &result)) return std::nullopt;
            return result;
          case BinaryOp::Mul:
            if (__builtin_mul_overflow(*a, *b, &result)) return std::nullopt;
            return result;
          case BinaryOp::Div:
            if (*b == 0 || (*b == -1 && *a == INT64_MIN)) return std::nullopt;
            return *a / *b;
          case BinaryOp::Mod:
            if (*b == 0 || (*b == -1 && *a == INT64_MIN)) return std::nullopt;
            return *a % *b;
          case BinaryOp::Shl:
            if (*b < 0 || *b > 32 || *a < 0 || *a > 0xFFFFFFFFll) return std::nullopt;
            return int64_t(uint64_t(*a) << *b);
          case BinaryOp::Shr:
            if (*b < 0 || *b > 63) return std::nullopt;
            return *a >> *b;
          case BinaryOp::BitAnd: return *a & *b;
          case BinaryOp::BitOr: return *a | *b;
          case BinaryOp::BitXor: return *a ^ *b;
          default: return std::nullopt;
        }
      }
      default: return std::nullopt;
    }
  }

  // : SEMANTIC, : register(...), : packoffset(...), any number of them. A null `binding` means
  // a register is not allowed here, a null `packoffset` a packoffset.
  bool parse_colon_clauses(std::string* semantic, Loc* semantic_loc, RegisterBinding* binding,
                           VarDecl* packoffset = nullptr) {
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
  std::optional<uint32_t> parse_packoffset() {
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
  bool parse_register(RegisterBinding& binding) {
    binding.loc = cur().loc;
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'register'");
      return false;
    }
    const size_t open = pos_;
    advance();
    // An optional shader profile first: register(ps_5_0, t0).
    if (cur().kind == TokenKind::Identifier && tok(pos_ + 1).is_punct(",") && cur().text.find('_') != std::string_view::npos) {
      advance();
      advance();
    }
    const Token& name = cur();
    const std::optional<uint32_t> index = name.kind == TokenKind::Identifier ? register_number(name.text.substr(std::min<size_t>(1, name.text.size()))) : std::nullopt;
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

  static std::optional<uint32_t> register_number(std::string_view digits) {
    if (digits.empty() || digits.size() > 9) return std::nullopt;
    uint32_t value = 0;
    for (char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      value = value * 10 + uint32_t(c - '0');
    }
    return value;
  }

  // <string UIName = "Metallic"; float UIMin = 0.0;>. On a malformed entry the rest of the
  // annotation block is skipped to its '>' and the declaration goes on without it.
  void parse_annotations(std::vector<Annotation>* out) {
    const size_t open = pos_;
    advance();
    while (!is(">") && !is(">>")) {
      if (at_end() || !parse_annotation(out)) {
        skip_annotations(open);
        return;
      }
    }
    expect_closing_angle(open);
  }

  bool parse_annotation(std::vector<Annotation>* out) {
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
  ExprPtr parse_annotation_literal() {
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

  void skip_annotations(size_t open) {
    while (!at_end() && !is(">") && !is(">>") && !is("{") && !is("}")) advance();
    if (is(">") || is(">>")) expect_closing_angle(open);
  }

  // { a, b, { c, d } }. Only the outermost list skips on an error: to just past its '}'.
  ExprPtr parse_init_list() {
    DepthGuard guard(*this);
    if (!guard.ok()) return nullptr;
    const size_t open = pos_;
    auto list = make<InitListExpr>(cur().loc);
    advance();
    ++init_list_nesting_;
    bool ok = true;
    while (!is("}")) {
      ExprPtr element = is("{") ? parse_init_list() : parse_assignment();
      if (!element) {
        ok = false;
        break;
      }
      list->elements.push_back(std::move(element));
      if (accept(",")) continue;
      if (!is("}")) {
        error_unmatched("}", open);
        ok = false;
        break;
      }
    }
    --init_list_nesting_;
    if (ok) {
      advance();
      return list;
    }
    if (init_list_nesting_ == 0) skip_group(open, false);
    return nullptr;
  }

  // One variable declarator after its name: dimensions, annotations, semantics and registers,
  // and an initializer.
  std::unique_ptr<VarDecl> parse_var_declarator(const Specifiers& spec, const Type& base, size_t name_index,
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
      if (!var->initializer || var->initializer->kind != ExprKind::InitList) {
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
  bool parse_declarators(const Specifiers& spec, const Type& base, size_t first_name, DeclContext context,
                         std::vector<std::unique_ptr<VarDecl>>& out) {
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
  Type checked_var_type(const Type& type, size_t type_index) {
    if (!type.is_void()) return type;
    error_at(type_index, "'void' is only valid as a function return type");
    return Type::error();
  }

  // -------------------------------------------------------------------------------------------
  // File scope

  bool parse_top_level() {
    if (accept(";")) return true;
    if (is("}")) {
      error_here("unexpected '}'");
      advance();
      return true;
    }
    std::vector<Attribute> attributes;
    if (is("[") && !parse_attributes(attributes)) return false;
    const Token& token = cur();
    if (token.kind == TokenKind::Identifier) {
      if (token.text == "struct" || token.text == "typedef" || token.text == "cbuffer") {
        if (!attributes.empty()) error_at(attribute_index_, "attributes are only allowed on functions and statements");
        if (token.text == "struct") return parse_struct();
        if (token.text == "typedef") return parse_typedef();
        return parse_cbuffer();
      }
      if (info(pos_).unsupported) {
        error_here(in_quotes(token.text) + " is not supported");
        return false;
      }
      // An unknown word followed by a name is a declaration with a misspelt type; anything else
      // that is neither a qualifier nor a type cannot start a declaration.
      if (is_specifier_at(pos_) || is_type_start(pos_) || (!is_reserved(pos_) && is_name(pos_ + 1)))
        return parse_global(std::move(attributes));
    }
    error_here("expected a declaration");
    return false;
  }

  // A global variable or a function.
  bool parse_global(std::vector<Attribute> attributes) {
    Specifiers spec;
    parse_specifiers(DeclContext::Global, spec);
    const size_t type_index = pos_;
    const std::optional<Type> type = parse_type(true);
    if (!type) return false;
    const std::optional<size_t> name = expect_name();
    if (!name) return false;
    if (is("(")) return parse_function(std::move(attributes), *type, *name);
    if (!attributes.empty()) error_at(attribute_index_, "attributes are only allowed on functions and statements");
    std::vector<std::unique_ptr<VarDecl>> vars;
    const bool ok = parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::Global, vars);
    for (auto& var : vars) unit_.decls.push_back(std::move(var));
    return ok;
  }

  bool parse_function(std::vector<Attribute> attributes, const Type& return_type, size_t name_index) {
    auto function = make<FunctionDecl>(tok(name_index).loc);
    function->name = std::string(tok(name_index).text);
    function->return_type = return_type;
    function->attributes = std::move(attributes);
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

  std::unique_ptr<ParamDecl> parse_param() {
    Specifiers spec;
    parse_specifiers(DeclContext::Param, spec);
    const size_t type_index = pos_;
    const std::optional<Type> type = parse_type(false);
    if (!type) return nullptr;
    Loc loc = tok(type_index).loc;
    std::string name;
    if (is_name(pos_)) {
      loc = cur().loc;
      name = std::string(cur().text);
      advance();
    } else if (!is(",") && !is(")")) {
      error_here("expected a name");
      return nullptr;
    }
    auto param = make<ParamDecl>(loc);
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

  bool parse_struct() {
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
      if (!parse_field(*decl)) recover_member();
      if (pos_ == before && !is("}") && !at_end()) advance();
    }
    const bool closed = accept("}");
    if (!closed) error_unmatched("}", open);
    unit_.decls.push_back(std::move(decl));
    if (closed) expect_semicolon("struct declaration");
    return true;
  }

  bool parse_field(StructDecl& decl) {
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

  // Inside a struct or cbuffer body: as after a statement.
  void recover_member() { recover_statement(); }

  bool parse_typedef() {
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

  bool parse_cbuffer() {
    advance();
    const std::optional<size_t> name = expect_name();
    if (!name) return false;
    auto decl = make<CBufferDecl>(tok(*name).loc);
    decl->name = std::string(tok(*name).text);
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
      if (!parse_cbuffer_member(*decl)) recover_member();
      if (pos_ == before && !is("}") && !at_end()) advance();
    }
    if (!accept("}")) error_unmatched("}", open);
    accept(";");
    unit_.decls.push_back(std::move(decl));
    return true;
  }

  bool parse_cbuffer_member(CBufferDecl& decl) {
    Specifiers spec;
    parse_specifiers(DeclContext::CBufferMember, spec);
    const size_t type_index = pos_;
    const std::optional<Type> type = parse_type(false);
    if (!type) return false;
    const std::optional<size_t> name = expect_name();
    if (!name) return false;
    return parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::CBufferMember,
                             decl.members);
  }

  // [unroll], [loop], [unroll(4)], [numthreads(8, 8, 1)]: any number in a row.
  bool parse_attributes(std::vector<Attribute>& out) {
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

  // -------------------------------------------------------------------------------------------
  // Statements

  std::unique_ptr<BlockStmt> parse_block() {
    const size_t open = pos_;
    auto block = make<BlockStmt>(cur().loc);
    advance();
    while (!is("}") && !at_end()) {
      const size_t before = pos_;
      StmtPtr statement = parse_statement();
      if (statement) {
        block->statements.push_back(std::move(statement));
      } else {
        recover_statement();
      }
      if (pos_ == before && !is("}") && !at_end()) advance();
    }
    if (!accept("}")) error_unmatched("}", open);
    return block;
  }

  static StmtPtr make_simple(StmtKind kind, Loc loc) { return make<SimpleStmt>(kind, loc); }

  // Null when the statement failed and the caller must recover. A statement that failed but
  // already recovered (a bad if condition, a switch) comes back as an empty statement.
  StmtPtr parse_statement() {
    DepthGuard guard(*this);
    if (!guard.ok()) {
      skip_to_block_end();
      return make_simple(StmtKind::Empty, cur().loc);
    }
    std::vector<Attribute> attributes;
    if (is("[") && !parse_attributes(attributes)) return nullptr;
    StmtPtr statement = parse_statement_body();
    if (statement) statement->attributes = std::move(attributes);
    return statement;
  }

  StmtPtr parse_statement_body() {
    const Token& token = cur();
    const Loc loc = token.loc;
    if (token.is_punct("{")) return parse_block();
    if (token.is_punct(";")) {
      advance();
      return make_simple(StmtKind::Empty, loc);
    }
    if (token.kind == TokenKind::Identifier) {
      const std::string_view word = token.text;
      if (word == "if") return parse_if();
      if (word == "for") return parse_for();
      if (word == "while") return parse_while();
      if (word == "do") return parse_do_while();
      if (word == "return") return parse_return();
      if (word == "break" || word == "continue" || word == "discard") {
        advance();
        if (!expect_semicolon(in_quotes(word))) return nullptr;
        const StmtKind kind = word == "break" ? StmtKind::Break : word == "continue" ? StmtKind::Continue : StmtKind::Discard;
        return make_simple(kind, loc);
      }
      if (word == "switch") return parse_switch();
      if (word == "goto") {
        error_here("goto is not supported");
        return nullptr;
      }
      if (word == "else" || word == "case" || word == "default") {  // a label outside a switch
        error_here("unexpected " + in_quotes(word));
        return nullptr;
      }
      if (word == "struct" || word == "typedef" || word == "cbuffer") {
        error_here("local " + std::string(word) + " declarations are not supported");
        return nullptr;
      }
      if (info(pos_).unsupported) {
        error_here(in_quotes(word) + " is not supported");
        return nullptr;
      }
      if (is_declaration_start()) return parse_declaration_statement();
    }
    auto statement = make<ExprStmt>(loc);
    statement->expr = parse_expression();
    if (!statement->expr || !expect_semicolon("expression")) return nullptr;
    return statement;
  }

  // switch (c) { case 1: ... default: ... }, at the word. A label outside any case is an error;
  // statements after a label belong to it until the next one.
  StmtPtr parse_switch() {
    auto statement = make<SwitchStmt>(cur().loc);
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'switch'");
      return nullptr;
    }
    const size_t open = pos_;
    advance();
    {
      DepthGuard guard(*this);
      if (!guard.ok()) return nullptr;
      statement->condition = parse_expression();
    }
    if (!statement->condition || !is(")")) {
      if (statement->condition) error_unmatched(")", open);
      skip_group(open, false);
      if (is("{")) skip_group(pos_, true);
      return make_simple(StmtKind::Empty, statement->loc);
    }
    advance();
    if (!is("{")) {
      error_here("expected '{' after the condition of 'switch'");
      return nullptr;
    }
    const size_t brace = pos_;
    advance();
    while (!is("}") && !at_end()) {
      const size_t before = pos_;
      if (is_word("case") || is_word("default")) {
        SwitchCase label;
        label.loc = cur().loc;
        const bool is_default = is_word("default");
        advance();
        if (!is_default) {
          DepthGuard guard(*this);
          if (!guard.ok()) return nullptr;
          label.value = parse_conditional();
          if (!label.value) {
            recover_statement();
            continue;
          }
        }
        if (!accept(":")) {
          error_after_previous(std::string("expected ':' after ") + (is_default ? "'default'" : "the case value"));
          recover_statement();
          continue;
        }
        statement->cases.push_back(std::move(label));
        continue;
      }
      if (statement->cases.empty()) {
        error_here("expected 'case' or 'default' in a switch");
        recover_statement();
        if (pos_ == before) advance();
        continue;
      }
      StmtPtr child = parse_statement();
      if (child) statement->cases.back().statements.push_back(std::move(child));
      else recover_statement();
      if (pos_ == before && !is("}") && !at_end()) advance();
    }
    if (!accept("}")) error_unmatched("}", brace);
    return statement;
  }

  // A declaration begins with a qualifier, or with a type not followed by '(' (which would be a
  // constructor call), or with two names in a row (an unknown type, reported by parse_type).
  bool is_declaration_start() const {
    const Token& token = cur();
    if (token.kind != TokenKind::Identifier) return false;
    if (is_specifier_at(pos_)) return true;
    if (is_type_start(pos_)) return !tok(type_end(pos_)).is_punct("(");
    return !is_reserved(pos_) && is_name(pos_ + 1);
  }

  // float a = 1, b[2]; — in a block or a for header. Consumes the ';'.
  StmtPtr parse_declaration_statement() {
    auto statement = make<DeclStmt>(cur().loc);
    Specifiers spec;
    parse_specifiers(DeclContext::Local, spec);
    const size_t type_index = pos_;
    const std::optional<Type> type = parse_type(false);
    if (!type) return nullptr;
    const std::optional<size_t> name = expect_name();
    if (!name) return nullptr;
    if (!parse_declarators(spec, checked_var_type(*type, type_index), *name, DeclContext::Local, statement->vars))
      return nullptr;
    return statement;
  }

  // ( expression ) after if and while. On an error the group is skipped, so that the body can
  // still be read; null then.
  ExprPtr parse_paren_condition(std::string_view keyword) {
    if (!is("(")) {
      error_here("expected '(' after " + in_quotes(keyword));
      return nullptr;
    }
    const size_t open = pos_;
    advance();
    ExprPtr condition = parse_expression();
    if (condition && is(")")) {
      advance();
      return condition;
    }
    if (condition) error_unmatched(")", open);
    skip_group(open, false);
    return nullptr;
  }

  StmtPtr parse_if() {
    auto statement = make<IfStmt>(cur().loc);
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'if'");
      return nullptr;
    }
    statement->condition = parse_paren_condition("if");
    if (!statement->condition && (is("}") || at_end())) return make_simple(StmtKind::Empty, statement->loc);
    statement->then_branch = parse_statement();
    if (!statement->then_branch) return nullptr;
    if (is_word("else")) {
      advance();
      statement->else_branch = parse_statement();
      if (!statement->else_branch) return nullptr;
    }
    if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
    return statement;
  }

  StmtPtr parse_while() {
    auto statement = make<WhileStmt>(cur().loc);
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'while'");
      return nullptr;
    }
    statement->condition = parse_paren_condition("while");
    if (!statement->condition && (is("}") || at_end())) return make_simple(StmtKind::Empty, statement->loc);
    statement->body = parse_statement();
    if (!statement->body) return nullptr;
    if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
    return statement;
  }

  StmtPtr parse_do_while() {
    auto statement = make<DoWhileStmt>(cur().loc);
    advance();
    statement->body = parse_statement();
    if (!statement->body) return nullptr;
    if (!is_word("while")) {
      error_here("expected 'while' after the body of 'do'");
      return nullptr;
    }
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'while'");
      return nullptr;
    }
    statement->condition = parse_paren_condition("while");
    if (!expect_semicolon("do-while statement")) return nullptr;
    if (!statement->condition) return make_simple(StmtKind::Empty, statement->loc);
    return statement;
  }

  StmtPtr parse_for() {
    auto statement = make<ForStmt>(cur().loc);
    advance();
    if (!is("(")) {
      error_here("expected '(' after 'for'");
      return nullptr;
    }
    const size_t open = pos_;
    advance();
    const bool header_ok = parse_for_header(*statement, open);
    if (!header_ok) {
      skip_group(open, true);
      if (is("}") || at_end()) return make_simple(StmtKind::Empty, statement->loc);
    }
    statement->body = parse_statement();
    if (!statement->body) return nullptr;
    if (!header_ok) return make_simple(StmtKind::Empty, statement->loc);
    return statement;
  }

  bool parse_for_header(ForStmt& statement, size_t open) {
    if (!is(";")) {
      if (is_declaration_start()) {
        statement.init = parse_declaration_statement();
        if (!statement.init) return false;
      } else {
        auto init = make<ExprStmt>(cur().loc);
        init->expr = parse_expression();
        if (!init->expr) return false;
        if (!is(";")) {
          error_here("expected ';' in 'for' statement");
          return false;
        }
        advance();
        statement.init = std::move(init);
      }
    } else {
      advance();
    }
    if (!is(";")) {
      statement.condition = parse_expression();
      if (!statement.condition) return false;
      if (!is(";")) {
        error_here("expected ';' in 'for' statement");
        return false;
      }
    }
    advance();
    if (!is(")")) {
      statement.step = parse_expression();
      if (!statement.step) return false;
      if (!is(")")) {
        error_unmatched(")", open);
        return false;
      }
    }
    advance();
    return true;
  }

  StmtPtr parse_return() {
    auto statement = make<ReturnStmt>(cur().loc);
    advance();
    if (!is(";")) {
      statement->value = parse_expression();
      if (!statement->value) return nullptr;
    }
    if (!expect_semicolon("return statement")) return nullptr;
    return statement;
  }

  // -------------------------------------------------------------------------------------------
  // Expressions

  ExprPtr parse_expression() {
    ChainDepth chain(*this);
    ExprPtr lhs = parse_assignment();
    while (lhs && is(",")) {
      if (!chain.push()) return nullptr;
      auto comma = make<BinaryExpr>(cur().loc, BinaryOp::Comma);
      advance();
      comma->lhs = std::move(lhs);
      comma->rhs = parse_assignment();
      if (!comma->rhs) return nullptr;
      lhs = std::move(comma);
    }
    return lhs;
  }

  static std::optional<AssignOp> assign_op(const Token& token) {
    if (token.kind != TokenKind::Punct) return std::nullopt;
    const std::string_view t = token.text;
    if (t == "=") return AssignOp::Assign;
    if (t == "+=") return AssignOp::Add;
    if (t == "-=") return AssignOp::Sub;
    if (t == "*=") return AssignOp::Mul;
    if (t == "/=") return AssignOp::Div;
    if (t == "%=") return AssignOp::Mod;
    if (t == "<<=") return AssignOp::Shl;
    if (t == ">>=") return AssignOp::Shr;
    if (t == "&=") return AssignOp::BitAnd;
    if (t == "|=") return AssignOp::BitOr;
    if (t == "^=") return AssignOp::BitXor;
    return std::nullopt;
  }

  // Right-associative: a = b = c is a = (b = c).
  ExprPtr parse_assignment() {
    ExprPtr target = parse_conditional();
    if (!target) return nullptr;
    const std::optional<AssignOp> op = assign_op(cur());
    if (!op) return target;
    auto assign = make<AssignExpr>(cur().loc, *op);
    advance();
    DepthGuard guard(*this);
    if (!guard.ok()) return nullptr;
    assign->target = std::move(target);
    assign->value = parse_assignment();
    if (!assign->value) return nullptr;
    return assign;
  }

  // c ? a : b, right-associative through its last operand.
  ExprPtr parse_conditional() {
    ExprPtr condition = parse_binary(1);
    if (!condition || !is("?")) return condition;
    const size_t question = pos_;
    auto conditional = make<ConditionalExpr>(cur().loc);
    advance();
    DepthGuard guard(*this);
    if (!guard.ok()) return nullptr;
    conditional->condition = std::move(condition);
    conditional->then_value = parse_expression();
    if (!conditional->then_value) return nullptr;
    if (!is(":")) {
      if (error_here("expected ':' in conditional expression"))
        diagnostics_.note(tok(question).loc, "to match this '?'");
      return nullptr;
    }
    advance();
    conditional->else_value = parse_assignment();
    if (!conditional->else_value) return nullptr;
    return conditional;
  }

  // Precedence of a binary operator (higher binds tighter); 0 when the token is none.
  static int binary_precedence(const Token& token, BinaryOp& op) {
    if (token.kind != TokenKind::Punct) return 0;
    const std::string_view t = token.text;
    struct Entry {
      std::string_view text;
      BinaryOp op;
      int precedence;
    };
    static constexpr Entry kTable[] = {
        {"||", BinaryOp::LogicalOr, 1},   {"&&", BinaryOp::LogicalAnd, 2}, {"|", BinaryOp::BitOr, 3},
        {"^", BinaryOp::BitXor, 4},       {"&", BinaryOp::BitAnd, 5},      {"==", BinaryOp::Equal, 6},
        {"!=", BinaryOp::NotEqual, 6},    {"<", BinaryOp::Less, 7},        {">", BinaryOp::Greater, 7},
        {"<=", BinaryOp::LessEqual, 7},   {">=", BinaryOp::GreaterEqual, 7}, {"<<", BinaryOp::Shl, 8},
        {">>", BinaryOp::Shr, 8},         {"+", BinaryOp::Add, 9},         {"-", BinaryOp::Sub, 9},
        {"*", BinaryOp::Mul, 10},         {"/", BinaryOp::Div, 10},        {"%", BinaryOp::Mod, 10},
    };
    for (const Entry& entry : kTable) {
      if (entry.text == t) {
        op = entry.op;
        return entry.precedence;
      }
    }
    return 0;
  }

  // Precedence climbing: left-associative, one loop per level reached.
  ExprPtr parse_binary(int min_precedence) {
    ChainDepth chain(*this);
    ExprPtr lhs = parse_unary();
    while (lhs) {
      BinaryOp op{};
      const int precedence = binary_precedence(cur(), op);
      if (precedence == 0 || precedence < min_precedence) break;
      if (!chain.push()) return nullptr;
      auto binary = make<BinaryExpr>(cur().loc, op);
      advance();
      binary->lhs = std::move(lhs);
      binary->rhs = parse_binary(precedence + 1);
      if (!binary->rhs) return nullptr;
      lhs = std::move(binary);
    }
    return lhs;
  }

  // ( TYPE ) at `index`: a cast, told from a parenthesised expression by the type table.
  bool is_cast_at(size_t index) const {
    if (!tok(index).is_punct("(") || !is_type_start(index + 1)) return false;
    return tok(type_end(index + 1)).is_punct(")");
  }

  ExprPtr parse_unary() {
    const Token& token = cur();
    if (token.kind == TokenKind::Punct) {
      std::optional<UnaryOp> op;
      const std::string_view t = token.text;
      if (t == "+") op = UnaryOp::Plus;
      else if (t == "-") op = UnaryOp::Minus;
      else if (t == "!") op = UnaryOp::Not;
      else if (t == "~") op = UnaryOp::BitNot;
      else if (t == "++") op = UnaryOp::PreIncrement;
      else if (t == "--") op = UnaryOp::PreDecrement;
      if (op) {
        auto unary = make<UnaryExpr>(token.loc, *op);
        advance();
        DepthGuard guard(*this);
        if (!guard.ok()) return nullptr;
        unary->operand = parse_unary();
        if (!unary->operand) return nullptr;
        return unary;
      }
      if (t == "(" && is_cast_at(pos_)) {
        auto cast = make<CastExpr>(token.loc);
        advance();
        const std::optional<Type> target = parse_type(false);
        if (!target) return nullptr;
        cast->target = *target;
        if (!is(")")) {
          error_here("expected ')' after the type of a cast");
          return nullptr;
        }
        advance();
        DepthGuard guard(*this);
        if (!guard.ok()) return nullptr;
        cast->operand = parse_unary();
        if (!cast->operand) return nullptr;
        return cast;
      }
    }
    ExprPtr primary = parse_primary();
    if (!primary) return nullptr;
    return parse_postfix(std::move(primary));
  }

  ExprPtr parse_postfix(ExprPtr expr) {
    ChainDepth chain(*this);
    for (;;) {
      const Token& token = cur();
      if (token.kind != TokenKind::Punct) return expr;
      if ((token.text == "[" || token.text == "." || token.text == "++" || token.text == "--") && !chain.push())
        return nullptr;
      if (token.text == "[") {
        const size_t open = pos_;
        auto index = make<IndexExpr>(token.loc);
        advance();
        DepthGuard guard(*this);
        if (!guard.ok()) return nullptr;
        index->object = std::move(expr);
        index->index = parse_expression();
        if (!index->index) return nullptr;
        if (!is("]")) {
          error_unmatched("]", open);
          return nullptr;
        }
        advance();
        expr = std::move(index);
      } else if (token.text == ".") {
        advance();
        if (cur().kind != TokenKind::Identifier) {
          error_here("expected a member name after '.'");
          return nullptr;
        }
        const Token& member = cur();
        advance();
        if (is("(")) {
          auto call = make<CallExpr>(member.loc);
          call->callee = std::string(member.text);
          call->object = std::move(expr);
          if (!parse_call_args(*call)) return nullptr;
          expr = std::move(call);
        } else {
          auto access = make<MemberExpr>(member.loc);
          access->object = std::move(expr);
          access->member = std::string(member.text);
          expr = std::move(access);
        }
      } else if (token.text == "++" || token.text == "--") {
        auto unary = make<UnaryExpr>(token.loc, token.text == "++" ? UnaryOp::PostIncrement : UnaryOp::PostDecrement);
        advance();
        unary->operand = std::move(expr);
        expr = std::move(unary);
      } else if (token.text == "(") {
        error_here("only functions and methods can be called");
        return nullptr;
      } else {
        return expr;
      }
    }
  }

  // ( args ) of a call, at the '('.
  bool parse_call_args(CallExpr& call) {
    const size_t open = pos_;
    advance();
    DepthGuard guard(*this);
    if (!guard.ok()) return false;
    if (accept(")")) return true;
    for (;;) {
      ExprPtr arg = parse_assignment();
      if (!arg) return false;
      call.args.push_back(std::move(arg));
      if (accept(",")) continue;
      if (accept(")")) return true;
      error_unmatched(")", open);
      return false;
    }
  }

  ExprPtr parse_int_literal() {
    const Token& token = cur();
    auto literal = make<IntLiteralExpr>(token.loc);
    const IntValue value = parse_int_spelling(token.text);
    if (!value.valid) {
      literal_error("invalid integer literal " + in_quotes(token.text));
    } else if (value.too_large) {
      error_here("integer literal is too large");
    }
    literal->value = value.value;
    literal->is_unsigned = value.is_unsigned;
    advance();
    return literal;
  }

  ExprPtr parse_float_literal() {
    const Token& token = cur();
    auto literal = make<FloatLiteralExpr>(token.loc);
    std::string_view text = token.text;
    if (!text.empty()) {
      const char suffix = text.back();
      if (suffix == 'h' || suffix == 'H') {
        literal->half_suffix = true;
        text.remove_suffix(1);
      } else if (suffix == 'f' || suffix == 'F' || suffix == 'l' || suffix == 'L') {
        text.remove_suffix(1);
      }
    }
    literal->spelling = std::string(text);
    const bool starts_well = !text.empty() && ((text[0] >= '0' && text[0] <= '9') || text[0] == '.');
    char* end = nullptr;
    const char* begin = literal->spelling.c_str();
    literal->value = starts_well ? std::strtod(begin, &end) : 0.0;
    if (!starts_well || end != begin + literal->spelling.size()) {
      literal_error("invalid floating-point literal " + in_quotes(token.text));
      literal->value = 0.0;
    } else if (std::isinf(literal->value)) {
      error_here("floating-point literal is out of range");
    }
    advance();
    return literal;
  }

  ExprPtr parse_primary() {
    const Token& token = cur();
    switch (token.kind) {
      case TokenKind::IntLiteral: return parse_int_literal();
      case TokenKind::FloatLiteral: return parse_float_literal();
      case TokenKind::StringLiteral:  // an unterminated one was reported by the lexer already
        literal_error("string literals are only allowed in annotations");
        return nullptr;
      case TokenKind::Identifier: return parse_name_or_call();
      case TokenKind::Punct:
        if (token.text == "(") {
          const size_t open = pos_;
          advance();
          DepthGuard guard(*this);
          if (!guard.ok()) return nullptr;
          ExprPtr inner = parse_expression();
          if (!inner) return nullptr;
          if (!is(")")) {
            error_unmatched(")", open);
            return nullptr;
          }
          advance();
          return inner;
        }
        if (token.text == "{") {
          error_here("initializer lists are only allowed in initializers");
          return nullptr;
        }
        break;
      default: break;
    }
    error_here("expected an expression");
    return nullptr;
  }

  ExprPtr parse_name_or_call() {
    const Token& token = cur();
    if (token.text == "true" || token.text == "false") {
      auto literal = make<BoolLiteralExpr>(token.loc);
      literal->value = token.text == "true";
      advance();
      return literal;
    }
    if (is_type_start(pos_)) {
      // A constructor: float3(a, b), float2x2(...), vector<float, 2>(...).
      auto call = make<CallExpr>(token.loc);
      call->callee = std::string(token.text);
      const std::optional<Type> type = parse_type(false);
      if (!type) return nullptr;
      if (!is("(")) {
        error_here("expected '(' after type " + in_quotes(call->callee));
        return nullptr;
      }
      call->constructed = *type;
      call->call_kind = CallKind::Constructor;
      if (!parse_call_args(*call)) return nullptr;
      return call;
    }
    if (is_reserved(pos_)) {
      error_here("expected an expression");
      return nullptr;
    }
    advance();
    if (is("(")) {
      auto call = make<CallExpr>(token.loc);
      call->callee = std::string(token.text);
      if (!parse_call_args(*call)) return nullptr;
      return call;
    }
    auto name = make<NameExpr>(token.loc);
    name->name = std::string(token.text);
    return name;
  }

  const std::vector<Token>& tokens_;
  DiagnosticEngine& diagnostics_;
  Token eof_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool too_deep_reported_ = false;
  bool unwinding_too_deep_ = false;  // the depth limit failed the construct being unwound
  bool split_angle_ = false;  // the first '>' of the current '>>' closed a template
  size_t init_list_nesting_ = 0;
  size_t last_error_index_ = kNoIndex;
  size_t unknown_reported_until_ = 0;
  size_t attribute_index_ = 0;
  mutable std::unordered_map<std::string_view, Word> words_;
  std::unordered_map<std::string, int64_t, StringHash, std::equal_to<>> int_constants_;
  std::unordered_set<std::string> uniform_constants_;  // file-scope `const int` without static
  TranslationUnit unit_;
};

}  // namespace

TranslationUnit parse(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics) {
  return Parser(tokens, diagnostics).run();
}

}  // namespace xshade::hlsl
