// golden/MANIFEST.toml: one entry per blessed golden image saying why it is what it is.
//
// The text is written whole by format_golden_manifest, sorted by scene then lane, so that a bless
// changes only its own entry and a review shows exactly which golden moved and why.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "base/result.h"

namespace xshade::harness {

struct GoldenEntry {
  std::string scene;
  std::string lane;  // empty for the common image that serves every lane
  std::string reason;
  std::string blessed_by;
  std::string date;  // UTC, ISO 8601: 2024-05-01T12:34:56Z
  std::string hash;  // XXH3-128 of the PNG file's bytes, 32 hex digits; GoldenStore uses no image without it
  // The same of the float image beside it (<name>.exr), which bless writes when the render has a
  // value above 1: what the gate compares, the PNG being what people review. Empty: no such file.
  std::string float_hash;
  SourceLocation where;  // the entry in the manifest it was read from; unknown for a new one
};

struct GoldenManifest {
  std::vector<GoldenEntry> entries;  // sorted by scene, then lane; one per (scene, lane)

  const GoldenEntry* find(const std::string& scene, const std::string& lane) const;
  // Adds the entry or replaces the one for the same scene and lane, keeping the order.
  void record(GoldenEntry entry);
};

// A manifest entry is about 600 bytes; 32 MiB holds some fifty thousand goldens, far past any
// project, and keeps a mistaken file (a link to a log, /dev/zero) from being read at all.
inline constexpr size_t kMaxManifestBytes = size_t(32) << 20;
// The same bound counted in entries, for a file of short ones: 100,000 goldens (a day of
// blessing a second each) is past any project.
inline constexpr size_t kMaxManifestEntries = 100'000;

// A missing file is an empty manifest (GoldenStore refuses images without one); one that is not a
// file (a folder, a FIFO, a link to nothing) or is larger than kMaxManifestBytes is refused. An
// entry without a hash reads, so that bless can repair it; GoldenStore refuses to use its image.
// Errors carry the manifest's file:line:col.
Result<GoldenManifest> read_golden_manifest(const std::filesystem::path& path);
Result<GoldenManifest> parse_golden_manifest(std::string_view text, const std::string& file_name);
// The whole file: the header comment explaining the layout, then the entries.
std::string format_golden_manifest(const GoldenManifest& manifest);

}  // namespace xshade::harness
