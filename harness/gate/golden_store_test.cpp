#include "harness/gate/golden_store.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "harness/gate/golden_manifest.h"
#include "harness/gate/golden_transaction.h"
#include "harness/image/image_io.h"
#include "harness/render/shader_cache.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::StartsWith;

// A 3x2 image of one colour whose channels are exact 8-bit sRGB codes, so that it survives the
// PNG round trip bit for bit.
FloatImage solid(uint8_t red, uint8_t green, uint8_t blue) {
  FloatImage image(3, 2);
  for (uint32_t y = 0; y < image.height; ++y)
    for (uint32_t x = 0; x < image.width; ++x)
      image.set(x, y, {srgb8_to_linear(red), srgb8_to_linear(green), srgb8_to_linear(blue), 1.0f});
  return image;
}

// A fresh golden folder per test.
class GoldenStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("xshade_golden_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  void write(const std::string& name, const std::string& text) const {
    fs::create_directories((folder_ / name).parent_path());
    std::ofstream(folder_ / name, std::ios::binary) << text;
  }
  std::string read(const std::string& name) const {
    std::ifstream file(folder_ / name, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
  }
  // Every file under the folder with its contents: what "unchanged" means.
  std::set<std::pair<std::string, std::string>> snapshot() const {
    std::set<std::pair<std::string, std::string>> files;
    for (const auto& item : fs::recursive_directory_iterator(folder_))
      if (item.is_regular_file()) {
        const std::string name = fs::relative(item.path(), folder_).string();
        files.emplace(name, read(name));
      }
    return files;
  }
  GoldenManifest manifest() const {
    auto manifest = read_golden_manifest(folder_ / "MANIFEST.toml");
    EXPECT_TRUE(manifest) << manifest.error().to_string();
    return manifest ? *manifest : GoldenManifest{};
  }
  void bless(const std::string& scene, std::optional<std::string> lane, const FloatImage& image,
             const std::string& reason) const {
    auto blessed = GoldenStore(folder_).bless(scene, lane, image, reason, "ada");
    ASSERT_TRUE(blessed) << blessed.error().to_string();
  }

  fs::path folder_;
};

TEST_F(GoldenStoreTest, AMissingGoldenIsNoneAndTheMessageNamesTheCommandThatCreatesIt) {
  GoldenStore store(folder_);
  auto found = store.find("material_grid", "vk");
  ASSERT_TRUE(found) << found.error().to_string();
  EXPECT_FALSE(found->has_value());
  EXPECT_EQ(store.missing_message("material_grid", "vk"),
            "no golden image for material_grid on vk (looked for " + (folder_ / "vk" / "material_grid.png").string() +
                " and " + (folder_ / "material_grid.png").string() +
                "); create it with xshade bless material_grid --reason \"...\"");
  EXPECT_EQ(GoldenStore::bless_command("material_grid", std::nullopt), "xshade bless material_grid --reason \"...\"");
  EXPECT_EQ(GoldenStore::bless_command("material_grid", "vk-hlsl"),
            "xshade bless material_grid --lane vk-hlsl --reason \"...\"");
}

