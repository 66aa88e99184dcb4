#include "harness/backend/handle_table.h"

#include <gtest/gtest.h>

namespace xshade::harness {
namespace {

TEST(HandleTable, InsertGivesHandlesFromOneThatFindReaches) {
  HandleTable<MeshHandle, int> table("mesh");
  EXPECT_EQ(table.next_handle().id, 1u);
  const MeshHandle first = table.insert(std::make_unique<int>(7));
  const MeshHandle second = table.insert(std::make_unique<int>(8));
  EXPECT_EQ(first.id, 1u);
  EXPECT_EQ(second.id, 2u);
  ASSERT_NE(table.get(second), nullptr);
  EXPECT_EQ(*table.get(second), 8);
  auto found = table.find(first, "render");
  ASSERT_TRUE(found);
  EXPECT_EQ(**found, 7);
}

TEST(HandleTable, AnUnknownHandleIsALocatedError) {
  HandleTable<TargetHandle, int> table("target");
  auto found = table.find(TargetHandle{4}, "read_color");
  ASSERT_FALSE(found);
  EXPECT_EQ(found.error().message, "read_color: no such target (handle 4)");
  EXPECT_EQ(found.error().kind, ErrorKind::Internal);  // the caller's bug, never a scene's
  EXPECT_EQ(table.get(TargetHandle{}), nullptr);
}

TEST(HandleTable, EraseDestroysAndTheIdIsNotGivenOutAgain) {
  HandleTable<TextureHandle, std::shared_ptr<int>> table("texture");
  auto shared = std::make_shared<int>(1);
  const TextureHandle handle = table.insert(std::make_unique<std::shared_ptr<int>>(shared));
  EXPECT_EQ(shared.use_count(), 2);
  ASSERT_TRUE(table.erase(handle, "destroy"));
  EXPECT_EQ(shared.use_count(), 1);
  EXPECT_EQ(table.get(handle), nullptr);
  auto twice = table.erase(handle, "destroy");
  ASSERT_FALSE(twice);
  EXPECT_EQ(twice.error().message, "destroy: no such texture (handle 1)");
  EXPECT_EQ(table.insert(std::make_unique<std::shared_ptr<int>>(shared)).id, 2u);
  EXPECT_EQ(table.size(), 1u);
}

}  // namespace
}  // namespace xshade::harness
