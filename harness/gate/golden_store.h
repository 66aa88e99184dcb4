// The folder of golden images a scene's renders are compared against, and its manifest.
//
// `<scene>.png` serves every lane; `<lane>/<scene>.png` exists only where a lane legitimately
// differs, and MANIFEST.toml says why. Lookup falls back from the lane's own image to the common
// one. Every image (PNG and float EXR) must have its entry and hash in MANIFEST.toml: one that
// has not is an error naming the bless command, never a golden used unchecked.
//
// Only bless() writes here: a golden is evidence, so blessing demands a reason and records who
// and when. It holds the folder's exclusive lock (golden_lock.h) for its whole
// read-modify-write, and commits by renaming the manifest (golden_transaction.h): a bless killed
// at any instant leaves the old golden or the new one, and whatever it left half done is finished
// or removed, under the lock, by the next find() or bless().
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "base/result.h"
#include "harness/gate/golden_lock.h"
#include "harness/image/image.h"

namespace xshade::harness {

struct GoldenImage {
  std::filesystem::path path;
  FloatImage image;
  bool lane_specific = false;
  std::string reason;  // from the manifest
};

struct BlessOutcome {
  std::filesystem::path path;  // the image written
  bool replaced = false;       // an image was already at `path`
  // The image that was replaced, for the caller to report how much the golden moved; nullopt
  // when there was none or it could not be read (blessing is how a damaged golden is repaired).
  std::optional<FloatImage> previous;
};

class GoldenStore {
 public:
  // `on_wait` is told when another process holds the folder's lock and this one waits for it.
  explicit GoldenStore(std::filesystem::path folder, LockWaitNotice on_wait = {});

  // The golden `lane` is compared against: its own image when the manifest explains one, else
  // the common image; nullopt when neither exists. Errors: an image the manifest does not list
  // or a missing manifest beside images (each names the bless command), a hash that differs, a
  // manifest entry without its file, an unreadable image or manifest. With `lane` empty, the
  // common image alone. Reads under the folder's shared lock; finishes an interrupted bless
  // first when the folder holds its leftovers and can be written.
  Result<std::optional<GoldenImage>> find(const std::string& scene, const std::string& lane) const;

  // Writes `image` as the golden of `scene` (for every lane when `lane` is nullopt) and records
  // the reason, `who`, the UTC date and the file's hash in the manifest, replacing any earlier
  // entry for the same image. Refuses a blank reason without touching the folder. Waits for the
  // folder's exclusive lock. A test may kill the process after any step of the commit
  // (XSHADE_TEST_ABORT_AFTER_BLESS_STEP, golden_store.cpp) or hold it between reading the
  // manifest and writing it back (XSHADE_TEST_BLESS_HOLDS_MANIFEST_MS).
  Result<BlessOutcome> bless(const std::string& scene, const std::optional<std::string>& lane, const FloatImage& image,
                             const std::string& reason, const std::string& who) const;

  // The command that creates the golden, e.g. `xshade bless material_grid --lane vk --reason "..."`.
  static std::string bless_command(const std::string& scene, const std::optional<std::string>& lane);

  // Every image file find() may read for `scene` on `lane`: the lane's own and the common one,
  // PNG and EXR, whether or not they are there (a watcher waits for them to be made).
  std::vector<std::filesystem::path> files_for(const std::string& scene, const std::string& lane) const;

  // The failure to report when find() returns nullopt: where it looked and how to create one.
  std::string missing_message(const std::string& scene, const std::string& lane) const;

  const std::filesystem::path& folder() const { return folder_; }
  std::filesystem::path manifest_path() const { return folder_ / "MANIFEST.toml"; }

 private:
  std::filesystem::path image_path(const std::string& scene, const std::optional<std::string>& lane) const;

  std::filesystem::path folder_;
  LockWaitNotice on_wait_;
};

}  // namespace xshade::harness
