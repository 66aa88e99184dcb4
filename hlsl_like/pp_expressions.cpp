// #if and #elif: the line's `defined` answered, its macros expanded, and the constant expression
// evaluated. C's integer arithmetic on 64 bits, signed unless a u suffix or a too large literal
// makes a value unsigned. Precedence climbing for the binary operators; the only recursion is for
// parentheses and ?:, bounded by kMaxExpressionDepth.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hlsl_like/preprocessor_internal.h"

namespace xshade::hlsl {
namespace pp_detail {
namespace {

// Parentheses and ?: nesting in a #if expression.
constexpr size_t kMaxExpressionDepth = 128;

class ExpressionParser {
 public:
  ExpressionParser(const std::vector<PPTok>& tokens, Loc end, DiagnosticEngine& diagnostics,
                   const std::function<bool(std::string_view)>& is_defined)
      : is_defined_(is_defined), diagnostics_(diagnostics), t_(tokens), end_loc_(end) {}

  std::optional<ExpressionValue> evaluate() {
    const ExpressionValue value = comma(true);
    if (!failed_ && i_ < t_.size()) {
      const Token& token = t_[i_].tok;
      fail(token.loc, is_punct1(token, ')') ? std::string("unexpected ')' in expression")
                                            : "unexpected '" + clip(token.text) + "' in expression");
    }
    if (failed_) return std::nullopt;
    return value;
  }

 private:
  void fail(Loc loc, std::string message) {
    if (failed_) return;
    failed_ = true;
    diagnostics_.error(loc, std::move(message));
  }
  bool at_punct(std::string_view p) const { return i_ < t_.size() && t_[i_].tok.is_punct(p); }

  ExpressionValue comma(bool eval) {
    ExpressionValue value = conditional(eval);
    while (!failed_ && at_punct(",")) {
      ++i_;
      value = conditional(eval);
    }
    return value;
  }

  ExpressionValue conditional(bool eval) {
    ExpressionValue c = binary(1, eval);
    if (failed_ || !at_punct("?")) return c;
    const Loc question = t_[i_].tok.loc;
    ++i_;
    if (++depth_ > kMaxExpressionDepth) {
      fail(question, "expression nested too deeply");
      return {};
    }
    const bool truth = c.v != 0;
    const ExpressionValue a = comma(eval && truth);
    if (failed_) return {};
    if (!at_punct(":")) {
      fail(i_ < t_.size() ? t_[i_].tok.loc : end_loc_, "expected ':' in expression");
      return {};
    }
    ++i_;
    const ExpressionValue b = conditional(eval && !truth);
    --depth_;
    ExpressionValue result = truth ? a : b;
    result.is_unsigned = a.is_unsigned || b.is_unsigned;
    return result;
  }

  static int precedence(const Token& token) {
    if (token.kind != TokenKind::Punct) return 0;
    const std::string_view p = token.text;
    if (p == "*" || p == "/" || p == "%") return 10;
    if (p == "+" || p == "-") return 9;
    if (p == "<<" || p == ">>") return 8;
    if (p == "<" || p == ">" || p == "<=" || p == ">=") return 7;
    if (p == "==" || p == "!=") return 6;
    if (p == "&") return 5;
    if (p == "^") return 4;
    if (p == "|") return 3;
    if (p == "&&") return 2;
    if (p == "||") return 1;
    return 0;
  }

  ExpressionValue binary(int min_precedence, bool eval) {
    ExpressionValue lhs = unary(eval);
    for (;;) {
      if (failed_ || i_ >= t_.size()) return lhs;
      const int p = precedence(t_[i_].tok);
      if (p == 0 || p < min_precedence) return lhs;
      const Token& op = t_[i_].tok;
      ++i_;
      if (p == 2 || p == 1) {  // && and || evaluate their right side only when it matters
        const bool left = lhs.v != 0;
        const bool needed = p == 2 ? left : !left;
        const ExpressionValue rhs = binary(p + 1, eval && needed);
        lhs = ExpressionValue{(p == 2 ? (left && rhs.v != 0) : (left || rhs.v != 0)) ? 1u : 0u, false};
        continue;
      }
      const ExpressionValue rhs = binary(p + 1, eval);
      lhs = apply(op, lhs, rhs, eval);
    }
  }

