#include "harness/report/report_lock.h"

#include <unistd.h>

#include <filesystem>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;

// A second taker (another open of the lock, as another process makes) is refused at once, told
// which run holds the folder; once the first is gone the folder is free again.
TEST(ReportLock, OneRunHoldsAReportFolderAndASecondIsToldWhich) {
  const fs::path folder = fs::temp_directory_path() / ("xshade_report_lock_" + std::to_string(::getpid())) / "report";
  fs::remove_all(folder.parent_path());
  {
    auto first = ReportLock::take(folder, "xshade run --shard 1/2");
    ASSERT_TRUE(first) << first.error().message;
    auto second = ReportLock::take(folder, "xshade run --shard 2/2");
    ASSERT_FALSE(second);
    EXPECT_EQ(second.error().kind, ErrorKind::Usage);  // exit 2: the command line names a busy folder
    EXPECT_EQ(second.error().message, "the report folder " + folder.string() +
                                          " is being written by another xshade (process " + std::to_string(::getpid()) +
                                          ": xshade run --shard 1/2); give this run another --report, or wait for "
                                          "that one to finish");
  }
  EXPECT_TRUE(ReportLock::take(folder, "xshade run"));
  fs::remove_all(folder.parent_path());
}

}  // namespace
}  // namespace xshade::harness
