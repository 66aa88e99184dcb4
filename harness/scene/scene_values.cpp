#include "harness/scene/scene_values.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/paths.h"

namespace xshade::harness {

using namespace toml_text;

std::string numbers_text(uint32_t count) { return count == 1 ? "a number" : fmt::format("{} numbers", count); }

bool is_identifier(std::string_view text) {
  if (text.empty() || std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  return std::all_of(text.begin(), text.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

SceneValueReader::SceneValueReader(const std::filesystem::path& file) : TomlReader(file.string()) {
  std::error_code ignored;
  std::filesystem::path absolute = std::filesystem::absolute(file, ignored);
  scene_folder_ = (absolute.empty() ? file : absolute).parent_path().lexically_normal();
}

std::optional<double> SceneValueReader::number(const toml::node& node, std::string_view path,
                                               std::string_view expectation, const NumberCheck& check) {
  std::optional<double> value;
  if (auto* integer = node.as_integer()) value = static_cast<double>(integer->get());
  if (auto* floating = node.as_floating_point()) value = floating->get();
  if (!value || !std::isfinite(*value) || !check(*value)) {
    expected(node, path, expectation);
    return std::nullopt;
  }
  return value;
}

std::optional<float> SceneValueReader::float_value(const toml::node& node, std::string_view path,
                                                   std::string_view expectation, const NumberCheck& check) {
  auto value = number(node, path, expectation, check);
  if (!value) return std::nullopt;
  return static_cast<float>(*value);
}

bool SceneValueReader::optional_float(const toml::table& table, std::string_view key, const std::string& path,
                                      std::string_view expectation, const NumberCheck& check, float& out) {
  const toml::node* node = table.get(key);
  if (!node) return true;
  auto value = float_value(*node, path + "." + std::string(key), expectation, check);
  if (value) out = *value;
  return value.has_value();
}

std::optional<int64_t> SceneValueReader::integer(const toml::node& node, std::string_view path, int64_t min,
                                                 int64_t max) {
  auto* value = node.as_integer();
  if (!value || value->get() < min || value->get() > max) {
    expected(node, path, fmt::format("an integer in {}..{}", min, max));
    return std::nullopt;
  }
  return value->get();
}

std::optional<glm::vec3> SceneValueReader::point(const toml::node& node, std::string_view path) {
  return vector<3>(node, path, "a number", any_number);
}

std::optional<glm::vec3> SceneValueReader::colour(const toml::node& node, std::string_view path) {
  return vector<3>(node, path, "a number >= 0", non_negative);
}

std::optional<PropertyValue> SceneValueReader::property_value(const toml::node& node, std::string_view path) {
  constexpr std::string_view expectation = "a number or an array of 2 to 4 numbers";
  if (!node.is_array()) {
    auto value = float_value(node, path, expectation, any_number);
    if (!value) return std::nullopt;
    return PropertyValue::scalar(*value);
  }
  const toml::array& array = *node.as_array();
  if (array.size() < 2 || array.size() > 4) {
    expected(node, path, expectation);
    return std::nullopt;
  }
  PropertyValue result;
  result.count = static_cast<uint32_t>(array.size());
  bool ok = true;
  for (size_t i = 0; i < array.size(); ++i) {
    auto value = float_value(*array.get(i), index_path(path, i), "a number", any_number);
    if (value)
      result.components[i] = *value;
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  return result;
}

std::optional<std::filesystem::path> SceneValueReader::scene_file_path(const toml::node& node, std::string_view path,
                                                                       std::string_view text) {
  std::filesystem::path relative(text);
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory()) {
    report(node.source(), fmt::format("{}: expected a path relative to the scene file, got the absolute path {}", path,
                                      quote_text(text)));
    return std::nullopt;
  }
  std::filesystem::path normal = relative.lexically_normal();
  if (normal.empty() || *normal.begin() == "..") {
    report(node.source(), fmt::format("{}: expected a path inside the scene file's folder, got {}, which leads "
                                      "out of it",
                                      path, quote_text(text)));
    return std::nullopt;
  }
  if (!normal.has_filename() || normal == ".") {
    expected(node, path, "a file path");
    return std::nullopt;
  }
  std::filesystem::path full = (scene_folder_ / normal).lexically_normal();
  if (!path_is_inside(full, scene_folder_)) {
    report(node.source(), fmt::format("{}: expected a path inside the scene file's folder, got {}, which leads "
                                      "out of it through a symbolic link",
                                      path, quote_text(text)));
    return std::nullopt;
  }
  return full;
}

std::optional<std::string> SceneValueReader::library_path(const toml::node& node, std::string_view path) {
  auto text = string(node, path, "a path in the shader folders, e.g. \"materials/standard_pbr.hlsl\"");
  if (!text) return std::nullopt;
  std::filesystem::path relative(*text);
  std::filesystem::path normal = relative.lexically_normal();
  if (relative.is_absolute() || relative.has_root_directory() || normal.empty() || *normal.begin() == ".." ||
      !normal.has_filename()) {
    report(node.source(),
           fmt::format("{}: expected a file path inside the shader folders, got {}", path, quote_text(*text)));
    return std::nullopt;
  }
  return text;
}

std::vector<std::string> SceneValueReader::keywords(const toml::node& node, std::string_view path) {
  std::vector<std::string> result;
  auto* array = node.as_array();
  if (!array) {
    expected(node, path, "an array of keyword names");
    return result;
  }
  for (size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    auto* name = element.as_string();
    if (!name || !is_identifier(name->get())) {
      expected(element, index_path(path, i), "a keyword name (letters, digits and _)");
      continue;
    }
    result.push_back(name->get());
  }
  return result;
}

void SceneValueReader::for_each_named(
    const toml::node& node, std::string_view path, std::string_view table_expectation,
    std::string_view name_expectation,
    const std::function<void(const std::string&, const toml::node&, const std::string&)>& read) {
  auto* table = node.as_table();
  if (!table) {
    expected(node, path, table_expectation);
    return;
  }
  for (auto&& [key, value] : *table) {
    std::string name(key.str());
    std::string name_path = key_path(path, name);
    if (!is_identifier(name)) {
      report(key.source(), fmt::format("{}: expected {} (letters, digits and _)", name_path, name_expectation));
      continue;
    }
    read(name, value, name_path);
  }
}

std::map<std::string, PropertyValue> SceneValueReader::properties(const toml::node& node, std::string_view path) {
  std::map<std::string, PropertyValue> result;
  for_each_named(node, path, "a table of property values", "a property name",
                 [&](const std::string& name, const toml::node& value, const std::string& name_path) {
                   if (auto property = property_value(value, name_path)) result.emplace(name, *property);
                 });
  return result;
}

const toml::table* SceneValueReader::table(const toml::table& parent, std::string_view parent_path,
                                           std::string_view name, bool required) {
  const toml::node* node = parent.get(name);
  std::string path = key_path(parent_path, name);
  if (!node) {
    if (required) missing(parent, path, "a table");
    return nullptr;
  }
  if (!node->is_table()) {
    expected(*node, path, "a table");
    return nullptr;
  }
  return node->as_table();
}

std::vector<const toml::table*> SceneValueReader::table_array(const toml::table& parent, std::string_view name) {
  std::vector<const toml::table*> tables;
  const toml::node* node = parent.get(name);
  if (!node) return tables;
  auto* array = node->as_array();
  if (!array) {
    expected(*node, name, fmt::format("an array of tables ([[{}]])", name));
    return tables;
  }
  for (size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    if (auto* element_table = element.as_table())
      tables.push_back(element_table);
    else
      expected(element, index_path(name, i), "a table");
  }
  return tables;
}

}  // namespace xshade::harness
