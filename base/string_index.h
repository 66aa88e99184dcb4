// A table of names: the front end's words and scopes and the emitter's name checks look up a
// name for nearly every token or identifier they meet, where std::unordered_map's general string
// hash and a heap node per entry cost more than the rest of the lookup.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace xshade {

// Strings numbered 0, 1, 2... in the order they were added. The index keeps views: the caller
// keeps the text alive (source text, a syntax tree, a static table) as long as the index.
// Open addressing over a power-of-two table at most half full, with a hash of word-sized loads
// of the text (names are short).
class StringIndex {
 public:
  static constexpr uint32_t kAbsent = UINT32_MAX;

  // `expected`: how many strings are likely, to size the table once.
  explicit StringIndex(size_t expected = 0);

  // The string's number, or kAbsent.
  uint32_t find(std::string_view text) const;
  // The string's number, and whether it was added now.
  std::pair<uint32_t, bool> insert(std::string_view text);
  size_t size() const { return count_; }

 private:
  struct Slot {
    const char* text = nullptr;
    uint32_t size = 0;
    uint32_t check = 0;   // the hash's high half: most mismatches end here, without the text
    uint32_t number = 0;  // the string's number + 1; 0 in a free slot
  };
  size_t probe(std::string_view text, uint64_t hash) const;  // its slot, or the free one it would take
  void grow();

  std::vector<Slot> slots_;
  size_t count_ = 0;
};

}  // namespace xshade
