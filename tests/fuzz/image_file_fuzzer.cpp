// libFuzzer target: any bytes as an image file (a texture, an environment, a golden), read
// through OpenImageIO by xshade's reader. The first byte picks the format (PNG, EXR, Radiance
// HDR) by the file's extension, as a scene names it; the rest is the file. The reader must report,
// never crash, abort on an allocation or read out of bounds.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "harness/image/image_io.h"
#include "harness/image/image_limits.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const extensions[] = {".png", ".exr", ".hdr"};
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("xshade_image_fuzz_" + std::to_string(::getpid()) + extensions[data[0] % 3]);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  auto image = xshade::harness::read_image(path, (data[0] & 0x80) == 0);
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  if (!image) return 0;
  if (uint64_t(image->width) * image->height > xshade::harness::kMaxImageFilePixels ||
      image->rgba.size() != size_t(image->width) * image->height * 4)
    std::abort();
  return 0;
}
