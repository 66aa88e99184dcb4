// How bless commits a golden, and how what an interrupted bless left is finished or removed.
//
// MANIFEST.toml is the single point of commit. bless writes each new image under its pending
// name first (`.<name>.pending.<ext>` beside it: the leading dot means no scene's image can have
// that name), then the new manifest to MANIFEST.toml.pending, each synced to disk; renaming the
// manifest into place is the commit; only then are the pending images renamed over the old ones.
// A float image the new golden no longer has is marked by an empty pending file, and removed
// after the commit.
//
// Recovery needs no log of its own because the committed manifest says which bytes each golden
// must have: a pending image whose hash is the manifest's is the committed image not yet renamed,
// and is rolled forward; an empty pending float image where the manifest records none is a
// removal not yet done, and is done; anything else pending belongs to a bless that never
// committed and is deleted, as is a MANIFEST.toml.pending (a commit would have renamed it away).
// Recovery runs under the folder's exclusive lock (golden_lock.h), by bless and by any reader.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

#include "base/result.h"
#include "harness/gate/golden_manifest.h"

namespace xshade::harness {

// folder/vk/dof_off.png -> folder/vk/.dof_off.pending.png (the extension kept: OpenImageIO
// chooses the format by it).
std::filesystem::path pending_path(const std::filesystem::path& golden);
std::filesystem::path pending_manifest_path(const std::filesystem::path& folder);

struct RecoveryAction {
  enum class Kind {
    RollForward,    // the pending image is the committed one: rename it over the golden
    FinishRemoval,  // the committed golden has no float image: remove it and the marker
    Discard,        // from a bless that never committed: delete it
  };
  Kind kind = Kind::Discard;
  std::filesystem::path leftover;  // the pending file, or a manifest that was never committed
  std::filesystem::path golden;    // the image it is for; empty for a manifest leftover
};

// Every file an interrupted bless can leave in `folder` and its lane folders, in name order.
std::vector<std::filesystem::path> find_leftovers(const std::filesystem::path& folder);

// What recovery does with each leftover given the committed `manifest`, in name order.
std::vector<RecoveryAction> plan_recovery(const std::filesystem::path& folder, const GoldenManifest& manifest);

// Reads the committed manifest, carries out plan_recovery and syncs the folders it changed. The
// caller holds the folder's exclusive lock. An unreadable manifest is an error and nothing is
// touched: what is pending cannot be judged against it.
Result<std::vector<RecoveryAction>> recover_golden_folder(const std::filesystem::path& folder);

// Writes `bytes` to `path` and syncs it to disk before returning.
Result<void> write_synced(const std::filesystem::path& path, std::string_view bytes);
// Syncs a file written by someone else (OpenImageIO) to disk.
Result<void> sync_file(const std::filesystem::path& path);
// Syncs a folder, so that a rename or a new file in it survives a power cut.
Result<void> sync_folder(const std::filesystem::path& folder);

}  // namespace xshade::harness
