#include "harness/image/srgb8_encoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <vector>

#include "harness/image/image_io.h"

namespace xshade::harness {
namespace {

// Floats in (0, 1) grouped by their top 16 bits (exponent and 7 mantissa bits): a group spans at
// most 1/128 of its value, narrower than two sRGB steps anywhere in (0, 1), so the group's first
// code is at most a step or two short of any of its values' codes.
constexpr uint32_t kGroupShift = 16;

struct Srgb8Table {
  // starts[code]: the smallest float that encodes as `code`; starts[256] is infinity, so that a
  // search upwards stops without a bound check.
  std::array<float, 257> starts{};
  std::vector<uint8_t> group_first_code;  // the code of each group's smallest float
};

// Positive floats sort in the same order as their bit patterns, so the start of each code is
// found by bisecting bit patterns in (0, 1]. This relies on linear_to_srgb8 never decreasing as
// its argument grows; srgb8_encoder_test checks that across (0, 1) and at every boundary.
Srgb8Table build_table() {
  Srgb8Table table;
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  for (int code = 1; code < 256; ++code) {
    uint32_t low = 0;     // encodes below `code` (0.0f encodes as 0)
    uint32_t high = one;  // encodes as `code` or above (1.0f encodes as 255)
    while (high - low > 1) {
      const uint32_t middle = low + (high - low) / 2;
      if (linear_to_srgb8(std::bit_cast<float>(middle)) >= code)
        high = middle;
      else
        low = middle;
    }
    table.starts[size_t(code)] = std::bit_cast<float>(high);
  }
  table.starts[256] = std::numeric_limits<float>::infinity();

  table.group_first_code.resize((one >> kGroupShift) + 1);
  for (uint32_t group = 0; group < table.group_first_code.size(); ++group) {
    const float smallest = std::bit_cast<float>(group << kGroupShift);
    // The number of codes 1..255 that start at or below it.
    table.group_first_code[group] = uint8_t(
        std::upper_bound(table.starts.begin() + 1, table.starts.begin() + 256, smallest) - (table.starts.begin() + 1));
  }
  return table;
}

const Srgb8Table& table() {
  static const Srgb8Table built = build_table();
  return built;
}

}  // namespace

float srgb8_code_start(uint8_t code) { return table().starts[code]; }

uint8_t linear_to_srgb8_by_table(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN, as linear_to_srgb8
  if (linear >= 1.0f) return 255;
  const Srgb8Table& codes = table();
  uint32_t code = codes.group_first_code[std::bit_cast<uint32_t>(linear) >> kGroupShift];
  while (codes.starts[code + 1] <= linear) ++code;
  return uint8_t(code);
}

}  // namespace xshade::harness
