#include "base/string_index.h"

#include <cstring>

namespace xshade {
namespace {

uint64_t load64(const char* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

uint32_t load32(const char* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

uint64_t mix(uint64_t v) {
  v *= 0xbf58476d1ce4e5b9ull;
  return v ^ (v >> 31);
}

// Every byte of the text counts, read 8 or 4 at a time (the last loads overlap rather than
// read past the end).
uint64_t hash_of(std::string_view text) {
  const char* p = text.data();
  size_t n = text.size();
  uint64_t hash = 0x9e3779b97f4a7c15ull * (n + 1);
  for (; n > 8; p += 8, n -= 8) hash = mix(hash ^ load64(p));
  uint64_t tail = 0;
  if (n >= 4) {
    tail = (uint64_t(load32(p)) << 32) | load32(p + n - 4);
  } else if (n > 0) {
    tail = (uint64_t(uint8_t(p[0])) << 16) | (uint64_t(uint8_t(p[n / 2])) << 8) | uint8_t(p[n - 1]);
  }
  return mix(mix(hash ^ tail));
}

}  // namespace

StringIndex::StringIndex(size_t expected) {
  size_t slots = 16;
  while (slots < 2 * expected) slots *= 2;
  slots_.resize(slots);
}

size_t StringIndex::probe(std::string_view text, uint64_t hash) const {
  const auto check = uint32_t(hash >> 32);
  const size_t mask = slots_.size() - 1;
  size_t i = size_t(hash) & mask;
  for (;; i = (i + 1) & mask) {
    const Slot& slot = slots_[i];
    if (slot.number == 0) return i;
    if (slot.check == check && slot.size == text.size() &&
        (slot.text == text.data() || std::memcmp(slot.text, text.data(), text.size()) == 0))
      return i;
  }
}

uint32_t StringIndex::find(std::string_view text) const {
  const Slot& slot = slots_[probe(text, hash_of(text))];
  return slot.number == 0 ? kAbsent : slot.number - 1;
}

std::pair<uint32_t, bool> StringIndex::insert(std::string_view text) {
  const uint64_t hash = hash_of(text);
  size_t i = probe(text, hash);
  if (slots_[i].number != 0) return {slots_[i].number - 1, false};
  if (2 * (count_ + 1) > slots_.size()) {
    grow();
    i = probe(text, hash);
  }
  slots_[i] = {text.data(), uint32_t(text.size()), uint32_t(hash >> 32), uint32_t(++count_)};
  return {uint32_t(count_ - 1), true};
}

void StringIndex::grow() {
  std::vector<Slot> old(slots_.size() * 2);
  old.swap(slots_);
  const size_t mask = slots_.size() - 1;
  for (const Slot& slot : old) {
    if (slot.number == 0) continue;
    size_t i = size_t(hash_of({slot.text, slot.size})) & mask;
    while (slots_[i].number != 0) i = (i + 1) & mask;
    slots_[i] = slot;
  }
}

}  // namespace xshade
