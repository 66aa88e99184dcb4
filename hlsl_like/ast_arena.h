// Where the syntax tree's nodes live. A tree is made whole (a variant's parse, then the nodes
// semantic analysis adds) and dropped whole (with its TranslationUnit), so its nodes come from
// a bump arena the unit owns, instead of one heap allocation and one free apiece.
//
// The nodes stay ordinary objects held by std::unique_ptr: their destructors still run (their
// strings and most vectors own heap memory), only the node's own memory is not freed one by one.
// Nodes made while no arena is installed (a test building a tree by hand) come from the heap,
// so every node carries a word saying where its memory came from, for operator delete.
// A node dropped before its tree (a production that failed) keeps its memory until the arena
// goes; the parser makes a few nodes per token at most, so that waste is bounded by the input.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>
#include <vector>

namespace xshade::hlsl {

class AstArena {
 public:
  AstArena() = default;
  AstArena(const AstArena&) = delete;
  AstArena& operator=(const AstArena&) = delete;
  // The blocks move, not the nodes in them: what was made from `other` stays where it is.
  AstArena(AstArena&& other) noexcept
      : last_(std::exchange(other.last_, nullptr)),
        cursor_(std::exchange(other.cursor_, nullptr)),
        end_(std::exchange(other.end_, nullptr)) {}
  AstArena& operator=(AstArena&& other) noexcept {
    if (this != &other) {
      release();
      last_ = std::exchange(other.last_, nullptr);
      cursor_ = std::exchange(other.cursor_, nullptr);
      end_ = std::exchange(other.end_, nullptr);
    }
    return *this;
  }
  ~AstArena() { release(); }

  // `size` bytes, aligned to kAlignment.
  void* allocate(size_t size) {
    size = (size + kAlignment - 1) & ~(kAlignment - 1);
    if (size > size_t(end_ - cursor_)) return allocate_in_new_block(size);
    void* memory = cursor_;
    cursor_ += size;
    return memory;
  }

  static constexpr size_t kAlignment = 8;

 private:
  struct Block {
    Block* previous;
  };
  static constexpr size_t kHeader = (sizeof(Block) + kAlignment - 1) & ~(kAlignment - 1);
  // Below glibc's mmap threshold, so that a block freed by one compile is reused by the next.
  static constexpr size_t kBlockSize = 64 * 1024 - 64;

  void* allocate_in_new_block(size_t size) {
    // Nodes are small; anything larger than a quarter block gets a block of its own, kept
    // behind the current one, so that the space left in the current block is not lost.
    if (size > kBlockSize / 4) {
      Block* block = new_block(kHeader + size);
      if (last_) {
        block->previous = last_->previous;
        last_->previous = block;
      } else {
        block->previous = nullptr;
        last_ = block;
      }
      return data(block);
    }
    Block* block = new_block(kBlockSize);
    block->previous = last_;
    last_ = block;
    cursor_ = data(block) + size;
    end_ = reinterpret_cast<char*>(block) + kBlockSize;
    return data(block);
  }

  static Block* new_block(size_t bytes) {
    void* memory = std::malloc(bytes);
    if (!memory) throw std::bad_alloc();
    return static_cast<Block*>(memory);
  }
  static char* data(Block* block) { return reinterpret_cast<char*>(block) + kHeader; }

  void release() {
    while (last_) std::free(std::exchange(last_, last_->previous));
    cursor_ = end_ = nullptr;
  }

  Block* last_ = nullptr;
  char* cursor_ = nullptr;
  char* end_ = nullptr;
};

namespace ast_arena_detail {
// The arena new nodes of this thread come from; null: the heap.
inline thread_local AstArena* current = nullptr;

// The word in front of each node.
enum class Origin : uint64_t { Heap = 0x6865617021, Arena = 0x6172656e6121 };
inline constexpr size_t kOriginSize = sizeof(Origin);

// `bytes` from the current arena, or the heap while none is installed, behind the word that
// says which (and so whether release_with_origin frees it).
inline void* allocate_with_origin(size_t bytes) {
  AstArena* arena = current;
  void* memory = arena ? arena->allocate(kOriginSize + bytes) : ::operator new(kOriginSize + bytes);
  *static_cast<Origin*>(memory) = arena ? Origin::Arena : Origin::Heap;
  return static_cast<char*>(memory) + kOriginSize;
}
// Arena memory goes when its arena does.
inline void release_with_origin(void* pointer) noexcept {
  if (!pointer) return;
  void* memory = static_cast<char*>(pointer) - kOriginSize;
  if (*static_cast<const Origin*>(memory) == Origin::Heap) ::operator delete(memory);
}
}  // namespace ast_arena_detail

// The allocator of the vectors inside nodes (a call's arguments, a block's statements): they
// are made with the tree and dropped with it, like the nodes, and a vector apiece was among a
// compile's commonest allocations. A vector that grows leaves its old array in the arena.
template <class T>
struct AstAllocator {
  using value_type = T;
  static_assert(alignof(T) <= AstArena::kAlignment);
  AstAllocator() = default;
  template <class U>
  AstAllocator(const AstAllocator<U>&) noexcept {}
  T* allocate(size_t count) { return static_cast<T*>(ast_arena_detail::allocate_with_origin(count * sizeof(T))); }
  void deallocate(T* array, size_t) noexcept { ast_arena_detail::release_with_origin(array); }
  template <class U>
  bool operator==(const AstAllocator<U>&) const noexcept {
    return true;
  }
  template <class U>
  bool operator!=(const AstAllocator<U>&) const noexcept {
    return false;
  }
};

template <class T>
using AstVector = std::vector<T, AstAllocator<T>>;

// Nodes made while this lives (on this thread) come from `arena`; the previous arena, if any,
// is back when it ends.
class AstArenaScope {
 public:
  explicit AstArenaScope(AstArena& arena) : previous_(std::exchange(ast_arena_detail::current, &arena)) {}
  ~AstArenaScope() { ast_arena_detail::current = previous_; }
  AstArenaScope(const AstArenaScope&) = delete;
  AstArenaScope& operator=(const AstArenaScope&) = delete;

 private:
  AstArena* previous_;
};

// The base of the node classes (Expr, Stmt, Decl): their operator new and delete. The node
// types' alignment is checked against AstArena::kAlignment in ast.h.
struct AstNodeMemory {
  static void* operator new(size_t size) { return ast_arena_detail::allocate_with_origin(size); }

  // Arena memory goes when its arena does. The unsized global delete: clang leaves sized
  // deallocation off unless asked (-fsized-deallocation).
  static void operator delete(void* node) noexcept { ast_arena_detail::release_with_origin(node); }
};

}  // namespace xshade::hlsl
