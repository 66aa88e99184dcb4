#include "harness/render/driver_cache.h"

#include <unistd.h>

#include <map>
#include <sstream>

#include "base/file_io.h"
#include "harness/render/shader_cache.h"  // compiler_identity, content_hash

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// One line an entry: HASH SIZE MTIME PATH, the path relative to the folder.
constexpr const char* kRecord = ".xshade-entries";

struct Seen {
  std::string hash;
  uintmax_t size = 0;
  int64_t mtime = 0;  // file_time_type ticks
};

// The size and modification time of `file`; nothing when it is gone.
std::optional<Seen> stat_of(const fs::path& file) {
  std::error_code error;
  Seen seen;
  seen.size = fs::file_size(file, error);
  if (error) return std::nullopt;
  seen.mtime = int64_t(fs::last_write_time(file, error).time_since_epoch().count());
  if (error) return std::nullopt;
  return seen;
}

std::map<std::string, Seen> read_record(const fs::path& folder) {
  std::map<std::string, Seen> record;
  const std::optional<std::string> text = read_file(folder / kRecord);
  if (!text) return record;
  std::istringstream lines(*text);
  Seen seen;
  for (std::string path; lines >> seen.hash >> seen.size >> seen.mtime >> path;) record[path] = seen;
  return record;
}

// Whether the entry holds what was recorded: a file whose size and time are as recorded is taken
// as it was (as ccache's and make's checks do: a run reads no entry it need not); one whose time
// moved is read and hashed.
bool as_recorded(const fs::path& file, const Seen& recorded, const Seen& now) {
  if (now.size != recorded.size) return false;
  if (now.mtime == recorded.mtime) return true;
  const std::optional<std::string> bytes = read_file(file);
  return bytes && content_hash(*bytes) == recorded.hash;
}

}  // namespace

fs::path driver_cache_folder(const fs::path& cache_dir) {
  return cache_dir / ("driver-" + compiler_identity().substr(0, 16));
}

std::optional<std::string> check_driver_cache(const fs::path& folder) {
  size_t changed = 0;
  std::string first;
  for (const auto& [path, recorded] : read_record(folder)) {
    const std::optional<Seen> now = stat_of(folder / path);
    if (!now || as_recorded(folder / path, recorded, *now)) continue;  // evicted, or as it was
    if (changed++ == 0) first = path;
  }
  if (changed == 0) return std::nullopt;
  // Renamed first, so that a run starting now finds no folder rather than half of one.
  std::error_code error;
  const fs::path aside = folder.string() + ".damaged-" + std::to_string(::getpid());
  fs::rename(folder, aside, error);
  fs::remove_all(error ? folder : aside, error);
  return "the drivers' shader cache in " + folder.string() + " had " + std::to_string(changed) + " entr" +
         (changed == 1 ? "y" : "ies") + " changed since xshade saw them written (" + first +
         "): it is set aside and built again";
}

void record_driver_cache(const fs::path& folder) {
  const std::map<std::string, Seen> before = read_record(folder);
  std::string text;
  std::error_code error;
  // Mesa's entries: every file under mesa_shader_cache but its index, which Mesa rewrites in
  // place through a memory map as it runs (and checks itself), and the temporaries it writes an
  // entry under before renaming it into place. Only an entry not seen before is read.
  for (fs::recursive_directory_iterator it(folder / "mesa_shader_cache", error), end; !error && it != end;
       it.increment(error)) {
    if (!it->is_regular_file() || it->path().filename() == "index" || it->path().extension() == ".tmp") continue;
    const std::string path = fs::relative(it->path(), folder).string();
    std::optional<Seen> now = stat_of(it->path());
    if (!now) continue;
    if (auto known = before.find(path);
        known != before.end() && known->second.size == now->size && known->second.mtime == now->mtime) {
      now->hash = known->second.hash;
    } else {
      const std::optional<std::string> bytes = read_file(it->path());
      if (!bytes) continue;
      now->hash = content_hash(*bytes);
    }
    text += now->hash + " " + std::to_string(now->size) + " " + std::to_string(now->mtime) + " " + path + "\n";
  }
  // Best effort: without a record the next run checks nothing, as before any run.
  if (!text.empty()) (void)write_file_atomically(folder / kRecord, text);
}

}  // namespace xshade::harness
