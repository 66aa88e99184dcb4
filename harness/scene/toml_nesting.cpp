#include "harness/scene/toml_nesting.h"

#include <fmt/format.h>

namespace xshade::harness {
namespace {

// Walks TOML text byte by byte, keeping line and column as toml++ counts them (columns in code
// points, so that both point at the same character).
class NestingScanner {
 public:
  NestingScanner(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  Result<void> scan() {
    while (i_ < text_.size()) {
      const char c = text_[i_];
      switch (c) {
        case '\n':
        case '=':
        case ',':
          if (auto ended = end_key(); !ended) return ended;
          advance();
          break;
        case '[':
        case '{':
          if (auto ended = end_key(); !ended) return ended;
          if (++depth_ > kMaxTomlNesting)
            return fail(ErrorKind::UserInput,
                        fmt::format("arrays, inline tables and table headers nest more than {} deep here; xshade "
                                    "reads at most {} levels (a deeper file could overflow the TOML parser's stack)",
                                    kMaxTomlNesting, kMaxTomlNesting),
                        here());
          advance();
          break;
        case ']':
        case '}':
          if (auto ended = end_key(); !ended) return ended;
          if (depth_ > 0) --depth_;
          advance();
          break;
        case '#':
          while (i_ < text_.size() && text_[i_] != '\n') advance();
          break;
        case ' ':
        case '\t':
        case '\r': advance(); break;
        case '.':
          start_key();
          ++key_parts_;
          advance();
          break;
        case '"':
        case '\'':
          start_key();
          skip_string(c);
          break;
        default:
          start_key();
          advance();
          break;
      }
    }
    return end_key();
  }

 private:
  SourceLocation here() const { return {file_, line_, column_}; }

  void advance() {
    const auto byte = static_cast<unsigned char>(text_[i_++]);
    if (byte == '\n') {
      ++line_;
      column_ = 1;
    } else if ((byte & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
      ++column_;
    }
  }

  bool at(std::string_view what) const { return text_.substr(i_, what.size()) == what; }

  // A bare word, a quoted part or a dot outside a key starts one: `a`, `"a"`, `1.5` (a float
  // counts as two parts, which no limit worth having trips on).
  void start_key() {
    if (key_parts_ != 0) return;
    key_parts_ = 1;
    key_start_ = here();
  }

  // What ends a dotted run (a newline, `=`, `,`, a bracket) ends the key: now its parts are known.
  Result<void> end_key() {
    const size_t parts = key_parts_;
    key_parts_ = 0;
    if (parts <= kMaxTomlNesting) return {};
    return fail(ErrorKind::UserInput,
                fmt::format("a dotted key or table header of {} parts; xshade reads at most {} (a longer one could "
                            "overflow the TOML parser's stack)",
                            parts, kMaxTomlNesting),
                key_start_);
  }

  // A basic ("..."), literal ('...') or multi-line ("""...""", '''...''') string. An unclosed
  // one-line string stops at the end of its line, where toml++ will report it.
  void skip_string(char quote) {
    const std::string triple(3, quote);
    if (at(triple)) {
      for (int k = 0; k < 3; ++k) advance();
      while (i_ < text_.size() && !at(triple)) {
        if (quote == '"' && text_[i_] == '\\' && i_ + 1 < text_.size()) advance();
        advance();
      }
      for (int k = 0; k < 3 && i_ < text_.size(); ++k) advance();
      // Up to two quotes right before the closing three are part of the string: `""""" `.
      for (int k = 0; k < 2 && i_ < text_.size() && text_[i_] == quote; ++k) advance();
      return;
    }
    advance();
    while (i_ < text_.size() && text_[i_] != quote && text_[i_] != '\n') {
      if (quote == '"' && text_[i_] == '\\' && i_ + 1 < text_.size() && text_[i_ + 1] != '\n') advance();
      advance();
    }
    if (i_ < text_.size() && text_[i_] == quote) advance();
  }

  std::string_view text_;
  const std::string& file_;
  size_t i_ = 0;
  uint32_t line_ = 1;
  uint32_t column_ = 1;
  size_t depth_ = 0;
  size_t key_parts_ = 0;  // parts of the dotted run being read; 0 outside one
  SourceLocation key_start_;
};

}  // namespace

Result<void> check_toml_nesting(std::string_view text, const std::string& file) {
  return NestingScanner(text, file).scan();
}

}  // namespace xshade::harness
