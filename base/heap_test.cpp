#include "base/heap.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include <unistd.h>

namespace xshade {
namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define XSHADE_SANITIZED_HEAP 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(XSHADE_SANITIZED_BUILD)  // the program links ASan's allocator
#define XSHADE_SANITIZED_HEAP 1
#endif

// glibc's heap only: a sanitizer's allocator takes no notice of mallopt, nor moves the break.
#if defined(__GLIBC__) && !defined(XSHADE_SANITIZED_HEAP)
// What a compile does to the heap: many small blocks, then all of them freed. glibc by itself
// gives the freed top back to the system (the break moves down, and the next compile takes the
// same pages again); after keep_freed_heap the break stays where the blocks took it.
TEST(Heap, KeepsWhatAFreedTreeHeldForTheNextOne) {
  keep_freed_heap();
  std::vector<std::unique_ptr<char[]>> blocks;
  blocks.reserve(8000);
  for (int i = 0; i < 8000; ++i) blocks.push_back(std::make_unique<char[]>(200));  // ~1.6 MiB
  const void* with_blocks = sbrk(0);
  blocks.clear();
  EXPECT_EQ(sbrk(0), with_blocks);
}
#endif

}  // namespace
}  // namespace xshade
