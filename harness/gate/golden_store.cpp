#include "harness/gate/golden_store.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "base/file_io.h"
#include "harness/gate/golden_manifest.h"
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
    return fail(fmt::format("'{}' is not a scene name", scene));
  return {};
}

Result<void> check_lane_name(const std::string& lane) {
  if (!parse_lane(lane)) return fail(fmt::format("unknown lane '{}' (lanes: gl, vk, vk-hlsl)", lane));
  return {};
}

Result<void> write_bytes(const fs::path& path, std::string_view bytes) {
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (file) file.write(bytes.data(), std::streamsize(bytes.size()));
  file.close();
  if (!file) return fail("cannot write " + path.string());
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

// A golden whose bytes differ from what bless recorded was written by something else.
Result<void> check_hash(const fs::path& path, const GoldenEntry& entry, const std::string& hash) {
  if (hash.empty()) return {};
  std::optional<std::string> bytes = read_file(path);
  if (!bytes) return fail("cannot read image " + path.string());
  if (content_hash(*bytes) != hash)
    return fail(fmt::format("{} is not the image blessed on {} (its hash differs from the manifest's): only "
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

// Removes what a failed bless left behind; the originals are untouched until the renames.
void remove_temporaries(const std::vector<fs::path>& paths) {
  std::error_code ignored;
  for (const fs::path& path : paths) fs::remove(path, ignored);
}

}  // namespace

GoldenStore::GoldenStore(std::filesystem::path folder) : folder_(std::move(folder)) {}

std::filesystem::path GoldenStore::image_path(const std::string& scene, const std::optional<std::string>& lane) const {
  return lane && !lane->empty() ? folder_ / *lane / (scene + ".png") : folder_ / (scene + ".png");
}

Result<std::optional<GoldenImage>> GoldenStore::find(const std::string& scene, const std::string& lane) const {
  if (Result<void> valid = check_scene_name(scene); !valid) return fail(valid.error());
  if (!lane.empty())
    if (Result<void> valid = check_lane_name(lane); !valid) return fail(valid.error());
  Result<GoldenManifest> manifest = read_golden_manifest(manifest_path());
  if (!manifest) return fail(manifest.error());

  // The lane's own image first, then the common one; each must agree with the manifest.
  for (const std::string& candidate : {lane, std::string()}) {
    const fs::path path = image_path(scene, candidate);
    const GoldenEntry* entry = manifest->find(scene, candidate);
    std::error_code error;
    const bool present = fs::exists(path, error);
    if (entry && !present)
      return fail(fmt::format("the manifest records the golden {}, but {} does not exist",
                              golden_name(scene, candidate), path.string()),
                  entry->where);
    if (!present) continue;
    if (!candidate.empty() && !entry)
      return fail(fmt::format("{} has no entry in {}: a lane's own golden must say why the lane differs; bless it "
                              "with {} or remove it",
                              path.string(), manifest_path().string(), bless_command(scene, candidate)));
    if (entry)
      if (Result<void> same = check_hash(path, *entry, entry->hash); !same) return fail(same.error());
    // The float image where bless wrote one: the values above 1 that the PNG clamps.
    const fs::path float_path = float_image_path(path);
    const bool has_float = fs::exists(float_path, error);
    if (has_float && !(entry && !entry->float_hash.empty()))
      return fail(fmt::format("{} has no float_hash in {}: a golden's float image is trusted only as bless wrote it; "
                              "bless it with {} or remove it",
                              float_path.string(), manifest_path().string(), bless_command(scene, candidate)));
    if (entry && !entry->float_hash.empty()) {
      if (!has_float)
        return fail(fmt::format("the manifest records a float image for {}, but {} does not exist",
                                golden_name(scene, candidate), float_path.string()),
                    entry->where);
      if (Result<void> same = check_hash(float_path, *entry, entry->float_hash); !same) return fail(same.error());
    }
    Result<FloatImage> image = read_image(has_float ? float_path : path);
    if (!image) return fail(image.error());
    return GoldenImage{has_float ? float_path : path, std::move(*image), !candidate.empty(),
                       entry ? entry->reason : std::string()};
  }
  return std::optional<GoldenImage>();
}

Result<BlessOutcome> GoldenStore::bless(const std::string& scene, const std::optional<std::string>& lane,
                                        const FloatImage& image, const std::string& reason,
                                        const std::string& who) const {
  if (blank(reason)) return fail("a golden is evidence: say why with --reason");
  if (blank(who)) return fail("a golden records who blessed it: the name is empty");
  if (Result<void> valid = check_scene_name(scene); !valid) return fail(valid.error());
  if (lane)
    if (Result<void> valid = check_lane_name(*lane); !valid) return fail(valid.error());
  if (image.width == 0 || image.height == 0)
    return fail(fmt::format("cannot bless an empty image as the golden of {}", scene));
  // A manifest that cannot be read is not overwritten: its entries would be lost.
  Result<GoldenManifest> manifest = read_golden_manifest(manifest_path());
  if (!manifest) return fail(manifest.error());

  BlessOutcome outcome;
  outcome.path = image_path(scene, lane);
  const fs::path folder = outcome.path.parent_path();
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) return fail(fmt::format("cannot create {}: {}", folder.string(), error.message()));
  if (fs::exists(outcome.path, error)) {
    outcome.replaced = true;
    if (Result<FloatImage> previous = read_image(outcome.path)) outcome.previous = std::move(*previous);
  }

  // Every file is written in full beside its destination before any is renamed into place, so a
  // failure leaves the old golden and manifest as they were. The images' temporaries keep their
  // extensions because OpenImageIO chooses the format by them. A render with a value above 1
  // also gets its float image, which the gate compares.
  const std::string pid = std::to_string(::getpid());
  const fs::path image_temporary = folder / (scene + ".tmp." + pid + ".png");
  const fs::path float_temporary = folder / (scene + ".tmp." + pid + ".exr");
  const fs::path manifest_temporary = manifest_path().string() + ".tmp." + pid;
  const std::vector<fs::path> temporaries{image_temporary, float_temporary, manifest_temporary};
  const bool high = has_values_above_one(image);
  const auto written_hash = [&](const fs::path& temporary, bool exr) -> Result<std::string> {
    if (Result<void> written = exr ? write_exr(image, temporary) : write_png(image, temporary); !written)
      return fail(written.error());
    std::optional<std::string> bytes = read_file(temporary);
    if (!bytes) return fail("cannot read back " + temporary.string());
    return content_hash(*bytes);
  };
  Result<std::string> png_hash = written_hash(image_temporary, false);
  Result<std::string> float_hash = high ? written_hash(float_temporary, true) : Result<std::string>(std::string());
  if (!png_hash || !float_hash) {
    remove_temporaries(temporaries);
    return fail(!png_hash ? png_hash.error() : float_hash.error());
  }
  manifest->record(
      GoldenEntry{scene, lane.value_or(""), reason, who, utc_now_iso8601(), *png_hash, *float_hash, {}});
  if (Result<void> written = write_bytes(manifest_temporary, format_golden_manifest(*manifest)); !written) {
    remove_temporaries(temporaries);
    return fail(written.error());
  }

  const fs::path float_path = float_image_path(outcome.path);
  fs::rename(image_temporary, outcome.path, error);
  if (!error) {
    if (high) fs::rename(float_temporary, float_path, error);
    else fs::remove(float_path, error);  // an earlier bless's float image, which no longer applies
  }
  if (error) {
    remove_temporaries(temporaries);
    return fail(fmt::format("cannot write {}: {}", outcome.path.string(), error.message()));
  }
  fs::rename(manifest_temporary, manifest_path(), error);
  if (error) {
    remove_temporaries({manifest_temporary});
    return fail(fmt::format("wrote {} but cannot update {}: {}; bless it again", outcome.path.string(),
                            manifest_path().string(), error.message()));
  }
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
