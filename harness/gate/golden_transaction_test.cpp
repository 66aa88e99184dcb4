#include "harness/gate/golden_transaction.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "harness/render/shader_cache.h"

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using Kind = RecoveryAction::Kind;

// A golden folder written by hand in each state an interrupted bless can leave.
class GoldenTransactionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        fs::temp_directory_path() /
        ("xshade_transaction_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  void write(const fs::path& path, const std::string& bytes) const {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  }
  std::string read(const fs::path& path) const {
    std::ifstream file(path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    return bytes.str();
  }
  // The manifest with one entry for `scene` (on `lane`) whose image is `png` (and float image `exr`).
  void commit(const std::string& scene, const std::string& lane, const std::string& png, const std::string& exr = "") {
    GoldenManifest manifest;
    manifest.record({scene,
                     lane,
                     "why",
                     "ada",
                     "2024-05-01T12:34:56Z",
                     content_hash(png),
                     exr.empty() ? "" : content_hash(exr),
                     {}});
    write(folder_ / "MANIFEST.toml", format_golden_manifest(manifest));
  }
  std::vector<std::pair<Kind, std::string>> plan() const {
    auto manifest = read_golden_manifest(folder_ / "MANIFEST.toml");
    EXPECT_TRUE(manifest) << manifest.error().to_string();
    std::vector<std::pair<Kind, std::string>> actions;
    for (const RecoveryAction& action : plan_recovery(folder_, manifest ? *manifest : GoldenManifest{}))
      actions.emplace_back(action.kind, fs::relative(action.leftover, folder_).string());
    return actions;
  }

  fs::path folder_;
};

TEST_F(GoldenTransactionTest, APendingNameStartsWithADotSoNoSceneImageHasIt) {
  EXPECT_EQ(pending_path(folder_ / "vk" / "dof_off.png"), folder_ / "vk" / ".dof_off.pending.png");
  EXPECT_EQ(pending_path(folder_ / "dof_off.exr"), folder_ / ".dof_off.pending.exr");
  EXPECT_EQ(pending_manifest_path(folder_), folder_ / "MANIFEST.toml.pending");
}

TEST_F(GoldenTransactionTest, AFolderWithoutLeftoversNeedsNothing) {
  commit("dof_off", "", "old png");
  write(folder_ / "dof_off.png", "old png");
  write(folder_ / ".golden.lock", "");
  write(folder_ / "README.md", "goldens");
  EXPECT_TRUE(find_leftovers(folder_).empty());
  auto recovered = recover_golden_folder(folder_);
  ASSERT_TRUE(recovered) << recovered.error().to_string();
  EXPECT_TRUE(recovered->empty());
}

// Killed before the manifest was renamed: the manifest still records the old image, so every
// pending file is from a bless that never happened.
TEST_F(GoldenTransactionTest, BeforeTheCommitEverythingPendingIsDiscarded) {
  commit("dof_off", "", "old png", "old exr");
  write(folder_ / "dof_off.png", "old png");
  write(folder_ / "dof_off.exr", "old exr");
  write(folder_ / ".dof_off.pending.png", "new png");
  write(folder_ / ".dof_off.pending.exr", "");  // the new golden would have had no float image
  write(folder_ / "MANIFEST.toml.pending", "the new manifest");
  write(folder_ / "MANIFEST.toml.tmp.4242", "what bless wrote before it had pending names");
  write(folder_ / "gl" / ".dof_off.pending.png", "a lane's new png");
  EXPECT_EQ(plan(), (std::vector<std::pair<Kind, std::string>>{{Kind::Discard, ".dof_off.pending.exr"},
                                                               {Kind::Discard, ".dof_off.pending.png"},
                                                               {Kind::Discard, "MANIFEST.toml.pending"},
                                                               {Kind::Discard, "MANIFEST.toml.tmp.4242"},
                                                               {Kind::Discard, "gl/.dof_off.pending.png"}}));
  const std::string manifest = read(folder_ / "MANIFEST.toml");
  auto recovered = recover_golden_folder(folder_);
  ASSERT_TRUE(recovered) << recovered.error().to_string();
  EXPECT_EQ(recovered->size(), 5u);
  EXPECT_TRUE(find_leftovers(folder_).empty());
  EXPECT_EQ(read(folder_ / "dof_off.png"), "old png");
  EXPECT_EQ(read(folder_ / "dof_off.exr"), "old exr");
  EXPECT_EQ(read(folder_ / "MANIFEST.toml"), manifest);
}

// Killed after the manifest was renamed: the pending files it records are the golden now.
TEST_F(GoldenTransactionTest, AfterTheCommitWhatTheManifestRecordsIsRolledForward) {
  commit("dof_off", "vk", "new png", "new exr");
  write(folder_ / "vk" / "dof_off.png", "old png");
  write(folder_ / "vk" / ".dof_off.pending.png", "new png");
  write(folder_ / "vk" / ".dof_off.pending.exr", "new exr");
  write(folder_ / "vk" / ".other.pending.png", "no entry records this");
  EXPECT_EQ(plan(), (std::vector<std::pair<Kind, std::string>>{{Kind::RollForward, "vk/.dof_off.pending.exr"},
                                                               {Kind::RollForward, "vk/.dof_off.pending.png"},
                                                               {Kind::Discard, "vk/.other.pending.png"}}));
  auto recovered = recover_golden_folder(folder_);
  ASSERT_TRUE(recovered) << recovered.error().to_string();
  EXPECT_TRUE(find_leftovers(folder_).empty());
  EXPECT_EQ(read(folder_ / "vk" / "dof_off.png"), "new png");
  EXPECT_EQ(read(folder_ / "vk" / "dof_off.exr"), "new exr");
  EXPECT_FALSE(fs::exists(folder_ / "vk" / "other.png"));
}

// A pending image whose bytes are not the manifest's is never installed, whatever its name.
TEST_F(GoldenTransactionTest, APendingImageThatIsNotTheCommittedOneIsDiscarded) {
  commit("dof_off", "", "new png");
  write(folder_ / "dof_off.png", "new png");
  write(folder_ / ".dof_off.pending.png", "something else");
  write(folder_ / ".dof_off.pending.exr", "a float image the manifest does not record");
  EXPECT_EQ(plan(), (std::vector<std::pair<Kind, std::string>>{{Kind::Discard, ".dof_off.pending.exr"},
                                                               {Kind::Discard, ".dof_off.pending.png"}}));
}

// The committed golden has no float image: the old one goes, as bless would have removed it.
TEST_F(GoldenTransactionTest, AfterTheCommitAFloatImageMarkedForRemovalIsRemoved) {
  commit("dof_off", "", "new png");
  write(folder_ / "dof_off.png", "new png");
  write(folder_ / "dof_off.exr", "old exr");
  write(folder_ / ".dof_off.pending.exr", "");
  EXPECT_EQ(plan(), (std::vector<std::pair<Kind, std::string>>{{Kind::FinishRemoval, ".dof_off.pending.exr"}}));
  auto recovered = recover_golden_folder(folder_);
  ASSERT_TRUE(recovered) << recovered.error().to_string();
  EXPECT_FALSE(fs::exists(folder_ / "dof_off.exr"));
  EXPECT_TRUE(find_leftovers(folder_).empty());
}

// A removal marker for a scene the manifest does not know removes nothing.
TEST_F(GoldenTransactionTest, AMarkerForAnUnknownSceneRemovesNothing) {
  commit("dof_off", "", "png");
  write(folder_ / "toon.exr", "someone's file");
  write(folder_ / ".toon.pending.exr", "");
  EXPECT_EQ(plan(), (std::vector<std::pair<Kind, std::string>>{{Kind::Discard, ".toon.pending.exr"}}));
  ASSERT_TRUE(recover_golden_folder(folder_));
  EXPECT_EQ(read(folder_ / "toon.exr"), "someone's file");
}

TEST_F(GoldenTransactionTest, AnUnreadableManifestTouchesNothing) {
  write(folder_ / "MANIFEST.toml", "[[golden]\n");
  write(folder_ / ".dof_off.pending.png", "new png");
  auto recovered = recover_golden_folder(folder_);
  ASSERT_FALSE(recovered);
  EXPECT_NE(recovered.error().to_string().find("syntax error"), std::string::npos) << recovered.error().to_string();
  EXPECT_TRUE(fs::exists(folder_ / ".dof_off.pending.png"));
}

TEST_F(GoldenTransactionTest, WriteSyncedWritesTheBytes) {
  ASSERT_TRUE(write_synced(folder_ / "file", "bytes"));
  EXPECT_EQ(read(folder_ / "file"), "bytes");
  ASSERT_TRUE(sync_folder(folder_));
  EXPECT_FALSE(write_synced(folder_ / "no such folder" / "file", "bytes"));
}

}  // namespace
}  // namespace xshade::harness
