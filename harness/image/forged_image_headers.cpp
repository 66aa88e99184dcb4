#include "harness/image/forged_image_headers.h"

#include <array>
#include <fstream>

namespace xshade::harness::forged {
namespace {

// PNG's CRC-32 (ISO 3309), over a chunk's type and data.
uint32_t crc32(const std::string& bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> entries{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      entries[n] = c;
    }
    return entries;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (char byte : bytes) c = table[(c ^ static_cast<uint8_t>(byte)) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::string big_endian(uint32_t value) {
  return {char(value >> 24), char((value >> 16) & 0xFF), char((value >> 8) & 0xFF), char(value & 0xFF)};
}

std::string little_endian(uint32_t value) {
  return {char(value & 0xFF), char((value >> 8) & 0xFF), char((value >> 16) & 0xFF), char(value >> 24)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

// name, type, size, value: one attribute of an OpenEXR header.

std::string exr_box(int32_t width, int32_t height) {
  return little_endian(0) + little_endian(0) + little_endian(uint32_t(width - 1)) + little_endian(uint32_t(height - 1));
}

}  // namespace

std::string exr_attribute(const std::string& name, const std::string& type, uint32_t claimed,
                          const std::string& value) {
  return name + '\0' + type + '\0' + little_endian(claimed) + value;
}

std::string png(uint32_t width, uint32_t height) {
  const std::string header = big_endian(width) + big_endian(height) + std::string("\x08\x06\x00\x00\x00", 5);
  // The start of a zlib stream: the reader fails in it, if it ever gets that far.
  const std::string data("\x78\x9c\x63\x60\x60\x60\x60\x00\x00\x00\x04", 11);
  return "\x89PNG\r\n\x1a\n" + png_chunk("IHDR", header) + png_chunk("IDAT", data) + png_chunk("IEND", "");
}

std::string exr(int32_t width, int32_t height, bool offset_table, const std::string& extra_attribute) {
  const auto exr_attribute = [](const std::string& name, const std::string& type, const std::string& value) {
    return forged::exr_attribute(name, type, uint32_t(value.size()), value);
  };
  std::string channels;
  for (const char* name : {"B", "G", "R"})  // sorted, as OpenEXR writes them
    channels +=
        std::string(name) + '\0' + little_endian(2) + std::string(4, '\0') + little_endian(1) + little_endian(1);
  channels += '\0';
  const std::string one = little_endian(0x3F800000);              // 1.0f
  std::string file = little_endian(20000630) + little_endian(2);  // magic number, version 2, scan lines
  file += exr_attribute("channels", "chlist", channels);
  file += exr_attribute("compression", "compression", std::string(1, '\x03'));  // ZIP: 16 lines a chunk
  file += exr_attribute("dataWindow", "box2i", exr_box(width, height));
  file += exr_attribute("displayWindow", "box2i", exr_box(width, height));
  file += exr_attribute("lineOrder", "lineOrder", std::string(1, '\0'));
  file += exr_attribute("pixelAspectRatio", "float", one);
  file += exr_attribute("screenWindowCenter", "v2f", std::string(8, '\0'));
  file += exr_attribute("screenWindowWidth", "float", one);
  file += extra_attribute;
  file += '\0';
  // OpenEXR reads the line offset table when it opens the file: it must be all there.
  if (offset_table) file += std::string(8 * ((size_t(height) + 15) / 16), '\0');
  return file;
}

std::string hdr(int32_t width, int32_t height) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n" +
         std::string("\x02\x02\x00\x10\x02\x02\x00\x10", 8);
}

void write(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace xshade::harness::forged
