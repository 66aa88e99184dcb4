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

std::string DiagnosticEngine::render(size_t index) const {
  std::string text = diagnostics_.at(index).to_string();
  const Loc loc = locs_[index];
  std::string_view line = sources_.line_text(loc.file, loc.line);
  if (line.empty() || loc.column == 0) return text;
  // A very long line is shown around the column, so that a 1 MiB line prints a readable excerpt.
  constexpr size_t kWidth = 120;
  size_t start = 0;
  if (line.size() > kWidth && loc.column > kWidth / 2) start = std::min<size_t>(loc.column - 1 - kWidth / 2, line.size() - 1);
  std::string_view shown = line.substr(start, kWidth);
  text += "\n    ";
  if (start > 0) text += "...";
  text += shown;
  text += "\n    ";
  if (start > 0) text += "   ";
  for (size_t i = start; i + 1 < loc.column && i < line.size(); ++i) text += line[i] == '\t' ? '\t' : ' ';
  text += '^';
  return text;
}

std::string DiagnosticEngine::render_all() const {
  std::string text;
  for (size_t i = 0; i < diagnostics_.size(); ++i) text += render(i) + "\n";
  return text;
}

}  // namespace xshade::hlsl
