#include "harness/scene/toml_reader.h"

#include <algorithm>
#include <cctype>
#include <utility>

#include <fmt/format.h>

#include "harness/scene/toml_nesting.h"

namespace xshade::harness {
namespace toml_text {
namespace {

std::string number_text(double value) {
  std::string text = fmt::format("{}", value);
  // A float that happens to be whole is shown as one, so that "expected an integer, got 2.0"
  // says what is wrong.
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

}  // namespace

std::string join(std::initializer_list<std::string_view> words, std::string_view separator) {
  std::string text;
  for (std::string_view word : words) {
    if (!text.empty()) text += separator;
    text += word;
  }
  return text;
}

std::string quote_text(std::string_view text) {
  constexpr size_t max_shown = 48;
  if (text.size() > max_shown) return fmt::format("\"{}...\"", text.substr(0, max_shown));
  return fmt::format("\"{}\"", text);
}

std::string describe(const toml::node& node) {
  if (auto* text = node.as_string()) return quote_text(text->get());
  if (auto* integer = node.as_integer()) return std::to_string(integer->get());
  if (auto* floating = node.as_floating_point()) return number_text(floating->get());
  if (auto* boolean = node.as_boolean()) return boolean->get() ? "true" : "false";
  if (node.is_table()) return "a table";
  if (node.is_date()) return "a date";
  if (node.is_time()) return "a time";
  if (node.is_date_time()) return "a date-time";
  if (auto* array = node.as_array()) {
    if (array->empty()) return "an empty array";
    constexpr size_t max_shown = 6;
    std::string text = "[";
    for (size_t i = 0; i < array->size() && i < max_shown; ++i) {
      if (i != 0) text += ", ";
      text += describe(*array->get(i));
    }
    return text + (array->size() > max_shown ? ", ...]" : "]");
  }
  return "a value";
}

std::string index_path(std::string_view base, size_t index) { return fmt::format("{}[{}]", base, index); }
std::string key_path(std::string_view base, std::string_view key) {
  return base.empty() ? std::string(key) : fmt::format("{}.{}", base, key);
}

}  // namespace toml_text

using namespace toml_text;

std::optional<toml::table> TomlReader::parse(std::string_view text) {
  // Before toml++ sees it: a key nested deep enough would overflow its stack (toml_nesting.h).
  if (auto nesting = check_toml_nesting(text, file_text_); !nesting) {
    report(nesting.error().where, nesting.error().message);
    return std::nullopt;
  }
  // Debian's toml++ is a shared library built with exceptions; the one it throws stops here.
  try {
    return toml::parse(text, std::string_view(file_text_));
  } catch (const toml::parse_error& error) {
    report(error.source(), fmt::format("syntax error: {}", error.description()));
    return std::nullopt;
  }
}

SourceLocation TomlReader::where(const toml::source_region& region) const {
  return {file_text_, static_cast<uint32_t>(region.begin.line), static_cast<uint32_t>(region.begin.column)};
}

void TomlReader::report(const toml::source_region& region, std::string message) {
  diagnostics_.push_back(Diagnostic{Severity::Error, where(region), std::move(message)});
}

void TomlReader::report(const SourceLocation& location, std::string message) {
  diagnostics_.push_back(Diagnostic{Severity::Error, location, std::move(message)});
}

void TomlReader::expected(const toml::node& node, std::string_view path, std::string_view expectation) {
  report(node.source(), fmt::format("{}: expected {}, got {}", path, expectation, describe(node)));
}

void TomlReader::missing(const toml::node& parent, std::string_view path, std::string_view expectation) {
  report(parent.source(), fmt::format("{}: missing; expected {}", path, expectation));
}

void TomlReader::check_keys(const toml::table& table, std::string_view path,
                            std::initializer_list<std::string_view> known, std::string_view context) {
  for (auto&& [key, value] : table) {
    std::string_view name = key.str();
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string message = fmt::format("{}: unknown key{}", key_path(path, name), context);
    if (auto suggestion = nearest(name, known))
      message += fmt::format("; did you mean {}?", *suggestion);
    else
      message += fmt::format("; expected one of {}", join(known));
    report(key.source(), std::move(message));
  }
}

std::optional<std::string> TomlReader::string(const toml::node& node, std::string_view path,
                                              std::string_view expectation) {
  auto* value = node.as_string();
  if (!value || value->get().empty()) {
    expected(node, path, expectation);
    return std::nullopt;
  }
  return value->get();
}

Error TomlReader::first_problem() {
  std::stable_sort(diagnostics_.begin(), diagnostics_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::pair(a.where.line, a.where.column) < std::pair(b.where.line, b.where.column);
  });
  return Error{diagnostics_.front().message, diagnostics_.front().where, diagnostics_};
}

}  // namespace xshade::harness
