// Whole files in and out, for xshade's own files (cache entries, reports, goldens).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "base/result.h"

namespace xshade {

// The file's bytes, or nothing when it cannot be read.
std::optional<std::string> read_file(const std::filesystem::path& path);

// Writes to a temporary file beside `path`, then renames it into place: a reader sees the old
// file or the new one, never half of one, and an interrupted write leaves no torn file.
Result<void> write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace xshade
