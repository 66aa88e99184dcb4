#include "harness/gate/golden_transaction.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <set>

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include "base/file_io.h"
#include "harness/render/lanes.h"
#include "harness/render/shader_cache.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kPending = ".pending";

bool ends_with(std::string_view text, std::string_view end) {
  return text.size() >= end.size() && text.substr(text.size() - end.size()) == end;
}
bool starts_with(std::string_view text, std::string_view start) { return text.substr(0, start.size()) == start; }

// ".dof_off.pending.png" -> "dof_off.png"; nullopt for any other name.
std::optional<std::string> golden_of_pending(std::string_view name) {
  for (std::string_view extension : {".png", ".exr"}) {
    const std::string suffix = std::string(kPending) + std::string(extension);
    if (name.size() > suffix.size() + 1 && name.front() == '.' && ends_with(name, suffix))
      return std::string(name.substr(1, name.size() - 1 - suffix.size())) + std::string(extension);
  }
  return std::nullopt;
}

// What bless wrote before it kept its temporaries under the names above: MANIFEST.toml.tmp.<pid>
// and <scene>.tmp.<pid>.png; none of them was ever committed.
bool old_temporary(std::string_view name) {
  if (starts_with(name, "MANIFEST.toml.tmp")) return true;
  for (std::string_view extension : {".png", ".exr"}) {
    if (!ends_with(name, extension)) continue;
    const std::string_view stem = name.substr(0, name.size() - extension.size());
    const size_t dot = stem.rfind(".tmp.");
    if (dot == std::string_view::npos || dot == 0) continue;
    const std::string_view pid = stem.substr(dot + 5);
    if (!pid.empty() && std::all_of(pid.begin(), pid.end(), [](char c) { return c >= '0' && c <= '9'; })) return true;
  }
  return false;
}

// The folders goldens live in: the folder itself (common images) and one per lane.
std::vector<std::pair<fs::path, std::string>> golden_folders(const fs::path& folder) {
  std::vector<std::pair<fs::path, std::string>> folders{{folder, ""}};
  for (Lane lane : all_lanes()) folders.emplace_back(folder / lane_name(lane), std::string(lane_name(lane)));
  return folders;
}

Result<void> sync_descriptor(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return fail(ErrorKind::Backend, fmt::format("cannot open {}: {}", path.string(), std::strerror(errno)));
  const bool synced = ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  if (!synced)
    return fail(ErrorKind::Backend, fmt::format("cannot sync {} to disk: {}", path.string(), std::strerror(error)));
  return {};
}

}  // namespace

fs::path pending_path(const fs::path& golden) {
  return golden.parent_path() / ("." + golden.stem().string() + std::string(kPending) + golden.extension().string());
}

fs::path pending_manifest_path(const fs::path& folder) { return folder / "MANIFEST.toml.pending"; }

std::vector<fs::path> find_leftovers(const fs::path& folder) {
  std::vector<fs::path> leftovers;
  for (const auto& [directory, lane] : golden_folders(folder)) {
    std::error_code error;
    for (const auto& item : fs::directory_iterator(directory, error)) {
      const std::string name = item.path().filename().string();
      const bool manifest_leftover = lane.empty() && item.path() == pending_manifest_path(folder);
      if (manifest_leftover || golden_of_pending(name) || old_temporary(name)) leftovers.push_back(item.path());
    }
  }
  std::sort(leftovers.begin(), leftovers.end());
  return leftovers;
}

std::vector<RecoveryAction> plan_recovery(const fs::path& folder, const GoldenManifest& manifest) {
  std::vector<RecoveryAction> actions;
  for (const fs::path& leftover : find_leftovers(folder)) {
    RecoveryAction action{RecoveryAction::Kind::Discard, leftover, {}};
    const std::optional<std::string> golden = golden_of_pending(leftover.filename().string());
    if (golden) {
      action.golden = leftover.parent_path() / *golden;
      const std::string lane = leftover.parent_path() == folder ? "" : leftover.parent_path().filename().string();
      const GoldenEntry* entry = manifest.find(fs::path(*golden).stem().string(), lane);
      const bool float_image = fs::path(*golden).extension() == ".exr";
      const std::string expected = !entry ? "" : float_image ? entry->float_hash : entry->hash;
      const std::optional<std::string> bytes = read_file(leftover);
      if (bytes && bytes->empty() && float_image && entry && expected.empty())
        action.kind = RecoveryAction::Kind::FinishRemoval;
      else if (bytes && !bytes->empty() && !expected.empty() && content_hash(*bytes) == expected)
        action.kind = RecoveryAction::Kind::RollForward;
    }
    actions.push_back(std::move(action));
  }
  return actions;
}

Result<std::vector<RecoveryAction>> recover_golden_folder(const fs::path& folder) {
  if (find_leftovers(folder).empty()) return std::vector<RecoveryAction>();
  Result<GoldenManifest> manifest = read_golden_manifest(folder / "MANIFEST.toml");
  if (!manifest) return fail(manifest.error());
  std::vector<RecoveryAction> actions = plan_recovery(folder, *manifest);
  std::set<fs::path> changed;
  for (const RecoveryAction& action : actions) {
    std::error_code error;
    switch (action.kind) {
      case RecoveryAction::Kind::RollForward: fs::rename(action.leftover, action.golden, error); break;
      case RecoveryAction::Kind::FinishRemoval:
        fs::remove(action.golden, error);
        if (!error) fs::remove(action.leftover, error);
        break;
      case RecoveryAction::Kind::Discard: fs::remove(action.leftover, error); break;
    }
    if (error)
      return fail(ErrorKind::Backend, fmt::format("cannot finish the interrupted bless in {}: {}: {}", folder.string(),
                                                  action.leftover.string(), error.message()));
    changed.insert(action.leftover.parent_path());
  }
  for (const fs::path& directory : changed)
    if (Result<void> synced = sync_folder(directory); !synced) return fail(synced.error());
  return actions;
}

Result<void> write_synced(const fs::path& path, std::string_view bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) return fail(ErrorKind::Backend, fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
  const bool ok = write_all(fd, bytes) && ::fsync(fd) == 0;
  const int error = errno;
  ::close(fd);
  if (!ok) return fail(ErrorKind::Backend, fmt::format("cannot write {}: {}", path.string(), std::strerror(error)));
  return {};
}

Result<void> sync_file(const fs::path& path) { return sync_descriptor(path, O_RDONLY); }

Result<void> sync_folder(const fs::path& folder) { return sync_descriptor(folder, O_RDONLY | O_DIRECTORY); }

}  // namespace xshade::harness
