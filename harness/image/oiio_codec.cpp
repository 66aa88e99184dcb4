// The image codec through OpenImageIO: the module libxshade_image_codec.so (image_codec.h says
// why it is one). It holds no xshade code but this file, and knows nothing of xshade's rules:
// sizes and formats are checked by image_io.cpp from the header it gives.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "harness/image/image_codec.h"

namespace xshade::harness {
namespace {

OIIO::TypeDesc type_of(PixelType type) {
  return type == PixelType::UInt8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
}

// The file's bytes in memory (`format_name` picks the format by its extension): the caller writes
// them as a whole file, so that a full disk is an error with its reason and never a truncated
// or empty image (the library's own file writers can ignore a failed flush).
std::string encode(const char* format_name, const OIIO::ImageSpec& spec, OIIO::TypeDesc pixel_type, const void* pixels,
                   std::vector<unsigned char>& bytes) {
  auto output = OIIO::ImageOutput::create(format_name);
  if (!output) return OIIO::geterror();
  if (!output->supports("ioproxy")) return std::string("the image library cannot write ") + format_name + " to memory";
  OIIO::Filesystem::IOVecOutput memory(bytes);
  if (!output->set_ioproxy(&memory) || !output->open(format_name, spec)) return output->geterror();
  const bool written = output->write_image(pixel_type, pixels);
  const bool closed = output->close();
  if (!written || !closed) return output->geterror();
  return {};
}

class OiioReader final : public ImageFileReader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> input) : input_(std::move(input)) {
    const OIIO::ImageSpec& spec = input_->spec();
    header_ = {spec.width,
               spec.height,
               spec.depth,
               spec.nchannels,
               spec.alpha_channel,
               spec.tile_width,
               spec.tile_height,
               spec.tile_depth,
               spec.format == OIIO::TypeDesc::UINT8,
               spec.format.is_floating_point()};
  }
  const ImageFileHeader& header() const override { return header_; }
  std::string read(int channels, PixelType type, void* pixels) override {
    if (input_->read_image(0, 0, 0, channels, type_of(type), pixels)) return {};
    std::string error = input_->geterror();
    return error.empty() ? "the library read no pixels" : error;
  }

 private:
  std::unique_ptr<OIIO::ImageInput> input_;
  ImageFileHeader header_;
};

class OiioCodec final : public ImageCodec {
 public:
  std::string encode_png(uint32_t width, uint32_t height, const uint8_t* rgba, int compression_level,
                         std::vector<unsigned char>& bytes) const override {
    OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the colour is not premultiplied by alpha
    spec.attribute("png:compressionLevel", compression_level);
    return encode("image.png", spec, OIIO::TypeDesc::UINT8, rgba, bytes);
  }

  std::string encode_exr(uint32_t width, uint32_t height, const float* rgba,
                         std::vector<unsigned char>& bytes) const override {
    OIIO::ImageSpec spec(int(width), int(height), 4, OIIO::TypeDesc::FLOAT);
    spec.attribute("compression", "zip:1");
    return encode("image.exr", spec, OIIO::TypeDesc::FLOAT, rgba, bytes);
  }

  std::unique_ptr<ImageFileReader> open(const std::string& path, std::string& error) const override {
    // Without this OpenImageIO premultiplies colour by alpha when it reads a PNG.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path, &config);
    if (!input) {
      error = OIIO::geterror();
      return nullptr;
    }
    return std::make_unique<OiioReader>(std::move(input));
  }

  std::string color_map(const std::vector<float>& positions, const std::string& map,
                        std::vector<float>& rgb) const override {
    const int count = int(positions.size());
    OIIO::ImageBuf ramp(OIIO::ImageSpec(count, 1, 1, OIIO::TypeDesc::FLOAT));
    for (int i = 0; i < count; ++i) ramp.setpixel(i, 0, &positions[size_t(i)], 1);
    const OIIO::ImageBuf colours = OIIO::ImageBufAlgo::color_map(ramp, 0, map);
    if (colours.has_error()) return colours.geterror();
    rgb.assign(size_t(count) * 3, 0.0f);
    for (int i = 0; i < count; ++i) colours.getpixel(i, 0, &rgb[size_t(i) * 3], 3);
    return {};
  }
};

}  // namespace
}  // namespace xshade::harness

extern "C" __attribute__((visibility("default"))) const xshade::harness::ImageCodec* xshade_image_codec() {
  static const xshade::harness::OiioCodec codec;
  return &codec;
}
