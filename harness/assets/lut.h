// Colour look-up tables as 3D textures: from a strip image (Unity's colour-grading layout) or an
// Adobe/Resolve `.cube` file. Either way texel (x, y, z) of the N x N x N texture holds the output
// for input (red, green, blue) = (x, y, z) / (N - 1), one RGBA32F level (a LUT is not mipmapped).
#pragma once

#include <filesystem>

#include "base/result.h"
#include "harness/backend/backend.h"
#include "harness/image/image.h"

namespace xshade::harness {

// A strip as Unity lays a LUT out (its 1024 x 32 grading LUT is N = 32): N slices of N x N side by
// side, blue rising from slice to slice left to right, red rising to the right within a slice and
// green rising upward (the image's bottom row is green 0, as Unity's uv has it). Fails unless
// the image is N * N x N with N >= 2.
Result<TextureData> lut_from_strip(const FloatImage& strip);

// A `.cube` file: `LUT_3D_SIZE N` (2..256), then N^3 lines of three numbers, red changing
// fastest; `TITLE`, `DOMAIN_MIN 0 0 0`, `DOMAIN_MAX 1 1 1`, comments (#) and blank lines may come
// before the data. Errors name the file, line and column. A 1D LUT or another domain is refused.
Result<TextureData> read_cube_lut(const std::filesystem::path& file);
// The largest .cube the format allows (256^3 lines of three numbers, some 30 bytes a line) is
// about 500 MB; past 512 MiB a file is not a LUT (a log, a device), and is refused unread.
inline constexpr size_t kMaxCubeFileBytes = size_t(512) << 20;

}  // namespace xshade::harness
