#include "harness/gate/golden_store.h"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "base/file_io.h"
#include "harness/gate/golden_lock.h"
#include "harness/gate/golden_manifest.h"
#include "harness/gate/golden_transaction.h"
#include "harness/image/image_io.h"
#include "harness/render/lanes.h"
#include "harness/render/shader_cache.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

bool blank(const std::string& text) { return text.find_first_not_of(" \t\r\n") == std::string::npos; }

// "material_grid" or "vk/material_grid": how messages name one golden.
std::string golden_name(const std::string& scene, const std::string& lane) {
  return lane.empty() ? scene : lane + "/" + scene;
}

// A scene name becomes a file name: nothing that could reach outside the folder.
Result<void> check_scene_name(const std::string& scene) {
  if (scene.empty() || scene.front() == '.' || scene.find_first_of("/\\") != std::string::npos)
    return fail(ErrorKind::UserInput, fmt::format("'{}' is not a scene name", scene));
  return {};
}

Result<void> check_lane_name(const std::string& lane) {
  if (!parse_lane(lane)) return fail(ErrorKind::Usage, fmt::format("unknown lane '{}' (lanes: gl, vk, vk-hlsl)", lane));
  return {};
}

std::string utc_now_iso8601() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

// A golden whose bytes differ from what bless recorded was written by something else. A hash
// that is not there is not a check that passes.
Result<void> check_hash(const fs::path& path, const GoldenEntry& entry, const std::string& hash,
                        const std::string& command) {
  if (hash.empty())
    return fail(ErrorKind::UserInput,
                fmt::format("the manifest records no hash for {}, so it cannot be checked: bless it again with {}",
                            path.string(), command),
                entry.where);
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) return fail(ErrorKind::Backend, "cannot read image " + path.string());
  if (content_hash(*bytes) != hash)
    return fail(ErrorKind::UserInput,
                fmt::format("{} is not the image blessed on {} (its hash differs from the manifest's): only "
                            "`xshade bless` may change a golden",
                            path.string(), entry.date),
                entry.where);
  return {};
}

// golden/<name>.exr beside golden/<name>.png.
fs::path float_image_path(const fs::path& png) { return fs::path(png).replace_extension(".exr"); }

// Whether the 8-bit PNG loses a value of the image: a finite colour channel above 1.
bool has_values_above_one(const FloatImage& image) {
  for (size_t i = 0; i < image.rgba.size(); ++i)
    if (i % 4 != 3 && std::isfinite(image.rgba[i]) && image.rgba[i] > 1.0f) return true;
  return false;
}

// The number a test hook's environment variable holds; 0 when it is not set.
int test_hook(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::atoi(value) : 0;
}

// XSHADE_TEST_ABORT_AFTER_BLESS_STEP=k kills this process right after bless's step k, as a kill -9
// or a power cut would, so that a test can prove every instant leaves a state the next run
// recovers from. SIGKILL rather than abort(): nothing runs on the way out and no core is dumped.
void bless_step_done(int step) {
  static const int kill_after = test_hook("XSHADE_TEST_ABORT_AFTER_BLESS_STEP");
  if (step == kill_after) ::raise(SIGKILL);
}

// XSHADE_TEST_BLESS_HOLDS_MANIFEST_MS=n waits n milliseconds between reading the manifest and
// writing it back, so that a test of two blesses at once has them overlap where a bless without
// the folder's lock would lose one entry, every time rather than by chance.
void hold_manifest_for_test() {
  static const int hold_ms = test_hook("XSHADE_TEST_BLESS_HOLDS_MANIFEST_MS");
  if (hold_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(hold_ms));
}

}  // namespace

GoldenStore::GoldenStore(std::filesystem::path folder, LockWaitNotice on_wait)
    : folder_(std::move(folder)), on_wait_(std::move(on_wait)) {}

std::filesystem::path GoldenStore::image_path(const std::string& scene, const std::optional<std::string>& lane) const {
  return lane && !lane->empty() ? folder_ / *lane / (scene + ".png") : folder_ / (scene + ".png");
}

std::vector<fs::path> GoldenStore::files_for(const std::string& scene, const std::string& lane) const {
  std::vector<fs::path> files;
  for (const fs::path& png : {image_path(scene, lane), image_path(scene, std::nullopt)}) {
    files.push_back(png);
    files.push_back(float_image_path(png));
  }
  return files;
}

