#include "base/result.h"

namespace xshade {

std::string SourceLocation::to_string() const {
  std::string text = file;
  if (line != 0) {
    text += ':' + std::to_string(line);
    if (column != 0) text += ':' + std::to_string(column);
  }
  return text;
}

static const char* severity_name(Severity severity) {
  switch (severity) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "error";
}

std::string Diagnostic::to_string() const {
  std::string text;
  if (where.known()) text = where.to_string() + ": ";
  return text + severity_name(severity) + ": " + message;
}

std::string Error::to_string() const {
  std::string text;
  if (where.known()) text = where.to_string() + ": ";
  text += message;
  for (const Diagnostic& diagnostic : diagnostics) {
    text += "\n  " + diagnostic.to_string();
    if (!diagnostic.excerpt.empty()) text += "\n" + diagnostic.excerpt;
  }
  return text;
}

}  // namespace xshade
