#include "spirv/glslang_log.h"

#include <charconv>

namespace xshade::spirv {
namespace {

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

// Splits "name:12: message" at the last ":<digits>: " so that names may contain colons.
bool split_location(std::string_view rest, SourceLocation& where, std::string_view& message) {
  for (size_t colon = rest.rfind(": "); colon != std::string_view::npos && colon > 0;
       colon = rest.rfind(": ", colon - 1)) {
    size_t digits_start = rest.rfind(':', colon - 1);
    if (digits_start == std::string_view::npos) continue;
    std::string_view digits = rest.substr(digits_start + 1, colon - digits_start - 1);
    uint32_t line = 0;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), line);
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) continue;
    where.file = std::string(rest.substr(0, digits_start));
    where.line = line;
    message = rest.substr(colon + 2);
    return true;
  }
  return false;
}

}  // namespace

std::vector<Diagnostic> parse_glslang_log(std::string_view log) {
  std::vector<Diagnostic> diagnostics;
  while (!log.empty()) {
    size_t newline = log.find('\n');
    std::string_view line = log.substr(0, newline);
    log = newline == std::string_view::npos ? std::string_view{} : log.substr(newline + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) continue;

    Diagnostic diagnostic;
    std::string_view rest = line;
    if (starts_with(rest, "ERROR: ")) {
      rest.remove_prefix(7);
    } else if (starts_with(rest, "WARNING: ")) {
      diagnostic.severity = Severity::Warning;
      rest.remove_prefix(9);
    } else {
      continue;  // glslang's summary lines ("1 compilation errors. ...") repeat what came before
    }
    std::string_view message = rest;
    split_location(rest, diagnostic.where, message);
    diagnostic.message = std::string(message);
    diagnostics.push_back(std::move(diagnostic));
  }
  return diagnostics;
}

}  // namespace xshade::spirv
