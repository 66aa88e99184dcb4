// A hand-written recursive-descent parser for the HLSL subset of hlsl_like.
//
// Shape of the code:
// - Declarations and statements are told apart C-style: the parser keeps a table of the struct
//   and typedef names declared so far, beside the built-in type names, less those a variable
//   hides in the scope being read (parse_scopes.cpp).
// - A failed parse function returns null without skipping; the nearest recovery point skips:
//   a statement in a block, a declaration at file scope, a struct field or cbuffer member, the
//   parenthesised header of if/while/for, and the outermost initializer list.
// - Every recursion that input can nest goes through a DepthGuard, so hostile nesting is an
//   error at kMaxParseDepth, never a stack overflow; all skipping is iterative, in skip_until.
#include "hlsl_like/parser.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "hlsl_like/parser_internal.h"

namespace xshade::hlsl {
namespace parser_detail {
namespace {

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
  for (TextureShape shape :
       {TextureShape::Tex1D, TextureShape::Tex1DArray, TextureShape::Tex2D, TextureShape::Tex2DArray,
        TextureShape::Tex2DMS, TextureShape::Tex2DMSArray, TextureShape::Tex3D, TextureShape::Cube,
        TextureShape::CubeArray, TextureShape::Subpass, TextureShape::SubpassMS})
    table[texture_shape_name(shape)] = {Type::texture(shape, Type::vector(ScalarType::Float, 4)), TypeWord::Texture};
  table["SamplerState"] = {Type::sampler_state(), TypeWord::Plain};
  table["SamplerComparisonState"] = {Type::sampler_state(true), TypeWord::Plain};
  for (TextureShape shape : {TextureShape::Tex1D, TextureShape::Tex2D, TextureShape::Tex3D, TextureShape::Cube})
    table[texture_shape_name(shape, true)] = {Type::sampler(shape), TypeWord::Plain};
  table["sampler"] = {Type::sampler2d(), TypeWord::Plain};  // DX9: read as sampler2D
  for (BufferKind kind :
       {BufferKind::Buffer, BufferKind::RWBuffer, BufferKind::StructuredBuffer, BufferKind::RWStructuredBuffer,
        BufferKind::ByteAddressBuffer, BufferKind::RWByteAddressBuffer, BufferKind::AppendStructuredBuffer,
        BufferKind::ConsumeStructuredBuffer, BufferKind::RWTexture1D, BufferKind::RWTexture1DArray,
        BufferKind::RWTexture2D, BufferKind::RWTexture2DArray, BufferKind::RWTexture3D})
    table[buffer_kind_name(kind)] = {Type::buffer(kind, Type::vector(ScalarType::Float, 4)), TypeWord::Buffer};
  table["ConstantBuffer"] = {Type::error(), TypeWord::ConstantBuffer};
  for (const char* name : {"texture", "string"}) table[name] = {Type::error(), TypeWord::Unsupported};
  return table;
}

const BuiltinTable& builtin_types() {
  static const BuiltinTable table = make_builtin_types();
  return table;
}

using WordTable = std::unordered_map<std::string_view, WordInfo>;

WordTable make_word_table() {
  WordTable table;
  for (const auto& [name, builtin] : builtin_types()) table[name].builtin = &builtin;
  table["ConstantBuffer"].template_only = true;
  for (std::string_view word :
       {"struct",   "typedef",  "cbuffer",  "tbuffer",   "if",          "else",        "for",       "while",
        "do",       "break",    "continue", "return",    "discard",     "switch",      "case",      "default",
        "goto",     "true",     "false",    "register",  "packoffset",  "class",       "interface", "namespace",
        "template", "typename", "enum",     "technique", "technique10", "technique11", "sizeof",    "this"})
    table[word].reserved = true;
  for (std::string_view word : {"class", "interface", "namespace", "template", "typename", "tbuffer", "enum",
                                "technique", "technique10", "technique11", "sizeof", "this"})
    table[word].unsupported = true;
  for (std::string_view word : {"static", "const", "uniform", "extern", "groupshared", "volatile", "precise", "inline",
                                "row_major", "column_major", "in", "out", "inout", "shared", "snorm", "unorm"}) {
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

bool is_opener(const Token& token) {
  return token.kind == TokenKind::Punct && (token.text == "(" || token.text == "[" || token.text == "{");
}

bool is_closer(const Token& token) {
  return token.kind == TokenKind::Punct && (token.text == ")" || token.text == "]" || token.text == "}");
}

// The SkipToken bit of `token`; 0 for any token recovery does not look for.
unsigned skip_token(const Token& token) {
  if (token.kind != TokenKind::Punct) return 0;
  const std::string_view t = token.text;
  if (t == ";") return kSkipSemicolon;
  if (t == "{") return kSkipOpenBrace;
  if (t == "}") return kSkipCloseBrace;
  if (t == ")") return kSkipCloseParen;
  if (t == "]") return kSkipCloseBracket;
  if (t == ">" || t == ">>") return kSkipCloseAngle;
  return 0;
}

}  // namespace

Parser::Parser(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics)
    : tokens_(tokens), diagnostics_(diagnostics), word_index_(256), token_words_(tokens.size()) {
  words_.reserve(256);
  eof_.kind = TokenKind::EndOfFile;
  if (!tokens.empty()) eof_.loc = tokens.back().loc;
}

TranslationUnit Parser::run() {
  {
    AstArenaScope nodes(unit_.arena);
    while (!at_end()) {
      const size_t before = pos_;
      if (!parse_top_level()) recover_top_level();
      if (pos_ == before && !at_end()) advance();  // never loop in place
    }
  }
  return std::move(unit_);
}

// -------------------------------------------------------------------------------------------
// Diagnostics

void Parser::report_too_deep() {
  unwinding_too_deep_ = true;
  if (too_deep_reported_) return;
  too_deep_reported_ = true;
  error_here("nesting is too deep (more than " + std::to_string(kMaxParseDepth) + " levels)");
}

// At most one error per token position, and an Unknown token is always reported as the
// character it is, once, whatever the parser expected there.
bool Parser::error_at(size_t index, std::string message) {
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

// A malformed literal (a bad number, an unterminated string) was reported by the lexer at the
// token's start; the parser reports one only for a token stream that did not come from there.
void Parser::literal_error(std::string message) {
  const Loc loc = cur().loc;
  for (const Diagnostic& d : diagnostics_.diagnostics())
    if (d.severity == Severity::Error && d.where.line == loc.line && d.where.column == loc.column) return;
  error_here(std::move(message));
}

// "expected ')' to match '('" at the current token, with a note at the opening bracket.
void Parser::error_unmatched(std::string_view close, size_t open_index) {
  const std::string open(tok(open_index).text);
  if (error_here("expected '" + std::string(close) + "' to match '" + open + "'"))
    diagnostics_.note(tok(open_index).loc, "to match this '" + open + "'");
}

// A missing ';' is reported; when the next token starts a new line the statement is kept as
// if the ';' were there, which is what the author most likely meant.
bool Parser::expect_semicolon(std::string_view after) {
  if (accept(";")) return true;
  error_after_previous("expected ';' after " + std::string(after));
  return cur().at_line_start && cur().kind != TokenKind::Unknown && !is("}") && !at_end();
}

// Something missing between the previous token and this one is reported just past the end of
// the previous token, where clang and DXC point: the next token may be lines further on.
bool Parser::error_after_previous(std::string message) {
  if (pos_ == 0 || cur().kind == TokenKind::Unknown || pos_ == last_error_index_) return error_here(std::move(message));
  const std::optional<Loc> end = end_of(tok(pos_ - 1));
  if (!end) return error_here(std::move(message));
  last_error_index_ = pos_;
  diagnostics_.error(*end, std::move(message));
  return true;
}

// Where `token` ends in its file; nothing when its text is not the source at its location (a
// token from a macro expansion is located at the macro's name, a spliced one was rebuilt).
std::optional<Loc> Parser::end_of(const Token& token) const {
  if (token.loc.file == 0 || token.loc.column == 0) return std::nullopt;
  const std::string_view line = diagnostics_.sources().line_text(token.loc.file, token.loc.line);
  const size_t start = token.loc.column - 1;
  if (start > line.size() || line.data() + start != token.text.data()) return std::nullopt;
  if (token.text.size() > line.size() - start) return std::nullopt;
  return Loc{token.loc.file, token.loc.line, static_cast<uint32_t>(token.loc.column + token.text.size())};
}

// -------------------------------------------------------------------------------------------
// Recovery: one iterative skip, skip_until, and the recovery points that call it

// The recovery points, not this, end the unwinding of a construct the depth limit failed
// (unwinding_too_deep_): a skip inside an annotation leaves it to the declaration's recovery.
SkipEnd Parser::skip_until(const SkipUntil& until) {
  size_t balance = 0;
  while (!at_end()) {
    const Token& token = cur();
    const unsigned bit = skip_token(token);
    if (bit & until.barriers) return SkipEnd::Barrier;
    if (balance == 0 && (bit & until.stops)) {
      if (until.consume) advance();
      return SkipEnd::Stop;
    }
    if (!until.flat) {
      if (is_opener(token)) {
        ++balance;
      } else if (is_closer(token) && balance > 0) {
        --balance;
        if (balance == 0 && until.after_braces && token.is_punct("}")) {
          advance();
          return SkipEnd::AfterBraces;
        }
      }
    }
    advance();
  }
  return SkipEnd::EndOfFile;
}

// Inside a block, and a struct or cbuffer body: to just after the next ';' or to the '}' that
// closes the block, skipping bracketed groups whole; stray ')' and ']' belong to the failed
// statement and are skipped.
void Parser::recover_statement() {
  if (unwinding_too_deep_) {
    // Nesting too deep to read says nothing about where the failed statement ends (an
    // else-if chain goes on past any ';'): the rest of the block goes.
    skip_to_block_end();
    return;
  }
  skip_until({.stops = kSkipSemicolon | kSkipCloseBrace});
  accept(";");
}

// To the '}' that closes the current block, not consuming it.
void Parser::skip_to_block_end() {
  unwinding_too_deep_ = false;
  skip_until({.stops = kSkipCloseBrace});
}

// At file scope: to just after the next ';', or after the end of a {...} block (and a ';'
// right after it).
void Parser::recover_top_level() {
  unwinding_too_deep_ = false;
  skip_until({.stops = kSkipSemicolon, .after_braces = true});
  accept(";");
}

// From the opening bracket at `open`, moves to just past the bracket that closes it (true).
// Stops early (false) at the end of the input, at a ';' unless `semicolons_inside`, and, for
// a parenthesised group, at a brace: those cannot be inside, so the closer is missing.
bool Parser::skip_group(size_t open, bool semicolons_inside) {
  unwinding_too_deep_ = false;
  pos_ = open;
  const bool parens = tok(open).is_punct("(") || tok(open).is_punct("[");
  advance();
  const unsigned barriers =
      (semicolons_inside ? 0u : kSkipSemicolon) | (parens ? kSkipOpenBrace | kSkipCloseBrace : 0u);
  return skip_until(
             {.stops = kSkipCloseParen | kSkipCloseBracket | kSkipCloseBrace, .barriers = barriers, .consume = true}) ==
         SkipEnd::Stop;
}

// -------------------------------------------------------------------------------------------
// Words and names

uint32_t Parser::find_word(std::string_view text) const {
  const auto [word, added] = word_index_.insert(text);
  if (added) words_.push_back({&lookup_word(text), -1});
  return word;
}

// The classification of the token at `index`; a plain word for anything but an identifier.
const WordInfo& Parser::info(size_t index) const {
  const Token& token = tok(index);
  static const WordInfo kNone;
  return token.kind == TokenKind::Identifier ? *word_at(index).info : kNone;
}

bool Parser::is_type_start(size_t index) const {
  const Token& token = tok(index);
  if (token.kind != TokenKind::Identifier) return false;
  const Word& w = word_at(index);
  if (w.info->template_only && !tok(index + 1).is_punct("<")) return false;
  return w.info->builtin != nullptr || w.names_user_type();
}

// The index just past the type spelled at `index` (which is_type_start): the word and, for
// the template-like words, a bounded <...>. Only a look ahead; parse_type reports errors.
size_t Parser::type_end(size_t index) const {
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
    } else if (token.text == ";" || token.text == "{" || token.text == "}" || token.text == "(" || token.text == ")" ||
               token.text == "=") {
      return next;
    }
  }
  return next;
}

bool Parser::is_specifier_at(size_t index) const {
  const WordInfo& here = info(index);
  if (here.hard_specifier) return true;
  if (!here.interpolation) return false;
  const WordInfo& next = info(index + 1);
  return next.hard_specifier || next.interpolation || is_type_start(index + 1);
}

bool Parser::is_name(size_t index) const {
  const Token& token = tok(index);
  if (token.kind != TokenKind::Identifier) return false;
  const Word& w = word_at(index);
  if (w.info->template_only && !tok(index + 1).is_punct("<")) return !w.names_user_type();
  return !w.info->reserved && !w.info->builtin && !w.names_user_type();
}

bool Parser::is_declared_name(size_t index) const {
  if (is_name(index)) return true;
  const Token& token = tok(index);
  if (token.kind != TokenKind::Identifier) return false;
  const Word& w = word_at(index);
  return w.user_type >= 0 && !w.info->reserved && !w.info->builtin;
}

// Consumes a declared name; reports "expected a name" when there is none.
std::optional<size_t> Parser::expect_name() {
  if (!is_declared_name(pos_)) {
    error_here("expected a name");
    return std::nullopt;
  }
  const size_t index = pos_;
  advance();
  return index;
}

// The name of a new struct or typedef: a type name already declared is let through, for
// declare_type to report as a redefinition.
std::optional<size_t> Parser::expect_type_name() {
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
void Parser::declare_type(size_t name_index, const Type& type) {
  const std::string_view name = tok(name_index).text;
  Word& w = word_at(name_index);
  if (w.user_type >= 0) {
    error_at(name_index, "redefinition of type " + in_quotes(name));
    return;
  }
  w.user_type = int32_t(user_types_.size());
  user_types_.push_back(type);
}

}  // namespace parser_detail

TranslationUnit parse(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics) {
  return parser_detail::Parser(tokens, diagnostics).run();
}

}  // namespace xshade::hlsl
