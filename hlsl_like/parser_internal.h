// The parser, private: the Parser class that parser.cpp and parse_*.cpp define, shared with
// parser_test.cpp so that a test can start at any production. Nothing else includes it; the
// front end's interface is parser.h.
//
// parser.cpp: tokens, diagnostics, the word table and recovery (skip_until);
// parse_declarations.cpp: file scope, declarations, types and qualifiers; parse_statements.cpp;
// parse_expressions.cpp; parse_scopes.cpp: the type names variables hide, scope by scope.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "base/string_index.h"
#include "hlsl_like/ast.h"
#include "hlsl_like/diagnostic_engine.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/token.h"

namespace xshade::hlsl::parser_detail {

inline constexpr size_t kNoIndex = static_cast<size_t>(-1);
// Array lengths above this are an error: nothing in a shader needs more, and later layers
// multiply lengths by element sizes.
inline constexpr int64_t kMaxArrayLength = 65536;
inline constexpr size_t kMaxTemplateLookahead = 64;

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

// Everything the parser needs to know about a word, from one lookup.
struct WordInfo {
  const BuiltinType* builtin = nullptr;  // a built-in type name
  // A type only with template arguments: `ConstantBuffer<S>`; alone it is a name, as the D3D11
  // samples' `cbuffer ConstantBuffer : register(b0)` has it.
  bool template_only = false;
  bool reserved = false;                       // never a variable, function or field name
  bool hard_specifier = false;                 // always a qualifier
  bool unsupported = false;                    // a reserved word of HLSL (or C) not supported
  std::optional<Interpolation> interpolation;  // a qualifier only in front of a type
};

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

IntValue parse_int_spelling(std::string_view text);  // parse_expressions.cpp

// The punctuation recovery looks for, as bits of a set.
enum SkipToken : unsigned {
  kSkipSemicolon = 1u << 0,
  kSkipOpenBrace = 1u << 1,
  kSkipCloseBrace = 1u << 2,
  kSkipCloseParen = 1u << 3,
  kSkipCloseBracket = 1u << 4,
  kSkipCloseAngle = 1u << 5,  // '>' and '>>'
};

// Where Parser::skip_until stops. A bracketed group met on the way is skipped whole, so a stop
// token inside it does not count; a barrier counts wherever it is: it cannot be inside what is
// being skipped, so meeting it means the skip went too far.
struct SkipUntil {
  unsigned stops = 0;         // SkipToken bits that end the skip outside any group met on the way
  unsigned barriers = 0;      // SkipToken bits that end the skip anywhere, before the token
  bool consume = false;       // move past the stop token (never past a barrier)
  bool after_braces = false;  // a {...} group met on the way also ends the skip, past its '}'
  bool flat = false;          // brackets are tokens like any other: no group is skipped whole
};

enum class SkipEnd : uint8_t { Stop, Barrier, AfterBraces, EndOfFile };

template <class T, class... Args>
std::unique_ptr<T> make(Args&&... args) {
  return std::make_unique<T>(std::forward<Args>(args)...);
}

// The children of the node being parsed (a call's arguments, a block's statements) gather on a
// stack shared with the nested nodes of their kind, and move into the node's vector once, at
// its final size: a vector grown child by child was allocated two or three times over. Those
// left on the stack when the node fails are destroyed with the Gathered.
template <class T>
class Gathered {
 public:
  explicit Gathered(std::vector<T>& stack) : stack_(stack), first_(stack.size()) {}
  ~Gathered() { stack_.erase(stack_.begin() + std::ptrdiff_t(first_), stack_.end()); }
  Gathered(const Gathered&) = delete;
  Gathered& operator=(const Gathered&) = delete;

  void push(T child) { stack_.push_back(std::move(child)); }
  template <class Vector>
  void move_to(Vector& out) {
    const auto first = stack_.begin() + std::ptrdiff_t(first_);
    out.reserve(out.size() + size_t(stack_.end() - first));
    std::move(first, stack_.end(), std::back_inserter(out));
    stack_.erase(first, stack_.end());
  }

 private:
  std::vector<T>& stack_;
  size_t first_;
};

class Parser {
 public:
  Parser(const std::vector<Token>& tokens, DiagnosticEngine& diagnostics);

  // The whole token stream, recovering at file scope after each failed declaration.
  TranslationUnit run();

  // The productions. Each starts at the current token; a failed one returns null (or false)
  // without skipping, and the caller's recovery point skips.

