// The drivers' own shader cache (Mesa's), which xshade keeps inside its compile cache, one folder
// a build (driver_cache_folder). Mesa checks each entry as it reads it, but an entry that fails
// its check is compiled again and never replaced: a damaged cache gives right images and every
// later run slower than a cold one, silently. So xshade does not believe a file it did not see
// written: after a run it records each entry's hash, size and time (record_driver_cache), and
// before the next it holds the entries to their records (check_driver_cache); a folder with an
// entry that changed is set aside (renamed, then removed) and the drivers build a new one. Only
// an entry new or touched since is read: a warm run stats the cache, it does not read it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace xshade::harness {

// CACHE/driver-IDENTITY: the folder Mesa is given (MESA_SHADER_CACHE_DIR) under xshade's cache.
std::filesystem::path driver_cache_folder(const std::filesystem::path& cache_dir);

// Empty when every recorded entry that is still there has its recorded bytes (Mesa may evict
// entries); else the folder has been set aside and the text says why, for a warning.
std::optional<std::string> check_driver_cache(const std::filesystem::path& folder);

// Records the hash of every entry now in the folder, for the next run's check.
void record_driver_cache(const std::filesystem::path& folder);

}  // namespace xshade::harness