  ExpressionValue apply(const Token& op, ExpressionValue a, ExpressionValue b, bool eval) {
    const std::string_view p = op.text;
    const bool u = a.is_unsigned || b.is_unsigned;
    const auto sa = static_cast<int64_t>(a.v);
    const auto sb = static_cast<int64_t>(b.v);
    auto boolean = [](bool x) { return ExpressionValue{x ? 1u : 0u, false}; };
    if (p == "*") return {a.v * b.v, u};
    if (p == "+") return {a.v + b.v, u};
    if (p == "-") return {a.v - b.v, u};
    if (p == "/" || p == "%") {
      if (b.v == 0) {
        if (eval) fail(op.loc, "division by zero in preprocessor expression");
        return {0, u};
      }
      if (u) return {p == "/" ? a.v / b.v : a.v % b.v, true};
      if (sa == std::numeric_limits<int64_t>::min() && sb == -1) return {p == "/" ? a.v : 0, false};
      return {static_cast<uint64_t>(p == "/" ? sa / sb : sa % sb), false};
    }
    if (p == "<<" || p == ">>") {
      const bool negative_count = !b.is_unsigned && sb < 0;
      const bool too_far = negative_count || b.v >= 64;
      if (p == "<<") return {too_far ? 0 : a.v << b.v, a.is_unsigned};
      if (too_far) return {(!a.is_unsigned && sa < 0) ? ~uint64_t(0) : 0, a.is_unsigned};
      if (a.is_unsigned) return {a.v >> b.v, true};
      return {static_cast<uint64_t>(sa >> b.v), false};
    }
    if (p == "<") return boolean(u ? a.v < b.v : sa < sb);
    if (p == ">") return boolean(u ? a.v > b.v : sa > sb);
    if (p == "<=") return boolean(u ? a.v <= b.v : sa <= sb);
    if (p == ">=") return boolean(u ? a.v >= b.v : sa >= sb);
    if (p == "==") return boolean(a.v == b.v);
    if (p == "!=") return boolean(a.v != b.v);
    if (p == "&") return {a.v & b.v, u};
    if (p == "^") return {a.v ^ b.v, u};
    return {a.v | b.v, u};  // "|"
  }

  ExpressionValue unary(bool eval) {
    // Prefix operators are gathered first and applied afterwards, so that a long chain of them
    // costs no recursion.
    const size_t first = i_;
    while (i_ < t_.size()) {
      const Token& token = t_[i_].tok;
      if (!(is_punct1(token, '+') || is_punct1(token, '-') || is_punct1(token, '!') || is_punct1(token, '~'))) break;
      ++i_;
    }
    const size_t last = i_;
    ExpressionValue value = primary(eval);
    for (size_t k = last; k-- > first;) {
      switch (t_[k].tok.text[0]) {
        case '-': value.v = 0 - value.v; break;
        case '!': value = ExpressionValue{value.v == 0 ? 1u : 0u, false}; break;
        case '~': value.v = ~value.v; break;
        default: break;
      }
    }
    return value;
  }

  ExpressionValue primary(bool eval) {
    if (failed_) return {};
    if (i_ >= t_.size()) {
      fail(end_loc_, "expected value in expression");
      return {};
    }
    const Token& token = t_[i_].tok;
    switch (token.kind) {
      case TokenKind::IntLiteral: ++i_; return integer(token);
      case TokenKind::Identifier:
        ++i_;
        if (token.text == "defined") return defined(token);
        return {};  // an identifier that is not a macro counts as 0
      case TokenKind::FloatLiteral: fail(token.loc, "floating-point literal in preprocessor expression"); return {};
      default: break;
    }
    if (is_punct1(token, '(')) {
      ++i_;
      if (++depth_ > kMaxExpressionDepth) {
        fail(token.loc, "expression nested too deeply");
        return {};
      }
      const ExpressionValue value = comma(eval);
      --depth_;
      if (failed_) return {};
      if (!at_punct(")")) {
        fail(token.loc, "missing ')' in expression");
        return {};
      }
      ++i_;
      return value;
    }
    fail(token.loc, "expected value in expression, found '" + clip(token.text) + "'");
    return {};
  }