  // File scope and declarations (parse_declarations.cpp).
  bool parse_top_level();
  bool parse_global(std::vector<Attribute> attributes, VulkanAttributes vk = {});
  bool parse_function(std::vector<Attribute> attributes, const Type& return_type, size_t name_index);
  std::unique_ptr<ParamDecl> parse_param();
  bool parse_struct();
  bool parse_field(StructDecl& decl);
  bool parse_typedef();
  bool parse_cbuffer(VulkanAttributes vk = {});
  bool parse_cbuffer_member(CBufferDecl& decl);
  bool parse_attributes(std::vector<Attribute>& out);
  // [[vk::location(0)]] and the other Vulkan attributes (parse_vulkan_attributes.cpp).
  bool parse_vulkan_attributes(VulkanAttributes& out);
  bool at_vulkan_attribute() const {
    return is("[") && tok(pos_ + 1).kind == TokenKind::Punct && tok(pos_ + 1).text == "[";
  }
  std::unique_ptr<VarDecl> parse_var_declarator(const Specifiers& spec, const Type& base, size_t name_index,
                                                DeclContext context);
  bool parse_declarators(const Specifiers& spec, const Type& base, size_t first_name, DeclContext context,
                         AstVector<std::unique_ptr<VarDecl>>& out);
  std::optional<Type> parse_array_dims(const Type& base, bool allow_unsized, bool* unsized);
  bool parse_colon_clauses(std::string* semantic, Loc* semantic_loc, RegisterBinding* binding,
                           VarDecl* packoffset = nullptr);
  std::optional<uint32_t> parse_packoffset();
  bool parse_register(RegisterBinding& binding);
  void parse_annotations(std::vector<Annotation>* out);
  bool parse_annotation(std::vector<Annotation>* out);
  ExprPtr parse_annotation_literal();
  std::optional<Type> parse_type(bool allow_void);
  std::optional<Type> parse_shape_template(bool matrix);
  std::optional<ScalarType> parse_template_scalar();
  std::optional<uint64_t> parse_template_number();
  void parse_specifiers(DeclContext context, Specifiers& spec);

  // Statements (parse_statements.cpp).
  std::unique_ptr<BlockStmt> parse_block();
  StmtPtr parse_statement();
  StmtPtr parse_statement_body();
  StmtPtr parse_switch();
  StmtPtr parse_declaration_statement();
  ExprPtr parse_paren_condition(std::string_view keyword);
  StmtPtr parse_if();
  StmtPtr parse_while();
  StmtPtr parse_do_while();
  StmtPtr parse_for();
  bool parse_for_header(ForStmt& statement, size_t open);
  StmtPtr parse_return();

  // Expressions (parse_expressions.cpp).
  ExprPtr parse_expression();
  ExprPtr parse_assignment();
  ExprPtr parse_conditional();
  ExprPtr parse_binary(int min_precedence);
  ExprPtr parse_unary();
  ExprPtr parse_postfix(ExprPtr expr);
  bool parse_call_args(CallExpr& call);
  ExprPtr parse_primary();
  ExprPtr parse_name_or_call();
  ExprPtr parse_int_literal();
  ExprPtr parse_float_literal();
  ExprPtr parse_init_list();

  // The one way recovery moves forward: token by token, never recursing, however deep the
  // brackets skipped nest. The recovery points below say what each skips to.
  SkipEnd skip_until(const SkipUntil& until);

  const Token& cur() const { return tok(pos_); }
  bool at_end() const { return cur().kind == TokenKind::EndOfFile; }

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

  void report_too_deep();

  // -------------------------------------------------------------------------------------------
  // Tokens (parser.cpp)

  const Token& tok(size_t index) const { return index < tokens_.size() ? tokens_[index] : eof_; }
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

  // Diagnostics (parser.cpp)
  bool error_at(size_t index, std::string message);
  bool error_here(std::string message) { return error_at(pos_, std::move(message)); }
  void literal_error(std::string message);
  void error_unmatched(std::string_view close, size_t open_index);
  bool expect_semicolon(std::string_view after);
  bool error_after_previous(std::string message);
  std::optional<Loc> end_of(const Token& token) const;

  // Recovery points (parser.cpp), each a skip_until
  void recover_statement();
  void skip_to_block_end();
  void recover_top_level();
  bool skip_group(size_t open, bool semicolons_inside);

