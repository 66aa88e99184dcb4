#include "harness/image/image_io.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "base/file_io.h"
#include "harness/image/exr_header.h"
#include "harness/image/image_codec.h"
#include "harness/image/image_limits.h"

namespace xshade::harness {
namespace {

std::string file_error(const std::string& what, const std::filesystem::path& path, const std::string& detail) {
  std::string message = what + " " + path.string();
  if (!detail.empty()) message += ": " + detail;
  return message;
}

// The encoded file written whole (write_file_atomically): a full disk or an I/O error is the
// environment's error with its reason, and leaves the old file or none.
Result<void> write_encoded(const std::filesystem::path& path, const std::string& detail,
                           const std::vector<unsigned char>& bytes) {
  if (!detail.empty()) return fail(ErrorKind::Backend, file_error("cannot write", path, detail));
  return write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// What the header claims, against image_limits.h. For an EXR, width and height are its data
// window, which is what is read; a tiled file's tiles are buffers too.
// "it is W x H pixels; xshade reads ..." for a size image_limits.h does not allow, else empty.
std::string size_refusal(int64_t width, int64_t height, const std::string& size) {
  const bool too_large = width > int64_t(kMaxImageFileSide) || height > int64_t(kMaxImageFileSide) ||
                         (width > 0 && height > 0 && uint64_t(width) * uint64_t(height) > kMaxImageFilePixels);
  if (!too_large) return {};
  return "it is " + size + " pixels; xshade reads images of at most " + std::to_string(kMaxImageFileSide) +
         " pixels a side and " + std::to_string(kMaxImageFilePixels) + " pixels in all";
}

Result<void> check_header(const ImageFileHeader& spec, const std::filesystem::path& path) {
  std::string size = std::to_string(spec.width) + " x " + std::to_string(spec.height);
  if (spec.depth > 1) size += " x " + std::to_string(spec.depth);
  if (const std::string refused = size_refusal(spec.width, spec.height, size); !refused.empty())
    return fail(ErrorKind::UserInput, file_error("cannot read image", path, refused));
  if (spec.depth > 1)
    return fail(ErrorKind::UserInput,
                file_error("cannot read image", path,
                           "it is a volume of " + size + " pixels; xshade reads flat images (depth 1)"));
  if (spec.channels > kMaxImageFileChannels)
    return fail(ErrorKind::UserInput,
                file_error("cannot read image", path,
                           "it has " + std::to_string(spec.channels) + " channels; xshade reads images of at most " +
                               std::to_string(kMaxImageFileChannels)));
  const uint64_t tile_pixels =
      uint64_t(std::max<int64_t>(spec.tile_width, 0)) * uint64_t(std::max<int64_t>(spec.tile_height, 0));
  if (spec.tile_width > int64_t(kMaxImageFileSide) || spec.tile_height > int64_t(kMaxImageFileSide) ||
      tile_pixels > kMaxImageFilePixels || spec.tile_depth > 1)
    return fail(
        ErrorKind::UserInput,
        file_error("cannot read image", path,
                   "its tiles are " + std::to_string(spec.tile_width) + " x " + std::to_string(spec.tile_height) +
                       " pixels; xshade reads tiles of at most " + std::to_string(kMaxImageFileSide) +
                       " pixels a side and " + std::to_string(kMaxImageFilePixels) + " pixels in all"));
  return {};
}

double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// 8-bit sRGB decoding, exact per code, computed once.
const std::array<float, 256>& srgb_decode_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (int i = 0; i < 256; ++i) values[i] = float(srgb_decode(i / 255.0));
    return values;
  }();
  return table;
}

}  // namespace

float srgb_to_linear(float encoded) { return float(srgb_decode(std::clamp(double(encoded), 0.0, 1.0))); }

uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  if (linear >= 1.0f) return 255;
  double c = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(c * 255.0));
}

float srgb8_to_linear(uint8_t encoded) { return srgb_decode_table()[encoded]; }

Result<void> write_png(const FloatImage& image, const std::filesystem::path& path, PngCompression compression) {
  std::vector<uint8_t> bytes(image.rgba.size());
  for (size_t i = 0; i < image.rgba.size(); i += 4) {
    for (size_t c = 0; c < 3; ++c) bytes[i + c] = linear_to_srgb8(image.rgba[i + c]);
    float alpha = image.rgba[i + 3];
    bytes[i + 3] = alpha > 0.0f ? uint8_t(std::lround(std::min(alpha, 1.0f) * 255.0f)) : 0;
  }
  auto codec = image_codec();
  if (!codec) return fail(codec.error());
  std::vector<unsigned char> encoded;
  const std::string detail = (*codec)->encode_png(image.width, image.height, bytes.data(),
                                                  compression == PngCompression::Fast ? 1 : 6, encoded);
  return write_encoded(path, detail, encoded);
}

