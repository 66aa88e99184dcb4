#include "harness/render/scene_buffers.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include <fmt/core.h>

#include "base/file_io.h"

namespace xshade::harness {
namespace {

// The word `number` makes as `type` ('f', 'i', 'u' or 'b'), or why it cannot.
Result<uint32_t> word_of(double number, char type) {
  const auto whole_in = [&](double low, double high) {
    return std::floor(number) == number && number >= low && number <= high;
  };
  switch (type) {
    case 'i':
      if (!whole_in(double(INT32_MIN), double(INT32_MAX)))
        return fail(ErrorKind::UserInput, fmt::format("{} is not an int", number));
      return uint32_t(int32_t(number));
    case 'u':
      if (!whole_in(0.0, double(UINT32_MAX)))
        return fail(ErrorKind::UserInput, fmt::format("{} is not a uint", number));
      return uint32_t(number);
    case 'b':
      if (number != 0.0 && number != 1.0)
        return fail(ErrorKind::UserInput, fmt::format("{} is not a bool (0 or 1)", number));
      return uint32_t(number);
    default: {
      const float value = float(number);
      uint32_t word = 0;
      std::memcpy(&word, &value, 4);
      return word;
    }
  }
}

}  // namespace

Result<std::vector<std::byte>> scene_buffer_bytes(const BufferRef& given, const StorageBufferInput& buffer) {
  const std::string what = "buffer '" + buffer.name + "'";
  if (!given.file.empty()) {
    auto text = read_input_file(given.file, size_t(kMaxSceneBufferBytes), what);
    if (!text) {
      Error error = text.error();
      if (error.where.file.empty()) error.where = given.where;  // the scene's line that names the file
      return fail(std::move(error));
    }
    if (text->empty() || text->size() % buffer.stride != 0)
      return fail(ErrorKind::UserInput,
                  fmt::format("{}: {} is {} bytes, which is not a whole number of its {}-byte elements (at least one)",
                              what, given.file.string(), text->size(), buffer.stride),
                  given.where);
    std::vector<std::byte> bytes(text->size());
    std::memcpy(bytes.data(), text->data(), text->size());
    return bytes;
  }
  if (buffer.words.empty() || given.numbers.empty() || given.numbers.size() % buffer.words.size() != 0)
    return fail(ErrorKind::UserInput,
                fmt::format("{}: an element is {} 32-bit words; give a multiple of {} numbers, not {}", what,
                            buffer.words.size(), buffer.words.size(), given.numbers.size()),
                given.where);
  std::vector<std::byte> bytes(given.numbers.size() * 4);
  for (size_t i = 0; i < given.numbers.size(); ++i) {
    auto word = word_of(given.numbers[i], buffer.words[i % buffer.words.size()]);
    if (!word)
      return fail(ErrorKind::UserInput,
                  fmt::format("{}: number {} (word {} of element {}): {}", what, i, i % buffer.words.size(),
                              i / buffer.words.size(), word.error().message),
                  given.where);
    std::memcpy(bytes.data() + i * 4, &*word, 4);
  }
  return bytes;
}

}  // namespace xshade::harness
