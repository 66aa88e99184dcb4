#include "harness/gate/golden_lock.h"

#include <atomic>
#include <filesystem>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using Mode = GoldenLock::Mode;

class GoldenLockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              ("xshade_lock_test_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  fs::path folder_;
};

// Each acquire opens the file anew, so two in one process conflict as two processes would.
TEST_F(GoldenLockTest, ASecondExclusiveLockWaitsAndSaysSo) {
  auto acquired = GoldenLock::acquire(folder_, Mode::Exclusive);
  ASSERT_TRUE(acquired) << acquired.error().to_string();
  std::optional<GoldenLock> first(std::move(*acquired));
  EXPECT_TRUE(first->held());
  EXPECT_TRUE(fs::exists(folder_ / ".golden.lock"));

  std::atomic<bool> waiting = false, locked = false;
  std::string message;
  std::thread second([&] {
    auto lock = GoldenLock::acquire(folder_, Mode::Exclusive, [&](const std::string& text) {
      message = text;
      waiting = true;
    });
    locked = bool(lock);
  });
  while (!waiting) std::this_thread::yield();
  EXPECT_FALSE(locked);  // still waiting: the first lock is held
  first.reset();
  second.join();
  EXPECT_TRUE(locked);
  EXPECT_EQ(message, "waiting for another xshade to finish writing " + folder_.string() + " (it holds " +
                         (folder_ / ".golden.lock").string() + ")");
}

TEST_F(GoldenLockTest, SharedLocksDoNotWaitForEachOther) {
  auto first = GoldenLock::acquire(folder_, Mode::Shared);
  ASSERT_TRUE(first);
  bool waited = false;
  auto second = GoldenLock::acquire(folder_, Mode::Shared, [&](const std::string&) { waited = true; });
  ASSERT_TRUE(second);
  EXPECT_FALSE(waited);
}

TEST_F(GoldenLockTest, AnUpgradeWaitsForTheOtherReaders) {
  auto shared = GoldenLock::acquire(folder_, Mode::Shared);
  auto upgrading = GoldenLock::acquire(folder_, Mode::Shared);
  ASSERT_TRUE(shared && upgrading);
  std::optional<GoldenLock> reader(std::move(*shared));
  std::atomic<bool> waiting = false;
  std::thread upgrade([&] { EXPECT_TRUE(upgrading->upgrade([&](const std::string&) { waiting = true; })); });
  while (!waiting) std::this_thread::yield();
  reader.reset();
  upgrade.join();
  EXPECT_EQ(upgrading->mode(), Mode::Exclusive);
  std::atomic<bool> waited = false;
  auto blocked = std::thread([&] {
    auto lock = GoldenLock::acquire(folder_, Mode::Shared, [&](const std::string&) { waited = true; });
    EXPECT_TRUE(lock);
  });
  while (!waited) std::this_thread::yield();
  std::optional<GoldenLock> exclusive(std::move(*upgrading));
  exclusive.reset();
  blocked.join();
}

TEST_F(GoldenLockTest, AFolderThatDoesNotExistIsAnError) {
  auto lock = GoldenLock::acquire(folder_ / "missing", Mode::Exclusive);
  ASSERT_FALSE(lock);
  EXPECT_EQ(lock.error().kind, ErrorKind::Backend);
  EXPECT_NE(lock.error().message.find("cannot open the golden folder's lock"), std::string::npos);
}

}  // namespace
}  // namespace xshade::harness