Result<std::optional<GoldenImage>> GoldenStore::find(const std::string& scene, const std::string& lane) const {
  if (Result<void> valid = check_scene_name(scene); !valid) return fail(valid.error());
  if (!lane.empty())
    if (Result<void> valid = check_lane_name(lane); !valid) return fail(valid.error());
  std::error_code error;
  if (!fs::is_directory(folder_, error)) return std::optional<GoldenImage>();  // nothing was ever blessed here

  // Shared, so that a bless never commits between this reading the manifest and the image. What an
  // interrupted bless left is finished first, under the exclusive lock: the committed manifest
  // decides every leftover, so whoever finishes it does the same. A folder this process cannot
  // write is read as it is: the hash checks below still refuse any image the manifest did not commit.
  Result<GoldenLock> lock = GoldenLock::acquire(folder_, GoldenLock::Mode::Shared, on_wait_);
  if (!lock) return fail(lock.error());
  if (lock->held() && !find_leftovers(folder_).empty()) {
    if (Result<void> upgraded = lock->upgrade(on_wait_); !upgraded) return fail(upgraded.error());
    if (auto recovered = recover_golden_folder(folder_); !recovered) return fail(recovered.error());
  }
  Result<GoldenManifest> manifest = read_golden_manifest(manifest_path());
  if (!manifest) return fail(manifest.error());
  const bool has_manifest = fs::exists(manifest_path(), error);

  // The lane's own image first, then the common one; each must agree with the manifest.
  for (const std::string& candidate : {lane, std::string()}) {
    const fs::path path = image_path(scene, candidate);
    const fs::path float_path = float_image_path(path);
    const GoldenEntry* entry = manifest->find(scene, candidate);
    const bool present = fs::exists(path, error);
    const bool has_float = fs::exists(float_path, error);
    if (entry && !present)
      return fail(ErrorKind::UserInput,
                  fmt::format("the manifest records the golden {}, but {} does not exist",
                              golden_name(scene, candidate), path.string()),
                  entry->where);
    if (!present && !has_float) continue;
    // Every golden is checked against what bless recorded; one without an entry is never used.
    const fs::path& unlisted = present ? path : float_path;
    const std::optional<std::string> own = candidate.empty() ? std::nullopt : std::optional(candidate);
    if (!has_manifest)
      return fail(ErrorKind::UserInput,
                  fmt::format("{} is a golden, but {} does not exist, so no golden here can be checked: restore it "
                              "(it is committed with the goldens) or bless again with {}",
                              unlisted.string(), manifest_path().string(), bless_command(scene, own)));
    if (!entry && !candidate.empty())
      return fail(ErrorKind::UserInput,
                  fmt::format("{} has no entry in {}: a lane's own golden must say why the lane differs; bless it "
                              "with {} or remove it",
                              unlisted.string(), manifest_path().string(), bless_command(scene, candidate)));
    if (!entry)
      return fail(ErrorKind::UserInput,
                  fmt::format("{} has no entry in {}: a golden is trusted only as bless wrote it; bless it with {} or "
                              "remove it",
                              unlisted.string(), manifest_path().string(), bless_command(scene, std::nullopt)));
    if (Result<void> same = check_hash(path, *entry, entry->hash, bless_command(scene, own)); !same)
      return fail(same.error());
    // The float image where bless wrote one: the values above 1 that the PNG clamps.
    if (has_float && entry->float_hash.empty())
      return fail(ErrorKind::UserInput,
                  fmt::format("{} has no float_hash in {}: a golden's float image is trusted only as bless wrote it; "
                              "bless it with {} or remove it",
                              float_path.string(), manifest_path().string(), bless_command(scene, candidate)));
    if (!entry->float_hash.empty()) {
      if (!has_float)
        return fail(ErrorKind::UserInput,
                    fmt::format("the manifest records a float image for {}, but {} does not exist",
                                golden_name(scene, candidate), float_path.string()),
                    entry->where);
      if (Result<void> same = check_hash(float_path, *entry, entry->float_hash, bless_command(scene, own)); !same)
        return fail(same.error());
    }
    Result<FloatImage> image = read_image(has_float ? float_path : path);
    if (!image) return fail(image.error());
    return GoldenImage{has_float ? float_path : path, std::move(*image), !candidate.empty(), entry->reason};
  }
  return std::optional<GoldenImage>();
}