TEST_F(GoldenStoreTest, ACommonGoldenServesEveryLane) {
  const FloatImage grey = solid(128, 128, 128);
  auto blessed = GoldenStore(folder_).bless("material_grid", std::nullopt, grey, "first render", "ada");
  ASSERT_TRUE(blessed) << blessed.error().to_string();
  EXPECT_EQ(blessed->path, folder_ / "material_grid.png");
  EXPECT_FALSE(blessed->replaced);
  EXPECT_FALSE(blessed->previous);

  for (const std::string lane : {"gl", "vk", "vk-hlsl"}) {
    auto found = GoldenStore(folder_).find("material_grid", lane);
    ASSERT_TRUE(found) << found.error().to_string();
    ASSERT_TRUE(found->has_value()) << lane;
    EXPECT_EQ((*found)->path, folder_ / "material_grid.png");
    EXPECT_FALSE((*found)->lane_specific);
    EXPECT_EQ((*found)->reason, "first render");
    EXPECT_TRUE(bitwise_equal((*found)->image, grey));
  }

  const GoldenManifest recorded = manifest();
  ASSERT_EQ(recorded.entries.size(), 1u);
  const GoldenEntry& entry = recorded.entries[0];
  EXPECT_EQ(entry.scene, "material_grid");
  EXPECT_EQ(entry.lane, "");
  EXPECT_EQ(entry.reason, "first render");
  EXPECT_EQ(entry.blessed_by, "ada");
  EXPECT_THAT(entry.date, MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z"));
  EXPECT_THAT(entry.hash, MatchesRegex("[0-9a-f]{32}"));
}

TEST_F(GoldenStoreTest, ALaneGoldenServesItsLaneAndTheOthersKeepTheCommonOne) {
  const FloatImage grey = solid(128, 128, 128);
  const FloatImage darker = solid(120, 128, 128);
  bless("dof_off", std::nullopt, grey, "first render");
  bless("dof_off", "vk-hlsl", darker, "glslang's HLSL front end rounds the CoC differently");

  auto own = GoldenStore(folder_).find("dof_off", "vk-hlsl");
  ASSERT_TRUE(own) << own.error().to_string();
  ASSERT_TRUE(own->has_value());
  EXPECT_EQ((*own)->path, folder_ / "vk-hlsl" / "dof_off.png");
  EXPECT_TRUE((*own)->lane_specific);
  EXPECT_EQ((*own)->reason, "glslang's HLSL front end rounds the CoC differently");
  EXPECT_TRUE(bitwise_equal((*own)->image, darker));

  for (const std::string lane : {"gl", "vk"}) {
    auto common = GoldenStore(folder_).find("dof_off", lane);
    ASSERT_TRUE(common) << common.error().to_string();
    ASSERT_TRUE(common->has_value());
    EXPECT_EQ((*common)->path, folder_ / "dof_off.png");
    EXPECT_FALSE((*common)->lane_specific);
    EXPECT_TRUE(bitwise_equal((*common)->image, grey));
  }
}

TEST_F(GoldenStoreTest, AValueAboveOneIsKeptInAFloatImageThatIsWhatFindReturns) {
  FloatImage image = solid(128, 128, 128);
  image.set(1, 1, {1.85f, 0.5f, 0.25f, 1.0f});
  bless("material_grid", std::nullopt, image, "a highlight above 1");
  EXPECT_TRUE(fs::exists(folder_ / "material_grid.png"));
  ASSERT_TRUE(fs::exists(folder_ / "material_grid.exr"));
  const GoldenEntry* entry = manifest().find("material_grid", "");
  ASSERT_TRUE(entry);
  EXPECT_EQ(entry->float_hash.size(), 32u);
  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_TRUE(found && *found) << (found ? "none" : found.error().to_string());
  EXPECT_EQ((*found)->path, folder_ / "material_grid.exr");
  EXPECT_EQ((*found)->image.at(1, 1).r, 1.85f);  // the PNG would say 1

  // Blessed again without a value above 1, the float image goes: the PNG holds everything.
  bless("material_grid", std::nullopt, solid(128, 128, 128), "the highlight is gone");
  EXPECT_FALSE(fs::exists(folder_ / "material_grid.exr"));
  EXPECT_TRUE(manifest().find("material_grid", "")->float_hash.empty());

  // A float image the manifest does not record is not trusted.
  ASSERT_TRUE(write_exr(image, folder_ / "material_grid.exr"));
  auto untrusted = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_FALSE(untrusted);
  EXPECT_NE(untrusted.error().message.find("has no float_hash"), std::string::npos) << untrusted.error().message;
}

TEST_F(GoldenStoreTest, ALaneGoldenWithoutAManifestEntryIsNotTrusted) {
  bless("dof_off", std::nullopt, solid(128, 128, 128), "first render");
  fs::create_directories(folder_ / "vk");
  ASSERT_TRUE(write_png(solid(1, 2, 3), folder_ / "vk" / "dof_off.png"));

  auto found = GoldenStore(folder_).find("dof_off", "vk");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(),
            (folder_ / "vk" / "dof_off.png").string() + " has no entry in " + (folder_ / "MANIFEST.toml").string() +
                ": a lane's own golden must say why the lane differs; bless it with xshade bless dof_off --lane vk "
                "--reason \"...\" or remove it");
  // The other lanes do not look at vk's folder.
  auto gl = GoldenStore(folder_).find("dof_off", "gl");
  ASSERT_TRUE(gl) << gl.error().to_string();
  EXPECT_TRUE(gl->has_value());
}

TEST_F(GoldenStoreTest, AManifestEntryWhoseImageIsMissingIsAnError) {
  bless("dof_off", "gl", solid(128, 128, 128), "llvmpipe filters the far plane in linear space");
  fs::remove(folder_ / "gl" / "dof_off.png");

  auto found = GoldenStore(folder_).find("dof_off", "gl");
  ASSERT_FALSE(found);
  // The header comment is 12 lines and a blank one; the entry starts on line 14.
  EXPECT_EQ(found.error().to_string(), (folder_ / "MANIFEST.toml").string() +
                                           ":16:1: the manifest records the golden gl/dof_off, but " +
                                           (folder_ / "gl" / "dof_off.png").string() + " does not exist");
}

