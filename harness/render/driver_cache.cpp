#include "harness/render/driver_cache.h"

#include <unistd.h>

#include <map>
#include <sstream>

#include "base/file_io.h"
#include "harness/render/shader_cache.h"  // compiler_identity, content_hash

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// One line an entry: HASH PATH, the path relative to the folder.
constexpr const char* kRecord = ".xshade-entries";

// Mesa's entries: every file under the folder's mesa_shader_cache but its index, which Mesa
// rewrites in place through a memory map as it runs (and checks for itself).
std::map<std::string, std::string> entries_now(const fs::path& folder) {
  std::map<std::string, std::string> entries;
  std::error_code error;
  const fs::path mesa = folder / "mesa_shader_cache";
  for (fs::recursive_directory_iterator it(mesa, error), end; !error && it != end; it.increment(error)) {
    if (!it->is_regular_file(error) || it->path().filename() == "index") continue;
    // Mesa writes an entry under a temporary name and renames it into place.
    if (it->path().extension() == ".tmp") continue;
    if (const std::optional<std::string> bytes = read_file(it->path()))
      entries[fs::relative(it->path(), folder, error).string()] = content_hash(*bytes);
  }
  return entries;
}

}  // namespace

fs::path driver_cache_folder(const fs::path& cache_dir) {
  return cache_dir / ("driver-" + compiler_identity().substr(0, 16));
}

std::optional<std::string> check_driver_cache(const fs::path& folder) {
  const std::optional<std::string> record = read_file(folder / kRecord);
  if (!record) return std::nullopt;
  size_t changed = 0;
  std::string first;
  std::istringstream lines(*record);
  for (std::string hash, path; lines >> hash >> path;) {
    const fs::path entry = folder / path;
    std::error_code error;
    if (!fs::exists(entry, error)) continue;  // evicted
    const std::optional<std::string> bytes = read_file(entry);
    if (bytes && content_hash(*bytes) == hash) continue;
    if (changed++ == 0) first = path;
  }
  if (changed == 0) return std::nullopt;
  // Renamed first, so that a run starting now finds no folder rather than half of one.
  std::error_code error;
  const fs::path aside = folder.string() + ".damaged-" + std::to_string(::getpid());
  fs::rename(folder, aside, error);
  fs::remove_all(error ? folder : aside, error);
  return "the drivers' shader cache in " + folder.string() + " had " + std::to_string(changed) +
         " entr" + (changed == 1 ? "y" : "ies") + " changed since xshade saw them written (" + first +
         "): it is set aside and built again";
}

void record_driver_cache(const fs::path& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) return;
  std::string text;
  for (const auto& [path, hash] : entries_now(folder)) text += hash + " " + path + "\n";
  // Best effort: without a record the next run checks nothing, as before any run.
  (void)write_file_atomically(folder / kRecord, text);
}

}  // namespace xshade::harness
