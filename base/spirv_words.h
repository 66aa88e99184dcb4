// Walking a SPIR-V module's words instruction by instruction, for the few facts xshade reads or
// mends in a module glslang made (decorations, names, the entry point's interface) without a
// full SPIR-V parser. Stops at a malformed instruction rather than reading past the end.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace xshade::spirv {

// Calls visit(opcode, word_count, words_of_the_instruction) for every instruction after the
// 5-word header. The words are mutable where the module is.
template <typename Words, typename Visit>
void for_each_instruction(Words& words, const Visit& visit) {
  for (size_t at = 5; at < words.size();) {
    const uint32_t count = words[at] >> 16;
    if (count == 0 || at + count > words.size()) break;
    visit(words[at] & 0xffffu, count, &words[at]);
    at += count;
  }
}

// A literal string operand starting at `first` and at most `count` words long (nul-terminated,
// padded to a word).
inline std::string literal_string(const uint32_t* first, uint32_t count) {
  const char* chars = reinterpret_cast<const char*>(first);
  return std::string(chars, strnlen(chars, size_t(count) * 4));
}

// Words a literal string of `length` characters takes, its nul included.
inline uint32_t literal_string_words(size_t length) { return uint32_t(length / 4 + 1); }

}  // namespace xshade::spirv