  // `defined` that only appeared through macro expansion.
  ExpressionValue defined(const Token& keyword) {
    const bool paren = at_punct("(");
    if (paren) ++i_;
    if (i_ >= t_.size() || t_[i_].tok.kind != TokenKind::Identifier) {
      fail(i_ < t_.size() ? t_[i_].tok.loc : keyword.loc, "macro name missing after 'defined'");
      return {};
    }
    const bool result = is_defined_(t_[i_].tok.text);
    ++i_;
    if (paren) {
      if (!at_punct(")")) {
        fail(keyword.loc, "missing ')' after 'defined'");
        return {};
      }
      ++i_;
    }
    return {result ? 1u : 0u, false};
  }

  ExpressionValue integer(const Token& token) {
    const std::string_view text = token.text;
    size_t k = 0;
    unsigned base = 10;
    if (text.size() > 1 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
      base = 16;
      k = 2;
    } else if (text.size() > 1 && text[0] == '0') {
      base = 8;
    }
    uint64_t v = 0;
    bool overflow = false;
    for (; k < text.size(); ++k) {
      const char c = text[k];
      unsigned d;
      if (c >= '0' && c <= '9') {
        d = unsigned(c - '0');
      } else if (base == 16 && c >= 'a' && c <= 'f') {
        d = unsigned(c - 'a' + 10);
      } else if (base == 16 && c >= 'A' && c <= 'F') {
        d = unsigned(c - 'A' + 10);
      } else {
        break;
      }
      if (d >= base) {
        fail(token.loc, "invalid digit '" + std::string(1, c) + "' in octal literal");
        return {};
      }
      if (v > (std::numeric_limits<uint64_t>::max() - d) / base) overflow = true;
      v = v * base + d;
    }
    bool is_unsigned = false;
    for (; k < text.size(); ++k)
      if (text[k] == 'u' || text[k] == 'U') is_unsigned = true;
    if (overflow) {
      fail(token.loc, "integer literal is too large");
      return {};
    }
    if (v > uint64_t(std::numeric_limits<int64_t>::max())) is_unsigned = true;
    return {v, is_unsigned};
  }

  const std::function<bool(std::string_view)>& is_defined_;
  DiagnosticEngine& diagnostics_;
  const std::vector<PPTok>& t_;
  Loc end_loc_;
  size_t i_ = 0;
  size_t depth_ = 0;
  bool failed_ = false;
};

}  // namespace

std::optional<ExpressionValue> evaluate_expression(const std::vector<PPTok>& tokens, Loc end,
                                                   DiagnosticEngine& diagnostics,
                                                   const std::function<bool(std::string_view)>& is_defined) {
  return ExpressionParser(tokens, end, diagnostics, is_defined).evaluate();
}

}  // namespace pp_detail

using pp_detail::is_punct1;

bool Preprocessor::Impl::eval_line(Lexer& lex, const Token& name) {
  line_.clear();
  while (!lex.line_ended()) line_.push_back(lex.next());
  if (line_.empty()) {
    diagnostics_.error(name.loc, "#" + std::string(name.text) + " with no expression");
    return false;
  }
  // `defined X` and `defined(X)` are answered before expansion, so that X is not expanded.
  static constexpr std::string_view kOne = "1";
  static constexpr std::string_view kZero = "0";
  expr_in_.clear();
  for (size_t i = 0; i < line_.size(); ++i) {
    PPTok token;
    token.tok = line_[i];
    if (token.tok.is_identifier("defined")) {
      size_t k = i + 1;
      const bool paren = k < line_.size() && is_punct1(line_[k], '(');
      if (paren) ++k;
      if (k >= line_.size() || line_[k].kind != TokenKind::Identifier) {
        diagnostics_.error(k < line_.size() ? line_[k].loc : token.tok.loc, "macro name missing after 'defined'");
        return false;
      }
      const bool defined = is_defined(line_[k].text);
      if (paren) {
        if (k + 1 >= line_.size() || !is_punct1(line_[k + 1], ')')) {
          diagnostics_.error(token.tok.loc, "missing ')' after 'defined'");
          return false;
        }
        ++k;
      }
      token.tok.kind = TokenKind::IntLiteral;
      token.tok.text = defined ? kOne : kZero;
      i = k;
    }
    expr_in_.push_back(token);
  }
  std::vector<PPTok> expanded;
  expand_list(expr_in_, 0, expr_in_.size(), expanded, true);
  const std::optional<pp_detail::ExpressionValue> value = pp_detail::evaluate_expression(
      expanded, line_.back().loc, diagnostics_, [this](std::string_view macro) { return is_defined(macro); });
  return value && value->v != 0;
}

}  // namespace xshade::hlsl