  // Words and names (parser.cpp)

  // A word's classification and, once declared, its struct or typedef type: one hash lookup
  // per token, however many questions the look-ahead asks about it (token_words_ remembers the
  // answer), and the words met so far are numbered by a StringIndex (base/string_index.h).
  struct Word {
    const WordInfo* info = nullptr;
    int32_t user_type = -1;  // index in user_types_ once the word names a struct or typedef
    // 1 + the token index of the variable named like the type that hides it in the scopes being
    // read (parse_scopes.cpp); 0 when the word names its type there.
    uint32_t hidden_by = 0;
    bool names_user_type() const { return user_type >= 0 && hidden_by == 0; }
  };

  // The number of the word of the identifier token at `index` (its index in words_).
  uint32_t word_number(size_t index) const {
    if (index >= token_words_.size()) return find_word(tok(index).text);
    uint32_t& known = token_words_[index];
    if (known == 0) known = find_word(tok(index).text) + 1;
    return known - 1;
  }
  Word& word_at(size_t index) const { return words_[word_number(index)]; }
  uint32_t find_word(std::string_view text) const;
  const WordInfo& info(size_t index) const;
  const BuiltinType* find_builtin_type(size_t index) const { return info(index).builtin; }
  bool is_reserved(size_t index) const { return info(index).reserved; }
  bool is_type_start(size_t index) const;
  size_t type_end(size_t index) const;
  bool is_specifier_at(size_t index) const;
  bool is_name(size_t index) const;
  // A name being declared: a name, or a struct or typedef name that the declaration hides.
  bool is_declared_name(size_t index) const;
  std::optional<size_t> expect_name();
  std::optional<size_t> expect_type_name();
  void declare_type(size_t name_index, const Type& type);

  // Scopes of names (parse_scopes.cpp). C's rule, which HLSL keeps: a variable or parameter
  // named like a struct or typedef hides the type from its declarator to the end of its scope.
  class NameScope {
   public:
    explicit NameScope(Parser& parser) : parser_(parser), mark_(parser.hidden_log_.size()) {}
    ~NameScope() { parser_.restore_hidden(mark_); }
    NameScope(const NameScope&) = delete;
    NameScope& operator=(const NameScope&) = delete;

   private:
    Parser& parser_;
    size_t mark_;
  };
  void hide_type_name(size_t name_index);
  void restore_hidden(size_t mark);
  // Reports a type name used where a variable hides it; false when it is not hidden.
  bool report_hidden_type(size_t index);
  StmtPtr parse_substatement();

  // Types and declarators (parse_declarations.cpp)
  bool expect_closing_angle(size_t open_index);
  bool skip_angles();
  Type checked_var_type(const Type& type, size_t type_index);

  // Statements and expressions (parse_statements.cpp, parse_expressions.cpp)
  bool is_declaration_start() const;
  bool is_cast_at(size_t index) const;
  const NameExpr* find_uniform_constant(const Expr& expr) const;
  std::optional<int64_t> evaluate_int(const Expr& expr) const;

  const std::vector<Token>& tokens_;
  DiagnosticEngine& diagnostics_;
  Token eof_;
  size_t pos_ = 0;
  int depth_ = 0;
  bool too_deep_reported_ = false;
  bool unwinding_too_deep_ = false;  // the depth limit failed the construct being unwound
  bool split_angle_ = false;         // the first '>' of the current '>>' closed a template
  size_t init_list_nesting_ = 0;
  size_t last_error_index_ = kNoIndex;
  size_t unknown_reported_until_ = 0;
  size_t attribute_index_ = 0;
  mutable std::vector<Word> words_;
  mutable StringIndex word_index_;             // numbers words as words_ does
  mutable std::vector<uint32_t> token_words_;  // per token: index in words_ + 1; 0 until asked
  std::vector<Type> user_types_;
  struct HiddenWord {
    uint32_t word;      // in words_
    uint32_t previous;  // its hidden_by before
  };
  std::vector<HiddenWord> hidden_log_;  // undone by each NameScope as it closes
  std::vector<ExprPtr> gathered_args_;
  std::vector<StmtPtr> gathered_statements_;
  std::unordered_map<std::string, int64_t, StringHash, std::equal_to<>> int_constants_;
  std::unordered_set<std::string> uniform_constants_;  // file-scope `const int` without static
  TranslationUnit unit_;
};

}  // namespace xshade::hlsl::parser_detail
