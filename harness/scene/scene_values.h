// The values of a scene file as the scene reader takes them: numbers in a range, vectors,
// property values, keyword lists, and paths (a file beside the scene, refused when it leads out
// of the scene's folder; a shader in the shader folders, kept as written). Each reports what it
// expected at the value's line and column and gives nothing. Internal to the scene reader.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/scene/scene.h"
#include "harness/scene/toml_reader.h"

namespace xshade::harness {

// "a number" or "3 numbers": the shape of a property value.
std::string numbers_text(uint32_t count);
// Letters, digits and _, not starting with a digit: a shader's name for something.
bool is_identifier(std::string_view text);

using NumberCheck = std::function<bool(double)>;
inline bool any_number(double) { return true; }
inline bool non_negative(double value) { return value >= 0.0; }
inline bool positive(double value) { return value > 0.0; }

class SceneValueReader : protected TomlReader {
 protected:
  // `file` names the scene in every location; relative paths in it are relative to its folder.
  explicit SceneValueReader(const std::filesystem::path& file);

  std::optional<double> number(const toml::node& node, std::string_view path, std::string_view expectation,
                               const NumberCheck& check);

  std::optional<float> float_value(const toml::node& node, std::string_view path, std::string_view expectation,
                                   const NumberCheck& check);

  // `table`'s optional `key` (at `path`.key) into `out` where it is given and passes `check`;
  // false where it is given and does not (reported).
  bool optional_float(const toml::table& table, std::string_view key, const std::string& path,
                      std::string_view expectation, const NumberCheck& check, float& out);

  std::optional<int64_t> integer(const toml::node& node, std::string_view path, int64_t min, int64_t max);

  std::optional<glm::vec3> point(const toml::node& node, std::string_view path);

  std::optional<glm::vec3> colour(const toml::node& node, std::string_view path);

  // A number, or an array of 2..4 numbers: a float .. float4 property.
  std::optional<PropertyValue> property_value(const toml::node& node, std::string_view path);

  // A path relative to the scene file's folder, made absolute; one that leads out of the folder
  // is refused before anything could read it.
  std::optional<std::filesystem::path> scene_file_path(const toml::node& node, std::string_view path,
                                                       std::string_view text);

  // A path inside the shader folders, kept as written: the caller knows the folders (ShaderSearchPath).
  std::optional<std::string> library_path(const toml::node& node, std::string_view path);

  std::vector<std::string> keywords(const toml::node& node, std::string_view path);

  std::map<std::string, PropertyValue> properties(const toml::node& node, std::string_view path);
  // A table of names a shader has (properties, textures, buffers): `read(name, value, name_path)`
  // for each key that is an identifier; `table` and `name` say what was expected where the node
  // is not a table ("a table of texture names") or a key is not a name ("a texture property name").
  void for_each_named(const toml::node& node, std::string_view path, std::string_view table, std::string_view name,
                      const std::function<void(const std::string&, const toml::node&, const std::string&)>& read);

  // A table `name` of `parent`: nullptr when absent (reported when required) or not a table.
  const toml::table* table(const toml::table& parent, std::string_view parent_path, std::string_view name,
                           bool required);

  // The tables of an array of tables ([[name]]); an empty list when absent.
  std::vector<const toml::table*> table_array(const toml::table& parent, std::string_view name);

  // An array of exactly N numbers, each passing `check`.
  template <int N>
  std::optional<glm::vec<N, float>> vector(const toml::node& node, std::string_view path,
                                           std::string_view element_expectation, const NumberCheck& check);

  std::filesystem::path scene_folder_;  // absolute and normalised
};

// ---- template definitions

template <int N>
std::optional<glm::vec<N, float>> SceneValueReader::vector(const toml::node& node, std::string_view path,
                                                           std::string_view element_expectation,
                                                           const NumberCheck& check) {
  using toml_text::index_path;
  auto* array = node.as_array();
  if (!array || array->size() != N) {
    expected(node, path, fmt::format("an array of {} numbers", N));
    return std::nullopt;
  }
  glm::vec<N, float> result(0.0f);
  bool ok = true;
  for (int i = 0; i < N; ++i) {
    auto value = float_value(*array->get(static_cast<size_t>(i)), index_path(path, static_cast<size_t>(i)),
                             element_expectation, check);
    if (value)
      result[i] = *value;
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  return result;
}

}  // namespace xshade::harness