TEST_F(GoldenStoreTest, ABlankReasonIsRefusedAndNothingIsWritten) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  const auto before = snapshot();

  for (const std::string reason : {"", "  \t\n"}) {
    for (const std::optional<std::string>& lane : {std::optional<std::string>(), std::optional<std::string>("vk")}) {
      auto blessed = GoldenStore(folder_).bless("material_grid", lane, solid(9, 9, 9), reason, "ada");
      ASSERT_FALSE(blessed);
      EXPECT_EQ(blessed.error().to_string(), "a golden is evidence: say why with --reason");
      EXPECT_EQ(blessed.error().kind, ErrorKind::Usage);  // the command line's: bless exits 2
      EXPECT_EQ(snapshot(), before);
    }
  }
  auto nameless = GoldenStore(folder_).bless("material_grid", std::nullopt, solid(9, 9, 9), "why", " ");
  ASSERT_FALSE(nameless);
  EXPECT_EQ(nameless.error().to_string(), "a golden records who blessed it: the name is empty");
  // bless always names someone ("unknown" at worst): an empty name is xshade's bug, exit 3.
  EXPECT_EQ(nameless.error().kind, ErrorKind::Internal);
  EXPECT_EQ(snapshot(), before);
}

TEST_F(GoldenStoreTest, BlessingReplacesAnOldGoldenAndLeavesNoTemporaryFiles) {
  const FloatImage old_image = solid(128, 128, 128);
  const FloatImage new_image = solid(200, 10, 30);
  bless("material_grid", std::nullopt, old_image, "first render");
  bless("material_grid", "vk", old_image, "lavapipe's derivatives differ at triangle edges");

  for (const std::optional<std::string>& lane : {std::optional<std::string>(), std::optional<std::string>("vk")}) {
    auto blessed = GoldenStore(folder_).bless("material_grid", lane, new_image, "brighter light", "grace");
    ASSERT_TRUE(blessed) << blessed.error().to_string();
    EXPECT_TRUE(blessed->replaced);
    ASSERT_TRUE(blessed->previous);
    EXPECT_TRUE(bitwise_equal(*blessed->previous, old_image));
    auto reread = read_image(blessed->path);
    ASSERT_TRUE(reread) << reread.error().to_string();
    EXPECT_TRUE(bitwise_equal(*reread, new_image));
  }

  for (const auto& [name, contents] : snapshot()) EXPECT_THAT(name, ::testing::Not(HasSubstr(".pending"))) << name;
  // MANIFEST.toml, material_grid.png, vk/material_grid.png and the folder's lock file.
  EXPECT_EQ(snapshot().size(), 4u);
}

TEST_F(GoldenStoreTest, BlessingAgainReplacesTheManifestEntry) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  bless("material_grid", "vk", solid(128, 128, 128), "lavapipe rounds differently");
  bless("material_grid", std::nullopt, solid(130, 128, 128), "warmer light");
  bless("material_grid", "vk", solid(130, 128, 128), "lavapipe still rounds differently");

  const GoldenManifest recorded = manifest();
  ASSERT_EQ(recorded.entries.size(), 2u);
  EXPECT_EQ(recorded.entries[0].lane, "");
  EXPECT_EQ(recorded.entries[0].reason, "warmer light");
  EXPECT_EQ(recorded.entries[1].lane, "vk");
  EXPECT_EQ(recorded.entries[1].reason, "lavapipe still rounds differently");
  const std::string text = read("MANIFEST.toml");
  size_t entries = 0;
  for (size_t at = text.find("\n[[golden]]\n"); at != std::string::npos; at = text.find("\n[[golden]]\n", at + 1))
    ++entries;
  EXPECT_EQ(entries, 2u);
}

TEST_F(GoldenStoreTest, TheManifestIsSortedBySceneThenLane) {
  bless("toon", std::nullopt, solid(1, 1, 1), "a");
  bless("dof_off", "vk", solid(1, 1, 1), "b");
  bless("dof_off", "gl", solid(1, 1, 1), "c");
  bless("dof_off", std::nullopt, solid(1, 1, 1), "d");

  std::vector<std::string> order;
  for (const GoldenEntry& entry : manifest().entries) order.push_back(entry.scene + "/" + entry.lane);
  EXPECT_EQ(order, (std::vector<std::string>{"dof_off/", "dof_off/gl", "dof_off/vk", "toon/"}));
}

