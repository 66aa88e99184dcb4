#include "harness/gate/golden_manifest.h"

#include <algorithm>
#include <tuple>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "base/file_io.h"
#include "harness/scene/lane.h"  // parse_lane
#include "harness/scene/toml_nesting.h"

namespace xshade::harness {
namespace {

constexpr std::string_view kHeader =
    R"(# Why each golden image is what it is. Written by `xshade bless`; edit a reason by hand if you
# must, but never add an image without blessing it.
#
# golden/<scene>.png serves every lane; golden/<lane>/<scene>.png exists only where that lane
# legitimately differs, and is not trusted without an entry here. One [[golden]] entry per image:
#   scene       the scene's name (its file name without .toml)
#   lane        "gl", "vk" or "vk-hlsl" for a lane's own image; absent for the common image
#   reason      why the image was blessed: what changed, or why the lane differs
#   blessed_by  who blessed it
#   date        when, UTC, ISO 8601
#   hash        XXH3-128 of the PNG file
#   float_hash  XXH3-128 of the float image beside it (<name>.exr), written where the render has
#               values above 1: the gate compares it, so those values are gated too
# Entries are sorted by scene, then lane.
)";

bool scene_then_lane(const GoldenEntry& a, const GoldenEntry& b) {
  return std::tie(a.scene, a.lane) < std::tie(b.scene, b.lane);
}

// A TOML basic string: quotes, backslashes and control characters escaped, UTF-8 kept as is.
std::string toml_string(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
          out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
        else
          out += c;
    }
  }
  return out + '"';
}

SourceLocation where(const std::string& file, const toml::source_region& region) {
  return {file, static_cast<uint32_t>(region.begin.line), static_cast<uint32_t>(region.begin.column)};
}

Result<GoldenEntry> read_entry(const toml::table& table, const std::string& file) {
  GoldenEntry entry;
  entry.where = where(file, table.source());
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    std::string* field = name == "scene"        ? &entry.scene
                         : name == "lane"       ? &entry.lane
                         : name == "reason"     ? &entry.reason
                         : name == "blessed_by" ? &entry.blessed_by
                         : name == "date"       ? &entry.date
                         : name == "hash"       ? &entry.hash
                         : name == "float_hash" ? &entry.float_hash
                                                : nullptr;
    if (!field)
      return fail(ErrorKind::UserInput,
                  fmt::format("unknown key '{}' in a [[golden]] entry (known: scene, lane, reason, blessed_by, "
                              "date, hash, float_hash)",
                              name),
                  where(file, node.source()));
    const auto* text = node.as_string();
    if (!text)
      return fail(ErrorKind::UserInput, fmt::format("'{}' must be a string", name), where(file, node.source()));
    *field = text->get();
  }
  if (entry.scene.empty()) return fail(ErrorKind::UserInput, "a [[golden]] entry needs a scene", entry.where);
  if (!entry.lane.empty() && !parse_lane(entry.lane))
    return fail(ErrorKind::UserInput, fmt::format("unknown lane '{}' (lanes: gl, vk, vk-hlsl)", entry.lane),
                where(file, table.get("lane")->source()));
  if (entry.reason.find_first_not_of(" \t\r\n") == std::string::npos)
    return fail(ErrorKind::UserInput,
                fmt::format("the golden of {} has no reason",
                            entry.lane.empty() ? entry.scene : entry.lane + "/" + entry.scene),
                entry.where);
  // An entry without its hash reads, so that bless can repair it; GoldenStore::find refuses to
  // use its image, as it refuses one whose hash differs.
  return entry;
}

}  // namespace

const GoldenEntry* GoldenManifest::find(const std::string& scene, const std::string& lane) const {
  auto position = std::lower_bound(
      entries.begin(), entries.end(), std::tie(scene, lane),
      [](const GoldenEntry& entry, const auto& key) { return std::tie(entry.scene, entry.lane) < key; });
  if (position != entries.end() && position->scene == scene && position->lane == lane) return &*position;
  return nullptr;
}

