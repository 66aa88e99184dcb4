// linear_to_srgb8 for whole images: the same codes, found in a table of where each code starts.
//
// linear_to_srgb8 calls std::pow once per channel, about 45 ns: 90 ms to encode two 512x512
// images, most of a comparison's budget. A binary search among 255 floats gives the same code
// for every float in a few nanoseconds.
#pragma once

#include <cstdint>

namespace xshade::harness {

// The smallest float that linear_to_srgb8 encodes as `code`; 0 for code 0 (every float at or
// below zero, and NaN, encodes as 0).
float srgb8_code_start(uint8_t code);

// linear_to_srgb8(linear), bit for bit, for every float including NaN and infinities.
uint8_t linear_to_srgb8_by_table(float linear);

}  // namespace xshade::harness
