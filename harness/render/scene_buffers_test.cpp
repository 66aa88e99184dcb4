#include "harness/render/scene_buffers.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

uint32_t word_at(const std::vector<std::byte>& bytes, size_t word) {
  uint32_t value = 0;
  std::memcpy(&value, bytes.data() + word * 4, 4);
  return value;
}

// An element of a float, an int, a uint and a bool, as a StructuredBuffer<S> declares it.
const StorageBufferInput kMixed{"items", 16, "fiub"};

TEST(SceneBuffers, NumbersBecomeTheWordsTheElementDeclares) {
  BufferRef given;
  given.numbers = {0.5, -3, 7, 1, 2.25, 4, 0, 0};
  auto bytes = scene_buffer_bytes(given, kMixed);
  ASSERT_TRUE(bytes) << bytes.error().to_string();
  ASSERT_EQ(bytes->size(), 32u);
  float first = 0.0f;
  std::memcpy(&first, bytes->data(), 4);
  EXPECT_EQ(first, 0.5f);
  EXPECT_EQ(int32_t(word_at(*bytes, 1)), -3);
  EXPECT_EQ(word_at(*bytes, 2), 7u);
  EXPECT_EQ(word_at(*bytes, 3), 1u);
  float fifth = 0.0f;
  std::memcpy(&fifth, bytes->data() + 16, 4);
  EXPECT_EQ(fifth, 2.25f);
}

TEST(SceneBuffers, NumbersThatAreNotWholeElementsOrNotTheirWordsTypeAreRefusedAtTheValue) {
  BufferRef given;
  given.where = {"scene.toml", 7, 9};
  given.numbers = {1, 2, 3};
  auto partial = scene_buffer_bytes(given, kMixed);
  ASSERT_FALSE(partial);
  EXPECT_EQ(partial.error().where.line, 7u);
  EXPECT_NE(partial.error().message.find("give a multiple of 4 numbers, not 3"), std::string::npos)
      << partial.error().message;
  given.numbers = {1, 2.5, 3, 1};
  auto fraction = scene_buffer_bytes(given, kMixed);
  ASSERT_FALSE(fraction);
  EXPECT_NE(fraction.error().message.find("number 1 (word 1 of element 0): 2.5 is not an int"), std::string::npos)
      << fraction.error().message;
  given.numbers = {1, 2, -1, 1};
  auto negative = scene_buffer_bytes(given, kMixed);
  ASSERT_FALSE(negative);
  EXPECT_NE(negative.error().message.find("-1 is not a uint"), std::string::npos) << negative.error().message;
  given.numbers = {1, 2, 3, 2};
  auto not_bool = scene_buffer_bytes(given, kMixed);
  ASSERT_FALSE(not_bool);
  EXPECT_NE(not_bool.error().message.find("2 is not a bool"), std::string::npos) << not_bool.error().message;
}

TEST(SceneBuffers, AFileGivesItsBytesWhenTheyAreWholeElements) {
  const std::filesystem::path file = std::filesystem::path(testing::TempDir()) / "scene_buffers_test.bin";
  {
    std::ofstream out(file, std::ios::binary);
    const uint32_t words[4] = {1, 2, 3, 4};
    out.write(reinterpret_cast<const char*>(words), sizeof words);
  }
  BufferRef given;
  given.file = file;
  auto bytes = scene_buffer_bytes(given, kMixed);
  ASSERT_TRUE(bytes) << bytes.error().to_string();
  EXPECT_EQ(word_at(*bytes, 3), 4u);
  auto wider = scene_buffer_bytes(given, {"wide", 12, "fff"});
  ASSERT_FALSE(wider);
  EXPECT_NE(wider.error().message.find("16 bytes, which is not a whole number of its 12-byte elements"),
            std::string::npos)
      << wider.error().message;
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace xshade::harness