void GoldenManifest::record(GoldenEntry entry) {
  auto position = std::lower_bound(entries.begin(), entries.end(), entry, scene_then_lane);
  if (position != entries.end() && position->scene == entry.scene && position->lane == entry.lane)
    *position = std::move(entry);
  else
    entries.insert(position, std::move(entry));
}

Result<GoldenManifest> parse_golden_manifest(std::string_view text, const std::string& file_name) {
  // Before toml++ sees it: a key nested deep enough would overflow its stack (toml_nesting.h).
  if (auto nesting = check_toml_nesting(text, file_name); !nesting) return fail(nesting.error());
  // Debian's toml++ is a shared library built with exceptions; the one it throws stops here.
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(file_name));
  } catch (const toml::parse_error& error) {
    return fail(ErrorKind::UserInput, fmt::format("syntax error: {}", error.description()),
                where(file_name, error.source()));
  }

  // Read in file order, then sorted once: a find and an insert per entry would make a large
  // manifest quadratic.
  GoldenManifest manifest;
  for (const auto& [key, node] : root) {
    if (key.str() != "golden")
      return fail(ErrorKind::UserInput,
                  fmt::format("unknown key '{}' (the manifest holds only [[golden]] entries)", key.str()),
                  where(file_name, node.source()));
    const toml::array* array = node.as_array();
    if (!array || !array->is_array_of_tables())
      return fail(ErrorKind::UserInput, "'golden' must be an array of tables: [[golden]]",
                  where(file_name, node.source()));
    for (const toml::node& element : *array) {
      if (manifest.entries.size() == kMaxManifestEntries)
        return fail(ErrorKind::UserInput,
                    fmt::format("more than {} [[golden]] entries: this is not a golden manifest xshade wrote",
                                kMaxManifestEntries),
                    where(file_name, element.source()));
      Result<GoldenEntry> entry = read_entry(*element.as_table(), file_name);
      if (!entry) return fail(entry.error());
      manifest.entries.push_back(std::move(*entry));
    }
  }
  // Stable, so that of two entries for one image the earlier in the file comes first.
  std::stable_sort(manifest.entries.begin(), manifest.entries.end(), scene_then_lane);
  auto second = std::adjacent_find(
      manifest.entries.begin(), manifest.entries.end(),
      [](const GoldenEntry& a, const GoldenEntry& b) { return a.scene == b.scene && a.lane == b.lane; });
  if (second != manifest.entries.end()) {
    const GoldenEntry& earlier = *second;
    const GoldenEntry& later = *std::next(second);
    return fail(
        ErrorKind::UserInput,
        fmt::format("a second entry for the golden of {} (the first is at {})",
                    later.lane.empty() ? later.scene : later.lane + "/" + later.scene, earlier.where.to_string()),
        later.where);
  }
  return manifest;
}

Result<GoldenManifest> read_golden_manifest(const std::filesystem::path& path) {
  std::error_code error;
  // No manifest is no golden yet; one that is there but not a file (a link to nothing) is refused.
  if (!std::filesystem::exists(path, error) && not_a_file(path).empty()) return GoldenManifest{};
  auto text = read_input_file(path, kMaxManifestBytes, "the golden manifest");
  if (!text) return fail(text.error());
  return parse_golden_manifest(*text, path.string());
}

std::string format_golden_manifest(const GoldenManifest& manifest) {
  std::string text(kHeader);
  std::vector<GoldenEntry> entries = manifest.entries;
  std::stable_sort(entries.begin(), entries.end(), scene_then_lane);
  for (const GoldenEntry& entry : entries) {
    text += "\n[[golden]]\n";
    text += "scene = " + toml_string(entry.scene) + "\n";
    if (!entry.lane.empty()) text += "lane = " + toml_string(entry.lane) + "\n";
    text += "reason = " + toml_string(entry.reason) + "\n";
    text += "blessed_by = " + toml_string(entry.blessed_by) + "\n";
    text += "date = " + toml_string(entry.date) + "\n";
    if (!entry.hash.empty()) text += "hash = " + toml_string(entry.hash) + "\n";
    if (!entry.float_hash.empty()) text += "float_hash = " + toml_string(entry.float_hash) + "\n";
  }
  return text;
}

}  // namespace xshade::harness
