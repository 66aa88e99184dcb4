// Image files through OpenImageIO: PNG (clamped, sRGB-encoded, 8-bit) and EXR (float).
#pragma once

#include <cstdint>
#include <filesystem>

#include "base/result.h"
#include "harness/image/image.h"

namespace xshade::harness {

// The sRGB transfer function of IEC 61966-2-1 on a value clamped to [0, 1]; NaN encodes as 0.
uint8_t linear_to_srgb8(float linear);
float srgb8_to_linear(uint8_t encoded);

// How hard a PNG is compressed: Small for files kept in a repository (goldens), Fast for a
// report's, written every run (zlib level 1: about half the time, a quarter more bytes).
enum class PngCompression { Small, Fast };

// Colour is clamped to [0, 1] and sRGB-encoded; alpha is stored linearly.
Result<void> write_png(const FloatImage& image, const std::filesystem::path& path,
                       PngCompression compression = PngCompression::Small);
// Every float as it is, NaN and Inf included; zip at zlib's fastest level, which for renders
// takes half the time of OpenEXR's default for under 1% more bytes.
Result<void> write_exr(const FloatImage& image, const std::filesystem::path& path);
// sRGB's decoding of an encoded value in [0, 1] (clamped), to linear.
float srgb_to_linear(float encoded);
// Reads any format OpenImageIO knows into RGBA float. Integer files (8-bit, 16-bit) are taken as
// sRGB-encoded and decoded to linear, so that read_image(write_png(x)) is x up to 8-bit
// quantisation; with `srgb` false their colour is linear data (a LUT, a mask, noise) and reads as
// code / max code. Float files (EXR, HDR) are linear.
Result<FloatImage> read_image(const std::filesystem::path& path, bool srgb = true);

}  // namespace xshade::harness