Result<BlessOutcome> GoldenStore::bless(const std::string& scene, const std::optional<std::string>& lane,
                                        const FloatImage& image, const std::string& reason,
                                        const std::string& who) const {
  if (blank(reason)) return fail(ErrorKind::Usage, "a golden is evidence: say why with --reason");
  if (blank(who)) return fail(ErrorKind::Internal, "a golden records who blessed it: the name is empty");
  if (Result<void> valid = check_scene_name(scene); !valid) return fail(valid.error());
  if (lane)
    if (Result<void> valid = check_lane_name(*lane); !valid) return fail(valid.error());
  if (image.width == 0 || image.height == 0)
    return fail(ErrorKind::Internal, fmt::format("cannot bless an empty image as the golden of {}", scene));

  BlessOutcome outcome;
  outcome.path = image_path(scene, lane);
  const fs::path folder = outcome.path.parent_path();
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) return fail(ErrorKind::Backend, fmt::format("cannot create {}: {}", folder.string(), error.message()));

  // Held from reading the manifest to the last rename: another bless waits, so that its entry
  // and this one both survive. Whatever an earlier bless left unfinished is finished first.
  Result<GoldenLock> lock = GoldenLock::acquire(folder_, GoldenLock::Mode::Exclusive, on_wait_);
  if (!lock) return fail(lock.error());
  if (auto recovered = recover_golden_folder(folder_); !recovered) return fail(recovered.error());
  // A manifest that cannot be read is not overwritten: its entries would be lost.
  Result<GoldenManifest> manifest = read_golden_manifest(manifest_path());
  if (!manifest) return fail(manifest.error());
  hold_manifest_for_test();
  if (fs::exists(outcome.path, error)) {
    outcome.replaced = true;
    if (Result<FloatImage> previous = read_image(outcome.path)) outcome.previous = std::move(*previous);
  }

  // The commit protocol of golden_transaction.h. Until step 4 renames the manifest, every change
  // is under a pending name that recovery deletes; after it, recovery renames what is left.
  const fs::path float_path = float_image_path(outcome.path);
  const fs::path image_pending = pending_path(outcome.path);
  const fs::path float_pending = pending_path(float_path);
  const fs::path manifest_pending = pending_manifest_path(folder_);
  const bool high = has_values_above_one(image);
  const bool remove_float = !high && fs::exists(float_path, error);
  const auto abandon = [&](const Error& why) {
    std::error_code ignored;
    for (const fs::path& path : {image_pending, float_pending, manifest_pending}) fs::remove(path, ignored);
    return fail(why);
  };
  const auto written_hash = [&](const fs::path& pending, bool exr) -> Result<std::string> {
    if (Result<void> written = exr ? write_exr(image, pending) : write_png(image, pending); !written)
      return fail(written.error());
    if (Result<void> synced = sync_file(pending); !synced) return fail(synced.error());
    std::optional<std::string> bytes = read_file(pending);
    if (!bytes) return fail(ErrorKind::Backend, "cannot read back " + pending.string());
    return content_hash(*bytes);
  };

  Result<std::string> png_hash = written_hash(image_pending, false);
  if (!png_hash) return abandon(png_hash.error());
  bless_step_done(1);
  // The float image, or the empty marker that says the committed golden has none.
  Result<std::string> float_hash = high ? written_hash(float_pending, true) : Result<std::string>(std::string());
  if (!float_hash) return abandon(float_hash.error());
  if (remove_float)
    if (Result<void> marked = write_synced(float_pending, ""); !marked) return abandon(marked.error());
  if (Result<void> synced = sync_folder(folder); !synced) return abandon(synced.error());
  bless_step_done(2);
  manifest->record(GoldenEntry{scene, lane.value_or(""), reason, who, utc_now_iso8601(), *png_hash, *float_hash, {}});
  if (Result<void> written = write_synced(manifest_pending, format_golden_manifest(*manifest)); !written)
    return abandon(written.error());
  bless_step_done(3);

  // The commit.
  fs::rename(manifest_pending, manifest_path(), error);
  if (error)
    return abandon(
        Error{fmt::format("cannot update {}: {}; nothing was blessed", manifest_path().string(), error.message()),
              {},
              {},
              ErrorKind::Backend});
  if (Result<void> synced = sync_folder(folder_); !synced) return fail(synced.error());
  bless_step_done(4);

  // Committed: a failure from here on is finished by the next run or bless, not undone.
  const auto unfinished = [&](const fs::path& path) {
    return fail(ErrorKind::Backend, fmt::format("blessed {} in {}, but cannot put {} in place: {}; the next xshade run "
                                                "or bless finishes it",
                                                golden_name(scene, lane.value_or("")), manifest_path().string(),
                                                path.string(), error.message()));
  };
  fs::rename(image_pending, outcome.path, error);
  if (error) return unfinished(outcome.path);
  bless_step_done(5);
  if (high) fs::rename(float_pending, float_path, error);
  if (remove_float) {
    fs::remove(float_path, error);
    if (!error) fs::remove(float_pending, error);
  }
  if (error) return unfinished(float_path);
  bless_step_done(6);
  if (Result<void> synced = sync_folder(folder); !synced) return fail(synced.error());
  bless_step_done(7);
  return outcome;
}

std::string GoldenStore::bless_command(const std::string& scene, const std::optional<std::string>& lane) {
  std::string command = "xshade bless " + scene;
  if (lane && !lane->empty()) command += " --lane " + *lane;
  return command + " --reason \"...\"";
}

std::string GoldenStore::missing_message(const std::string& scene, const std::string& lane) const {
  return fmt::format("no golden image for {} on {} (looked for {} and {}); create it with {}", scene, lane,
                     image_path(scene, lane).string(), image_path(scene, std::nullopt).string(),
                     bless_command(scene, std::nullopt));
}

}  // namespace xshade::harness
