// An OpenEXR file's header, walked before OpenEXR reads it. OpenEXR 3.1 believes the sizes a
// header states: a string attribute that claims 2 GB in a 1 KB file is allocated and zeroed
// before the read fails (12 s and 2 GB of memory for one fuzzed file), and the data window sizes
// the line offset table it allocates as it opens the file, before the reader's check of the
// image's size could refuse it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "base/result.h"

namespace xshade::harness {

struct ExrDataWindow {
  int64_t width = 0;
  int64_t height = 0;
};

// For an OpenEXR file (known by its magic number, whatever its name): an error when an attribute
// of its header claims more bytes than the file holds, else the size of its data window (the
// first part's, in a multi-part file), also where the header breaks after it. nullopt for a file
// that is not OpenEXR, or whose header breaks before its data window: OpenImageIO reads it and
// says what is wrong.
Result<std::optional<ExrDataWindow>> exr_data_window(const std::filesystem::path& path);

}  // namespace xshade::harness
