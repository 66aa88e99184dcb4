#include "hlsl_like/lexer.h"

#include <array>
#include <cstring>

namespace xshade::hlsl {
namespace {

enum : uint8_t {
  kIdentStart = 1,
  kDigit = 2,
  kHex = 4,
  kHorizontalSpace = 8,
  kLineSpecial = 16,
  kSpaceStart = 32,   // may begin whitespace, a comment or a splice: where next() calls skip_space
  kSinglePunct = 64,  // a punctuator that never begins a longer token
};

constexpr std::array<uint8_t, 256> make_classes() {
  std::array<uint8_t, 256> c{};
  for (int i = 'a'; i <= 'z'; ++i) c[size_t(i)] |= kIdentStart;
  for (int i = 'A'; i <= 'Z'; ++i) c[size_t(i)] |= kIdentStart;
  c['_'] |= kIdentStart;
  for (int i = '0'; i <= '9'; ++i) c[size_t(i)] |= kDigit | kHex;
  for (int i = 'a'; i <= 'f'; ++i) c[size_t(i)] |= kHex;
  for (int i = 'A'; i <= 'F'; ++i) c[size_t(i)] |= kHex;
  for (char s : {' ', '\t', '\r', '\v', '\f'}) c[static_cast<unsigned char>(s)] |= kHorizontalSpace;
  // What a skipped line must look at: its end, splices, comments and strings.
  for (char s : {'\n', '\\', '/', '"'}) c[static_cast<unsigned char>(s)] |= kLineSpecial;
  for (char s : {' ', '\t', '\r', '\v', '\f', '\n', '\\', '/'}) c[static_cast<unsigned char>(s)] |= kSpaceStart;
  for (char s : {'(', ')', '[', ']', '{', '}', ';', ',', '?', '~'}) c[static_cast<unsigned char>(s)] |= kSinglePunct;
  return c;
}
constexpr std::array<uint8_t, 256> kClasses = make_classes();

bool has(int c, uint8_t cls) { return c >= 0 && (kClasses[size_t(c)] & cls) != 0; }
bool is_ident(int c) { return has(c, kIdentStart | kDigit); }
bool is_digit(int c) { return has(c, kDigit); }

}  // namespace

Lexer::Lexer(std::string_view text, uint32_t file, DiagnosticEngine& diagnostics, std::deque<std::string>* text_store)
    : text_(text), file_(file), diagnostics_(diagnostics), store_(text_store) {
  // A UTF-8 byte order mark (editors on Windows write one) is no token; columns count from after it.
  if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = line_start_ = 3;
  ends_outside_names_ = !text_.empty() && !is_ident(static_cast<unsigned char>(text_.back()));
}

size_t Lexer::splice_at(size_t p) const {
  const size_t n = text_.size();
  if (p >= n || text_[p] != '\\') return 0;
  if (p + 1 < n && text_[p + 1] == '\n') return 2;
  if (p + 2 < n && text_[p + 1] == '\r' && text_[p + 2] == '\n') return 3;
  return 0;
}

size_t Lexer::past_splices_slow(size_t p) const {
  while (size_t length = splice_at(p)) p += length;
  return p;
}

void Lexer::move_to(size_t p) {
  for (size_t i = pos_; i < p; ++i)
    if (text_[i] == '\n') new_line(i + 1);
  pos_ = p;
}

std::string_view Lexer::store(std::string text) {
  if (!store_) {
    if (!own_store_) own_store_ = std::make_unique<std::deque<std::string>>();
    store_ = own_store_.get();
  }
  store_->push_back(std::move(text));
  return store_->back();
}

// The text of [start, end): a view into the source unless a splice lies inside.
std::string_view Lexer::token_text(size_t start, size_t end) {
  if (first_splice_ == npos || first_splice_ >= end) return text_.substr(start, end - start);
  std::string joined;
  joined.reserve(end - start);
  for (size_t i = start; i < end;) {
    if (size_t length = splice_at(i)) {
      i += length;
    } else {
      joined += text_[i++];
    }
  }
  return store(std::move(joined));
}

void Lexer::skip_block_comment(size_t star) {
  const Loc start = loc_at(pos_);
  move_to(star + 1);
  const char* s = text_.data();
  const size_t n = text_.size();
  for (size_t p = pos_; p < n; ++p) {
    const char c = s[p];
    if (c == '\n') {
      new_line(p + 1);
    } else if (c == '*') {
      const size_t q = past_splices(p + 1);
      if (q < n && s[q] == '/') {
        pos_ = p + 1;
        move_to(q + 1);
        return;
      }
    }
  }
  pos_ = n;
  diagnostics_.error(start, "unterminated comment");
}

void Lexer::skip_line_comment(size_t second_slash) {
  move_to(second_slash + 1);
  const char* s = text_.data();
  const size_t n = text_.size();
  size_t p = pos_;
  for (;;) {
    const void* found = p < n ? std::memchr(s + p, '\n', n - p) : nullptr;
    if (!found) {
      pos_ = n;
      return;
    }
    const size_t nl = size_t(static_cast<const char*>(found) - s);
    // A backslash right before the line end continues the comment on the next line.
    const bool spliced = (nl >= 1 && nl - 1 >= p && s[nl - 1] == '\\') ||
                         (nl >= 2 && nl - 2 >= p && s[nl - 1] == '\r' && s[nl - 2] == '\\');
    if (!spliced) {
      pos_ = nl;
      return;
    }
    new_line(nl + 1);
    p = nl + 1;
  }
}

void Lexer::skip_space() {
  const char* s = text_.data();
  const size_t n = text_.size();
  // Kept in locals and stored once: pos_ and space_ written on every character cost as much as
  // the test of the character.
  size_t p = pos_;
  bool space = space_;
  while (p < n) {
    const char c = s[p];
    if (has(static_cast<unsigned char>(c), kHorizontalSpace)) {
      space = true;
      do ++p;
      while (p < n && has(static_cast<unsigned char>(s[p]), kHorizontalSpace));
    } else if (c == '\n') {
      ++p;
      new_line(p);
      at_line_start_ = true;
      space = true;
    } else if (c == '\\') {
      const size_t length = splice_at(p);
      if (length == 0) break;
      p += length;
      new_line(p);
    } else if (c == '/') {
      const size_t q = past_splices(p + 1);
      if (q >= n) break;
      if (s[q] == '*') {
        pos_ = p;
        skip_block_comment(q);
      } else if (s[q] == '/') {
        pos_ = p;
        skip_line_comment(q);
      } else {
        break;
      }
      p = pos_;
      space = true;
    } else {
      break;
    }
  }
  pos_ = p;
  space_ = space;
}

bool Lexer::line_ended() {
  skip_space();
  return at_line_start_ || pos_ >= text_.size();
}

// Scans a number starting at `start` (a digit, or a '.' before a digit); returns its end.
size_t Lexer::lex_number(size_t start, Loc loc, TokenKind& kind) {
  size_t end = start;  // after the last character taken
  // The next real character after `from`, skipping splices; `where` is its position.
  auto peek = [&](size_t from, size_t& where) {
    where = past_splices(from);
    return char_at(where);
  };
  auto take = [&](size_t where) {
    if (where != end && first_splice_ == npos) first_splice_ = end;
    end = where + 1;
  };
  auto digits = [&](bool hex) {
    size_t count = 0;
    for (;;) {
      size_t where;
      const int c = peek(end, where);
      if (!(hex ? has(c, kHex) : is_digit(c))) return count;
      take(where);
      ++count;
    }
  };

  bool is_float = false;
  bool reported = false;
  size_t where;
  size_t after_zero;
  if (text_[start] == '0' && (peek(start + 1, after_zero) == 'x' || char_at(after_zero) == 'X')) {
    take(start);
    take(after_zero);
    if (digits(true) == 0) {
      diagnostics_.error(loc, "hexadecimal literal has no digits");
      reported = true;
    }
  } else {
    digits(false);
    if (peek(end, where) == '.') {
      take(where);
      is_float = true;
      digits(false);
    }
    int c = peek(end, where);
    if (c == 'e' || c == 'E') {
      const size_t e = where;
      size_t sign;
      const int c2 = peek(e + 1, sign);
      const bool has_sign = c2 == '+' || c2 == '-';
      size_t first_digit = sign;
      if (has_sign) peek(sign + 1, first_digit);
      take(e);
      if (has_sign) take(sign);
      is_float = true;
      if (digits(false) == 0) {
        diagnostics_.error(loc, "exponent has no digits");
        reported = true;
      }
    }
  }
  kind = is_float ? TokenKind::FloatLiteral : TokenKind::IntLiteral;

  const size_t suffix_start = end;
  int c = peek(end, where);
  if (is_float) {
    if (c == 'f' || c == 'F' || c == 'h' || c == 'H' || c == 'l' || c == 'L') take(where);
  } else {
    for (int i = 0; i < 3 && (c == 'u' || c == 'U' || c == 'l' || c == 'L'); ++i) {
      take(where);
      c = peek(end, where);
    }
  }
  c = peek(end, where);
  if (is_ident(c)) {
    while (is_ident(c)) {
      take(where);
      c = peek(end, where);
    }
    if (!reported) {
      std::string suffix;
      for (size_t i = suffix_start; i < end;) {
        if (size_t length = splice_at(i)) {
          i += length;
        } else {
          suffix += text_[i++];
        }
      }
      if (suffix.size() > 64) suffix = suffix.substr(0, 64) + "...";
      diagnostics_.error(loc, "invalid suffix '" + suffix + "' on " + (is_float ? "floating" : "integer") + " literal");
    }
  }
  return end;
}

Token Lexer::next() {
  const char* s = text_.data();
  const size_t n = text_.size();
  if (pos_ < n && has(static_cast<unsigned char>(s[pos_]), kSpaceStart)) {
    // One space between tokens, the most common whitespace, without the call.
    if (s[pos_] == ' ' && pos_ + 1 < n && !has(static_cast<unsigned char>(s[pos_ + 1]), kSpaceStart)) {
      ++pos_;
      space_ = true;
    } else {
      skip_space();
    }
  }
  Token token;
  token.at_line_start = at_line_start_;
  token.space_before = space_;
  token.loc = loc_at(pos_);
  if (pos_ >= n) {
    token.kind = TokenKind::EndOfFile;
    token.text = text_.substr(n, 0);
    return token;
  }
  at_line_start_ = false;
  space_ = false;
  // Most tokens are a name no splice continues or a punctuator that is never the start of a
  // longer one: taken here, the rest in next_other (a function of its own keeps this path short).
  const size_t start = pos_;
  const unsigned char c = static_cast<unsigned char>(s[start]);
  if (has(c, kIdentStart)) {
    size_t end = start + 1;
    if (ends_outside_names_) {
      while (is_ident(static_cast<unsigned char>(s[end]))) ++end;
    } else {
      while (end < n && is_ident(static_cast<unsigned char>(s[end]))) ++end;
    }
    if (end == n || s[end] != '\\') {
      token.kind = TokenKind::Identifier;
      token.text = std::string_view(s + start, end - start);
      pos_ = end;
      return token;
    }
  } else if (has(c, kSinglePunct)) {
    token.kind = TokenKind::Punct;
    token.text = std::string_view(s + start, 1);
    pos_ = start + 1;
    return token;
  }
  next_other(token);
  return token;
}

void Lexer::next_other(Token& token) {
  const char* s = text_.data();
  const size_t n = text_.size();
  first_splice_ = npos;
  const size_t start = pos_;
  const unsigned char c = static_cast<unsigned char>(s[start]);
  size_t end = start + 1;

  // Takes `want` as the next character of a punctuator, looking through splices.
  auto match = [&](char want) {
    const size_t where = past_splices(end);
    if (where >= n || s[where] != want) return false;
    if (where != end && first_splice_ == npos) first_splice_ = end;
    end = where + 1;
    return true;
  };

  token.kind = TokenKind::Punct;
  if (has(c, kIdentStart)) {
    token.kind = TokenKind::Identifier;
    for (;;) {
      while (end < n && is_ident(static_cast<unsigned char>(s[end]))) ++end;
      if (end < n && s[end] == '\\') {
        const size_t where = past_splices(end);
        if (where != end && where < n && is_ident(static_cast<unsigned char>(s[where]))) {
          if (first_splice_ == npos) first_splice_ = end;
          end = where + 1;
          continue;
        }
      }
      break;
    }
  } else if (is_digit(c) || (c == '.' && is_digit(char_at(past_splices(start + 1))))) {
    end = lex_number(start, token.loc, token.kind);
  } else {
    switch (c) {
      case '"': {
        token.kind = TokenKind::StringLiteral;
        for (;;) {
          if (end >= n || s[end] == '\n') {
            diagnostics_.error(token.loc, "unterminated string literal");
            if (end > start && s[end - 1] == '\r') --end;
            break;
          }
          const char ch = s[end];
          if (ch == '"') {
            ++end;
            break;
          }
          if (ch == '\\') {
            if (size_t length = splice_at(end)) {
              if (first_splice_ == npos) first_splice_ = end;
              end += length;
              continue;
            }
            ++end;
            if (end < n && s[end] != '\n') ++end;
            continue;
          }
          ++end;
        }
        break;
      }
      case '(':
      case ')':
      case '[':
      case ']':
      case '{':
      case '}':
      case ';':
      case ',':
      case '?':
      case '~':
      case '.': break;
      case ':': match(':'); break;
      case '+':
        if (!match('+')) match('=');
        break;
      case '-':
        if (!match('-')) match('=');
        break;
      case '*':
      case '/':
      case '%':
      case '^':
      case '!':
      case '=': match('='); break;
      case '<':
        if (match('<')) {
          match('=');
        } else {
          match('=');
        }
        break;
      case '>':
        if (match('>')) {
          match('=');
        } else {
          match('=');
        }
        break;
      case '&':
        if (!match('&')) match('=');
        break;
      case '|':
        if (!match('|')) match('=');
        break;
      case '#': token.kind = match('#') ? TokenKind::HashHash : TokenKind::Hash; break;
      default: token.kind = TokenKind::Unknown; break;
    }
  }
  if (first_splice_ == npos) {
    token.text = text_.substr(start, end - start);
    pos_ = end;
  } else {
    token.text = token_text(start, end);
    move_to(end);
  }
}

Token Lexer::next_header_name() {
  skip_space();
  const size_t n = text_.size();
  if (pos_ < n && text_[pos_] == '<') {
    size_t end = pos_ + 1;
    while (end < n && text_[end] != '>' && text_[end] != '\n') ++end;
    if (end < n && text_[end] == '>') {
      Token token;
      token.kind = TokenKind::AngledHeader;
      token.space_before = space_;
      token.loc = loc_at(pos_);
      token.text = text_.substr(pos_, end + 1 - pos_);
      pos_ = end + 1;
      space_ = false;
      return token;
    }
  }
  return next();
}

std::string_view Lexer::rest_of_line() {
  const char* s = text_.data();
  const size_t n = text_.size();
  std::string joined;
  bool joining = false;
  size_t segment = pos_;
  size_t content_end = npos;
  bool in_string = false;
  auto flush = [&](size_t upto) {
    joined.append(s + segment, upto - segment);
    joining = true;
  };
  while (pos_ < n) {
    const char c = s[pos_];
    if (c == '\n') {
      if (content_end == npos) content_end = pos_;
      ++pos_;
      new_line(pos_);
      at_line_start_ = true;
      space_ = true;
      break;
    }
    if (c == '\\') {
      if (size_t length = splice_at(pos_)) {
        if (content_end == npos) flush(pos_);
        pos_ += length;
        new_line(pos_);
        segment = pos_;
        continue;
      }
      pos_ += (in_string && pos_ + 1 < n && s[pos_ + 1] != '\n') ? 2 : 1;
      continue;
    }
    if (in_string) {
      if (c == '"') in_string = false;
      ++pos_;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '/' && content_end == npos) {
      const size_t q = past_splices(pos_ + 1);
      if (q < n && s[q] == '*') {
        flush(pos_);
        joined += ' ';
        skip_block_comment(q);
        segment = pos_;
        continue;
      }
      if (q < n && s[q] == '/') {
        content_end = pos_;
        skip_line_comment(q);
        continue;
      }
    }
    ++pos_;
  }
  if (content_end == npos) content_end = pos_ < n ? pos_ : n;
  if (content_end < segment) content_end = segment;
  auto is_space = [](char c) { return has(static_cast<unsigned char>(c), kHorizontalSpace); };
  std::string_view result;
  if (joining) {
    joined.append(s + segment, content_end - segment);
    size_t b = 0;
    size_t e = joined.size();
    while (b < e && is_space(joined[b])) ++b;
    while (e > b && is_space(joined[e - 1])) --e;
    result = store(joined.substr(b, e - b));
  } else {
    result = text_.substr(segment, content_end - segment);
    while (!result.empty() && is_space(result.front())) result.remove_prefix(1);
    while (!result.empty() && is_space(result.back())) result.remove_suffix(1);
  }
  return result;
}

void Lexer::skip_line() {
  const char* s = text_.data();
  const size_t n = text_.size();
  bool in_string = false;
  size_t p = pos_;  // in a local, as in skip_space
  while (p < n) {
    while (p < n && !has(static_cast<unsigned char>(s[p]), kLineSpecial)) ++p;
    if (p >= n) break;
    const char c = s[p];
    if (c == '\n') {
      ++p;
      new_line(p);
      at_line_start_ = true;
      space_ = true;
      pos_ = p;
      return;
    }
    if (c == '\\') {
      if (size_t length = splice_at(p)) {
        p += length;
        new_line(p);
      } else {
        p += (in_string && p + 1 < n && s[p + 1] != '\n') ? 2 : 1;
      }
      continue;
    }
    if (c == '"') {
      in_string = !in_string;
      ++p;
      continue;
    }
    // c == '/'
    if (!in_string) {
      const size_t q = past_splices(p + 1);
      if (q < n && s[q] == '*') {
        pos_ = p;
        skip_block_comment(q);
        p = pos_;
        continue;
      }
      if (q < n && s[q] == '/') {
        pos_ = p;
        skip_line_comment(q);
        p = pos_;
        continue;
      }
    }
    ++p;
  }
  pos_ = p;
}

Token Lexer::skip_to_directive() {
  const size_t n = text_.size();
  for (;;) {
    if (!at_line_start_) skip_line();
    skip_space();
    if (pos_ >= n) return next();
    if (at_line_start_ && text_[pos_] == '#') {
      Token token = next();
      if (token.kind == TokenKind::Hash) return token;
      continue;  // "##" starts no directive
    }
    at_line_start_ = false;
  }
}

}  // namespace xshade::hlsl
