// Image files whose headers claim a size their bytes do not hold, made byte by byte at run time
// for the tests that check such a file is refused before its pixels are allocated (no binary
// file is kept in the repository). Test code only: compiled into the tests that use it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace xshade::harness::forged {

// A PNG of one IHDR (8-bit RGBA, `width` x `height`), a few bytes of IDAT and IEND, with valid
// CRCs: 68 bytes that OpenImageIO opens as a `width` x `height` image.
std::string png(uint32_t width, uint32_t height);
// An OpenEXR scan-line file (RGB float, ZIP) whose data and display windows are `width` x
// `height`, with a line offset table of zeros (unless `offset_table` is false) and no pixels;
// with `extra_attribute`, one more attribute written before the header's end, as it is.
std::string exr(int32_t width, int32_t height, bool offset_table = true, const std::string& extra_attribute = "");
// An OpenEXR attribute: `name`, `type`, then `claimed` as its size, followed by `value`.
std::string exr_attribute(const std::string& name, const std::string& type, uint32_t claimed, const std::string& value);
// A Radiance HDR header for `width` x `height` and a few bytes of pixels.
std::string hdr(int32_t width, int32_t height);

void write(const std::filesystem::path& path, const std::string& bytes);

}  // namespace xshade::harness::forged