// Bytes the manifest vouches for that are still not an image (written by hand, hash and all).
TEST_F(GoldenStoreTest, ACorruptImageIsAnErrorNamingTheFile) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  const std::string corrupt = "\x89PNG\r\n\x1a\n this is not the rest of a PNG";
  write("material_grid.png", corrupt);
  GoldenManifest edited = manifest();
  edited.entries.at(0).hash = content_hash(corrupt);
  write("MANIFEST.toml", format_golden_manifest(edited));
  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_FALSE(found);
  EXPECT_THAT(found.error().to_string(), StartsWith("cannot read image " + (folder_ / "material_grid.png").string()));
}

TEST_F(GoldenStoreTest, AGoldenChangedWithoutBlessingIsAnError) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  const std::string date = manifest().entries.at(0).date;
  ASSERT_TRUE(write_png(solid(129, 128, 128), folder_ / "material_grid.png"));

  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(), (folder_ / "MANIFEST.toml").string() +
                                           ":16:1: " + (folder_ / "material_grid.png").string() +
                                           " is not the image blessed on " + date +
                                           " (its hash differs from the manifest's): only `xshade bless` may "
                                           "change a golden");
}

TEST_F(GoldenStoreTest, AMalformedManifestIsAnErrorWithItsLineAndColumnAndIsNotOverwritten) {
  write("MANIFEST.toml", "# goldens\n[[golden]]\nscene = \"material_grid\"\nreason = why\n");
  const auto before = snapshot();

  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_FALSE(found);
  EXPECT_THAT(found.error().to_string(), StartsWith((folder_ / "MANIFEST.toml").string() + ":4:10: syntax error: "));

  auto blessed = GoldenStore(folder_).bless("material_grid", std::nullopt, solid(1, 1, 1), "why", "ada");
  ASSERT_FALSE(blessed);
  EXPECT_THAT(blessed.error().to_string(), StartsWith((folder_ / "MANIFEST.toml").string() + ":4:10: syntax error: "));
  auto after = snapshot();
  after.erase({".golden.lock", ""});  // the lock bless took to read the manifest
  EXPECT_EQ(after, before);
}

TEST_F(GoldenStoreTest, NamesThatAreNotScenesOrLanesAreRefused) {
  GoldenStore store(folder_);
  auto outside = store.bless("../escape", std::nullopt, solid(1, 1, 1), "why", "ada");
  ASSERT_FALSE(outside);
  EXPECT_EQ(outside.error().to_string(), "'../escape' is not a scene name");
  auto lane = store.bless("material_grid", "dx12", solid(1, 1, 1), "why", "ada");
  ASSERT_FALSE(lane);
  EXPECT_EQ(lane.error().to_string(), "unknown lane 'dx12' (lanes: gl, vk, vk-hlsl)");
  auto found = store.find("material_grid", "metal");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(), "unknown lane 'metal' (lanes: gl, vk, vk-hlsl)");
  EXPECT_TRUE(fs::is_empty(folder_));
}

TEST_F(GoldenStoreTest, ACommonGoldenWithoutAnEntryIsAnErrorNamingTheBlessCommand) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  ASSERT_TRUE(write_png(solid(1, 2, 3), folder_ / "toon.png"));
  auto found = GoldenStore(folder_).find("toon", "gl");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(),
            (folder_ / "toon.png").string() + " has no entry in " + (folder_ / "MANIFEST.toml").string() +
                ": a golden is trusted only as bless wrote it; bless it with xshade bless toon --reason \"...\" or "
                "remove it");
  // A float image alone is a golden too.
  fs::remove(folder_ / "toon.png");
  ASSERT_TRUE(write_exr(solid(1, 2, 3), folder_ / "toon.exr"));
  auto alone = GoldenStore(folder_).find("toon", "gl");
  ASSERT_FALSE(alone);
  EXPECT_THAT(alone.error().to_string(), StartsWith((folder_ / "toon.exr").string() + " has no entry in "));
}

TEST_F(GoldenStoreTest, AMissingManifestBesideImagesIsAnErrorNotAnUncheckedGolden) {
  bless("material_grid", "vk", solid(128, 128, 128), "lavapipe rounds differently");
  fs::remove(folder_ / "MANIFEST.toml");
  auto found = GoldenStore(folder_).find("material_grid", "vk");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(),
            (folder_ / "vk" / "material_grid.png").string() + " is a golden, but " +
                (folder_ / "MANIFEST.toml").string() +
                " does not exist, so no golden here can be checked: restore it (it is committed with the goldens) or "
                "bless again with xshade bless material_grid --lane vk --reason \"...\"");
}

