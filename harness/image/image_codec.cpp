#include "harness/image/image_codec.h"

#include <dlfcn.h>

namespace xshade::harness {

Result<const ImageCodec*> image_codec() {
  // Opened once per process and never closed: the library keeps threads and caches of its own.
  static const Result<const ImageCodec*> codec = []() -> Result<const ImageCodec*> {
    void* module = ::dlopen(kImageCodecModule, RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      const char* why = ::dlerror();
      return fail(ErrorKind::Backend, std::string("cannot load the image library module ") + kImageCodecModule + ": " +
                                          (why ? why : "unknown reason") +
                                          " (it is built beside xshade and installed in <libdir>/xshade; it needs "
                                          "OpenImageIO, Debian's libopenimageio2.4)");
    }
    auto entry = reinterpret_cast<ImageCodecEntry>(::dlsym(module, kImageCodecEntry));
    if (!entry)
      return fail(ErrorKind::Backend, std::string(kImageCodecModule) + " has no entry point " + kImageCodecEntry +
                                          ": it is not xshade's image library module");
    return entry();
  }();
  return codec;
}

}  // namespace xshade::harness
