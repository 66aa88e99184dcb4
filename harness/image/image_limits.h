// How large an image may be: a render a scene asks for, and an image file xshade reads (a
// texture, an environment, a golden). Here, in the lowest library that knows images, so that the
// scene reader (which checks a scene's size) and the image reader both see them.
#pragma once

#include <cstdint>

namespace xshade::harness {

// A scene's width and height in pixels. A 4096 x 4096 RGBA32F target is 256 MiB, and a scene
// keeps several (colour, each post pass's, the determinism re-render) on software drivers.
inline constexpr uint32_t kMaxRenderSize = 4096;

// An image file's width and height. llvmpipe and lavapipe upload at most 16384 texels a side
// (GL_MAX_TEXTURE_SIZE, maxImageDimension2D), so a larger file could never be used anyway.
inline constexpr uint32_t kMaxImageFileSide = 16384;
// An image file's pixels in all: 8192 x 4096, an "8K" equirect environment, the largest real
// input in sight. Read as float RGBA it takes 512 MiB, and the read buffer as much again; a
// header claiming more (65535 x 65535 in a 68-byte PNG) is refused before anything is allocated.
inline constexpr uint64_t kMaxImageFilePixels = uint64_t(8192) * 4096;
// An image file's channels: RGBA, or an EXR with a few extra layers. Every channel is read, so
// a header claiming thousands would multiply the read buffer.
inline constexpr int kMaxImageFileChannels = 16;

}  // namespace xshade::harness
