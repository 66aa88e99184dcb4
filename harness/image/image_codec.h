// What xshade asks of its image library (OpenImageIO): write a PNG or an EXR, open any image file
// and read its pixels, colour a ramp through a named colour map.
//
// OpenImageIO brings some 260 shared libraries (OpenCV, GDAL, ffmpeg, ...), a third of a second
// of loading before main, so it is reached only through this seam: its implementation
// (oiio_codec.cpp) is a module of its own, libxshade_image_codec.so, opened the first time a
// process reads or writes an image file (run and bless open it first thing, for the workers they
// fork to share). A process that reads none (compile, --version, a unit test) never loads it. The module is found
// through the program's run path: beside the build's harness/image folder in a build tree, in <libdir>/xshade when
// installed.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/result.h"

namespace xshade::harness {

// What a file's header says, before any pixel is read.
struct ImageFileHeader {
  int64_t width = 0;
  int64_t height = 0;
  int64_t depth = 1;
  int channels = 0;
  int alpha_channel = -1;  // -1: the file names none
  int64_t tile_width = 0;  // 0: not tiled
  int64_t tile_height = 0;
  int64_t tile_depth = 0;
  bool uint8 = false;           // 8-bit integer channels
  bool floating_point = false;  // half, float or double channels
};

enum class PixelType { UInt8, Float };

// An open image file. Errors are the library's words, without the file's name.
class ImageFileReader {
 public:
  virtual ~ImageFileReader() = default;
  virtual const ImageFileHeader& header() const = 0;
  // The whole image's first `channels` channels, converted to `type`, into `pixels`; empty when
  // it read them, else why not.
  virtual std::string read(int channels, PixelType type, void* pixels) = 0;
};

class ImageCodec {
 public:
  virtual ~ImageCodec() = default;
  // Each returns an empty string when it succeeded, else the library's words. The encoders give
  // the file's bytes, which image_io.cpp writes as a whole file.
  // 8-bit RGBA, sRGB-encoded colour with unassociated alpha, at zlib level `compression_level`.
  virtual std::string encode_png(uint32_t width, uint32_t height, const uint8_t* rgba, int compression_level,
                                 std::vector<unsigned char>& bytes) const = 0;
  // Float RGBA, every value as it is, zip-compressed at zlib's fastest level.
  virtual std::string encode_exr(uint32_t width, uint32_t height, const float* rgba,
                                 std::vector<unsigned char>& bytes) const = 0;
  // Opens a file of any format the library knows, alpha unassociated (colour is not premultiplied).
  virtual std::unique_ptr<ImageFileReader> open(const std::string& path, std::string& error) const = 0;
  // The sRGB colour of each of `positions` (0..1) through the colour map `map` ("inferno"): three
  // floats each, into `rgb`.
  virtual std::string color_map(const std::vector<float>& positions, const std::string& map,
                                std::vector<float>& rgb) const = 0;
};

// The image library, opened on the first call; the same codec (or the same error, a backend error
// naming the module and why it could not be opened) every call after.
Result<const ImageCodec*> image_codec();

// The module's one entry point, by this name.
using ImageCodecEntry = const ImageCodec* (*)();
inline constexpr const char* kImageCodecModule = "libxshade_image_codec.so";
inline constexpr const char* kImageCodecEntry = "xshade_image_codec";

}  // namespace xshade::harness
