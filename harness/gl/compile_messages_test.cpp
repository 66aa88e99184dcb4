#include "harness/gl/compile_messages.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

namespace fs = std::filesystem;
using Messages = std::vector<std::string>;

TEST(CompileMessages, WhatACompileSaidIsGivenBackWhenTheSameCompileSaysNothing) {
  const fs::path folder = fs::temp_directory_path() / "xshade_compile_messages_test";
  fs::remove_all(folder);
  const CompileMessages kept(folder);
  const Messages warning = {"0:4(14): warning: `x' used uninitialized\nsecond line"};
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "source", warning), warning);
  // The same source on the same driver, compiled no more (Mesa's cache): the warning again.
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "source", {}), warning);
  // Another source, or another driver, said nothing.
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "other source", {}), Messages{});
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 23.0.0", "source", {}), Messages{});
  // A fresh compile's own words win over what was kept.
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "source", {"new"}), Messages{"new"});
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "source", {}), Messages{"new"});
  // A damaged entry is not believed.
  for (const auto& entry : fs::directory_iterator(folder)) std::ofstream(entry.path(), std::ios::app) << "x";
  EXPECT_EQ(kept.settle("llvmpipe\nMesa 22.3.6", "source", {}), Messages{});
  // Without a folder nothing is kept.
  EXPECT_EQ(CompileMessages({}).settle("llvmpipe", "source", {}), Messages{});
  fs::remove_all(folder);
}

}  // namespace
}  // namespace xshade::harness