TEST_F(GoldenStoreTest, AnEntryWithoutItsHashIsAnErrorNotAnUncheckedGolden) {
  bless("material_grid", std::nullopt, solid(128, 128, 128), "first render");
  std::string text = read("MANIFEST.toml");
  const size_t hash = text.find("\nhash = ");
  ASSERT_NE(hash, std::string::npos);
  text.erase(hash + 1, text.find('\n', hash + 1) - hash);
  write("MANIFEST.toml", text);
  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().to_string(),
            (folder_ / "MANIFEST.toml").string() + ":16:1: the manifest records no hash for " +
                (folder_ / "material_grid.png").string() +
                ", so it cannot be checked: bless it again with xshade bless material_grid --reason \"...\"");
  // Blessing again, as the message says, repairs it.
  bless("material_grid", std::nullopt, solid(128, 128, 128), "the hash was lost");
  auto repaired = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_TRUE(repaired && *repaired) << (repaired ? "none" : repaired.error().to_string());
}

// What a bless killed before its commit left is removed by the next reader, which sees the old golden.
TEST_F(GoldenStoreTest, AReaderDiscardsWhatABlessLeftBeforeItsCommit) {
  const FloatImage old_image = solid(128, 128, 128);
  bless("material_grid", std::nullopt, old_image, "first render");
  const auto before = snapshot();
  ASSERT_TRUE(write_png(solid(9, 9, 9), pending_path(folder_ / "material_grid.png")));
  write("MANIFEST.toml.pending", "the manifest that was never renamed");

  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_TRUE(found && *found) << (found ? "none" : found.error().to_string());
  EXPECT_TRUE(bitwise_equal((*found)->image, old_image));
  EXPECT_EQ(snapshot(), before);
}

// A bless killed after its commit: the manifest records the new image, still under its pending
// name; the reader finishes the rename and uses it.
TEST_F(GoldenStoreTest, AReaderFinishesWhatABlessLeftAfterItsCommit) {
  FloatImage high = solid(128, 128, 128);
  high.set(0, 0, {2.5f, 0.5f, 0.5f, 1.0f});
  bless("material_grid", "gl", high, "a highlight");
  const FloatImage new_image = solid(10, 20, 30);
  const fs::path png = folder_ / "gl" / "material_grid.png";
  ASSERT_TRUE(write_png(new_image, pending_path(png)));
  write("gl/.material_grid.pending.exr", "");  // the new golden has no float image
  GoldenManifest committed = manifest();
  committed.entries.at(0).hash = content_hash(read("gl/.material_grid.pending.png"));
  committed.entries.at(0).float_hash.clear();
  write("MANIFEST.toml", format_golden_manifest(committed));

  auto found = GoldenStore(folder_).find("material_grid", "gl");
  ASSERT_TRUE(found && *found) << (found ? "none" : found.error().to_string());
  EXPECT_EQ((*found)->path, png);
  EXPECT_TRUE(bitwise_equal((*found)->image, new_image));
  EXPECT_FALSE(fs::exists(folder_ / "gl" / "material_grid.exr"));
  EXPECT_TRUE(find_leftovers(folder_).empty());
}

// The steps bless commits in are the ones recovery knows: after a bless nothing is pending,
// including the float image of a golden that no longer has one.
TEST_F(GoldenStoreTest, BlessingLeavesNothingPendingWithOrWithoutAFloatImage) {
  FloatImage high = solid(128, 128, 128);
  high.set(0, 0, {2.5f, 0.5f, 0.5f, 1.0f});
  bless("material_grid", std::nullopt, high, "a highlight");
  EXPECT_TRUE(find_leftovers(folder_).empty());
  bless("material_grid", std::nullopt, solid(128, 128, 128), "no highlight");
  EXPECT_TRUE(find_leftovers(folder_).empty());
  EXPECT_FALSE(fs::exists(folder_ / "material_grid.exr"));
}

// What a watcher waits on for a scene's lane: every file find() could read, there or not.
TEST_F(GoldenStoreTest, TheFilesForALaneAreItsOwnAndTheCommonImages) {
  GoldenStore store(folder_);
  EXPECT_EQ(store.files_for("toon", "vk"),
            (std::vector<fs::path>{folder_ / "vk" / "toon.png", folder_ / "vk" / "toon.exr", folder_ / "toon.png",
                                   folder_ / "toon.exr"}));
}

}  // namespace
}  // namespace xshade::harness
