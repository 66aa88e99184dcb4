#include "hlsl_like/diagnostic_engine.h"

#include <algorithm>

namespace xshade::hlsl {

void DiagnosticEngine::report(Severity severity, Loc loc, std::string message) {
  if (severity == Severity::Error) {
    if (errors_ == kErrorLimit) return;
    if (++errors_ == kErrorLimit) {
      diagnostics_.push_back({severity, sources_.resolve(loc), std::move(message)});
      locs_.push_back(loc);
      diagnostics_.push_back({Severity::Note, {}, "too many errors; stopping here"});
      locs_.push_back({});
      return;
    }
  } else if (severity == Severity::Warning) {
    ++warnings_;
  }
  diagnostics_.push_back({severity, sources_.resolve(loc), std::move(message)});
  locs_.push_back(loc);
}

namespace {

// One byte of the author's text as a terminal can show it.
void append_printable(std::string& out, char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte >= 0x20 && byte < 0x7f) {
    out += c;
    return;
  }
  constexpr char kHex[] = "0123456789ABCDEF";
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 0xf];
}

}  // namespace

std::string clipped(std::string_view text) {
  std::string out;
  for (size_t i = 0; i < text.size() && i < kMaxQuotedLength; ++i) append_printable(out, text[i]);
  if (text.size() > kMaxQuotedLength) out += "...";
  return out;
}

std::string in_quotes(std::string_view text) { return "'" + clipped(text) + "'"; }

std::string DiagnosticEngine::render(size_t index) const {
  std::string text = diagnostics_.at(index).to_string();
  const std::string shown = excerpt(index);
  return shown.empty() ? text : text + "\n" + shown;
}

std::vector<Diagnostic> DiagnosticEngine::errors_with_excerpts() const {
  std::vector<Diagnostic> errors;
  for (size_t i = 0; i < diagnostics_.size(); ++i) {
    if (diagnostics_[i].severity != Severity::Error) continue;
    errors.push_back(diagnostics_[i]);
    errors.back().excerpt = excerpt(i);
  }
  return errors;
}

std::string DiagnosticEngine::excerpt(size_t index) const {
  std::string text;
  const Loc loc = locs_.at(index);
  std::string_view line = sources_.line_text(loc.file, loc.line);
  if (line.empty() || loc.column == 0) return text;
  // A very long line is shown around the column, so that a 1 MiB line prints a readable excerpt.
  constexpr size_t kWidth = 120;
  size_t start = 0;
  if (line.size() > kWidth && loc.column > kWidth / 2)
    start = std::min<size_t>(loc.column - 1 - kWidth / 2, line.size() - 1);
  const size_t end = std::min(line.size(), start + kWidth);
  // The caret goes where the pointed-at byte starts in the shown text; a column past the end of
  // the line (a missing ';' after the last token) is that many places past the shown text.
  const size_t caret_byte = loc.column - 1;
  std::string shown;
  size_t caret = std::string::npos;
  for (size_t i = start; i < end; ++i) {
    if (i == caret_byte) caret = shown.size();
    if (line[i] == '\t')
      shown.append(kTabWidth - shown.size() % kTabWidth, ' ');
    else
      append_printable(shown, line[i]);
  }
  if (caret == std::string::npos)
    caret = shown.size() + (caret_byte >= end && caret_byte <= line.size() ? caret_byte - end : 0);
  text += "    ";
  if (start > 0) text += "...";
  text += shown;
  text += "\n    ";
  if (start > 0) text += "   ";
  text.append(caret, ' ');
  text += '^';
  return text;
}

std::string DiagnosticEngine::render_all() const {
  std::string text;
  for (size_t i = 0; i < diagnostics_.size(); ++i) text += render(i) + "\n";
  return text;
}

}  // namespace xshade::hlsl