Result<void> write_exr(const FloatImage& image, const std::filesystem::path& path) {
  auto codec = image_codec();
  if (!codec) return fail(codec.error());
  std::vector<unsigned char> encoded;
  const std::string detail = (*codec)->encode_exr(image.width, image.height, image.rgba.data(), encoded);
  return write_encoded(path, detail, encoded);
}

Result<FloatImage> read_image(const std::filesystem::path& path, bool srgb) {
  // The image libraries open by name and read on to the end: a FIFO would be waited on, and a
  // device (/dev/zero) read forever.
  if (const std::string kind = not_a_file(path); !kind.empty())
    return fail(ErrorKind::UserInput, file_error("cannot read image", path, "it is " + kind + ", not a file"));
  // OpenEXR allocates what its header claims as it opens the file: that is checked first.
  auto window = exr_data_window(path);
  if (!window) return fail(window.error());
  if (*window) {
    const std::string size = std::to_string((*window)->width) + " x " + std::to_string((*window)->height);
    if (const std::string refused = size_refusal((*window)->width, (*window)->height, size); !refused.empty())
      return fail(ErrorKind::UserInput, file_error("cannot read image", path, refused));
  }
  auto codec = image_codec();
  if (!codec) return fail(codec.error());
  std::string error;
  std::unique_ptr<ImageFileReader> input = (*codec)->open(path.string(), error);
  if (!input) return fail(ErrorKind::UserInput, file_error("cannot read image", path, error));
  const ImageFileHeader& spec = input->header();
  if (spec.width <= 0 || spec.height <= 0 || spec.channels <= 0)
    return fail(ErrorKind::UserInput, file_error("cannot read image", path, "it has no pixels"));
  // The header is all that has been read: its sizes are checked before they size any buffer.
  if (Result<void> fits = check_header(spec, path); !fits) return fail(fits.error());
  const int channels = spec.channels;
  // An integer file's colour is sRGB-encoded whatever its depth (a 16-bit PNG too); 8 bits
  // decode through the exact table.
  const bool encoded = spec.uint8;
  const bool integer = !spec.floating_point;

  FloatImage image(uint32_t(spec.width), uint32_t(spec.height));
  // A float file of RGBA (a render, a golden) is read straight into the image: a 2048 x 2048
  // file is 64 MB, and a second buffer of it was a fifth of what xshade diff took.
  const int file_alpha = spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 4 ? 3 : -1);
  if (!integer && channels == 4 && file_alpha == 3) {
    if (std::string failed = input->read(4, PixelType::Float, image.rgba.data()); !failed.empty())
      return fail(ErrorKind::UserInput, file_error("cannot read image", path, failed));
    return image;
  }
  std::vector<float> pixels(size_t(spec.width) * spec.height * channels);
  std::vector<uint8_t> bytes(encoded ? pixels.size() : 0);
  const std::string failed = encoded ? input->read(channels, PixelType::UInt8, bytes.data())
                                     : input->read(channels, PixelType::Float, pixels.data());
  if (!failed.empty()) return fail(ErrorKind::UserInput, file_error("cannot read image", path, failed));

  // Grey and grey+alpha files spread their first channel over RGB; missing alpha is 1.
  const int alpha_channel = spec.alpha_channel >= 0 ? spec.alpha_channel : (channels == 2 ? 1 : channels == 4 ? 3 : -1);
  for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p) {
    auto value = [&](int c, bool colour) {
      size_t i = p * channels + c;
      if (!encoded) return integer && colour && srgb ? srgb_to_linear(pixels[i]) : pixels[i];
      return colour && srgb ? srgb8_to_linear(bytes[i]) : bytes[i] / 255.0f;
    };
    float* out = &image.rgba[p * 4];
    for (int c = 0; c < 3; ++c) out[c] = value(channels >= 3 ? c : 0, true);
    out[3] = alpha_channel >= 0 ? value(alpha_channel, false) : 1.0f;
  }
  return image;
}

}  // namespace xshade::harness
