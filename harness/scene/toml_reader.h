// What xshade's TOML files (scenes, the project file) share when they are read: a syntax error or
// a wrong value is reported as file:line:col with the key's path, what was expected and what was
// found; an unknown key suggests the known one it is a typo of; every problem in the file is
// collected, and the first in file order is the error's message.
#pragma once

#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "base/result.h"
#include "base/spelling.h"

namespace xshade::harness::toml_text {

using xshade::nearest;  // base/spelling.h
std::string join(std::initializer_list<std::string_view> words, std::string_view separator = ", ");
// `text` in double quotes, cut after 48 characters.
std::string quote_text(std::string_view text);
// The value as a message shows what was found: scalars and short arrays as written in TOML.
std::string describe(const toml::node& node);
// "base[3]" and "base.key" ("key" when base is empty): where a value is, in messages.
std::string index_path(std::string_view base, size_t index);
std::string key_path(std::string_view base, std::string_view key);

}  // namespace xshade::harness::toml_text

namespace xshade::harness {

class TomlReader {
 protected:
  // `file_text` names the file in every location.
  explicit TomlReader(std::string file_text) : file_text_(std::move(file_text)) {}

  // The table tree of `text`; a syntax error is reported, and gives nullopt.
  std::optional<toml::table> parse(std::string_view text);

  SourceLocation where(const toml::source_region& region) const;
  void report(const toml::source_region& region, std::string message);
  void report(const SourceLocation& where, std::string message);
  void expected(const toml::node& node, std::string_view path, std::string_view expectation);
  void missing(const toml::node& parent, std::string_view path, std::string_view expectation);
  // Every key of `table` must be one of `known`; each stranger is reported at its own position.
  void check_keys(const toml::table& table, std::string_view path, std::initializer_list<std::string_view> known,
                  std::string_view context = {});
  // A non-empty string, else reported.
  std::optional<std::string> string(const toml::node& node, std::string_view path, std::string_view expectation);

  // `value` when nothing was reported, else the first problem in file order with all of them.
  template <class T>
  Result<T> finish(T value) {
    if (diagnostics_.empty()) return value;
    return fail(first_problem());
  }

  std::string file_text_;

 private:
  Error first_problem();
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace xshade::harness
