// The parser's nodes and their memory: every node from its unit's arena.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hlsl_like/lexer.h"
#include "hlsl_like/parser.h"
#include "hlsl_like/parser_internal.h"
#include "hlsl_like/parser_test_support.h"

namespace xshade::hlsl::parser_test {
namespace {

// ---------------------------------------------------------------------------------------------
// The nodes' memory

TEST(AstArena, NodesMadeInAScopeComeFromItsArenaOneAfterAnother) {
  AstArena arena;
  std::unique_ptr<NameExpr> first, second;
  {
    AstArenaScope scope(arena);
    first = std::make_unique<NameExpr>(Loc{});
    second = std::make_unique<NameExpr>(Loc{});
  }
  const auto gap = reinterpret_cast<const char*>(second.get()) - reinterpret_cast<const char*>(first.get());
  EXPECT_GT(gap, 0);
  EXPECT_LE(size_t(gap), sizeof(NameExpr) + 2 * AstArena::kAlignment);
  // Outside any scope the heap is back; both kinds of node are deleted the same way.
  auto from_heap = std::make_unique<NameExpr>(Loc{});
  from_heap->name = std::string(100, 'n');
  first->name = std::string(100, 'f');
  first.reset();
  from_heap.reset();
}

TEST(AstArena, ScopesNestAndRestoreTheOuterArena) {
  AstArena outer_arena, inner_arena;
  AstArenaScope outer(outer_arena);
  auto before = std::make_unique<BlockStmt>(Loc{});
  {
    AstArenaScope inner(inner_arena);
    auto inside = std::make_unique<BlockStmt>(Loc{});
  }
  auto after = std::make_unique<BlockStmt>(Loc{});
  const auto gap = reinterpret_cast<const char*>(after.get()) - reinterpret_cast<const char*>(before.get());
  EXPECT_GT(gap, 0);
  EXPECT_LE(size_t(gap), sizeof(BlockStmt) + 2 * AstArena::kAlignment);
}

TEST(AstArena, ManyAndLargeNodesAndUnitsMovedOver) {
  // More nodes than one block holds, names that own heap memory, a unit assigned over a
  // unit that holds a tree (the old tree goes before its arena).
  TranslationUnit unit;
  for (int round = 0; round < 3; ++round) {
    TranslationUnit next;
    {
      AstArenaScope scope(next.arena);
      for (int i = 0; i < 5000; ++i) {
        auto var = std::make_unique<VarDecl>(Loc{});
        var->name = "a_name_long_enough_for_the_heap_" + std::to_string(i);
        auto init = std::make_unique<InitListExpr>(Loc{});
        for (int k = 0; k < 3; ++k) init->elements.push_back(std::make_unique<IntLiteralExpr>(Loc{}));
        var->initializer = std::move(init);
        next.decls.push_back(std::move(var));
      }
    }
    unit = std::move(next);
    ASSERT_EQ(unit.decls.size(), 5000u);
    EXPECT_EQ(unit.decls.back()->name, "a_name_long_enough_for_the_heap_4999");
  }
  TranslationUnit moved(std::move(unit));
  EXPECT_EQ(moved.decls.size(), 5000u);
  // An arena's very large request gets a block of its own; allocation goes on in the current one.
  AstArena arena;
  void* small = arena.allocate(16);
  void* large = arena.allocate(1 << 20);
  void* small_again = arena.allocate(16);
  EXPECT_NE(large, nullptr);
  EXPECT_EQ(static_cast<char*>(small_again) - static_cast<char*>(small), 16);
}

}  // namespace
}  // namespace xshade::hlsl::parser_test
