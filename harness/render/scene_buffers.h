// The bytes of a read-only buffer a scene gives an object ([object.buffers], docs/scenes.md):
// its numbers made into the words the shader's element declares, or its file's bytes.
#pragma once

#include <cstddef>
#include <vector>

#include "base/result.h"
#include "harness/render/shader_interface.h"
#include "harness/scene/scene.h"

namespace xshade::harness {

// Number i becomes word i of the buffer, of the type `buffer.words[i % words]` gives: a float; an
// int or uint, which must be a whole number in its range; a bool, 0 or 1. A file is read whole
// and must hold whole elements (a multiple of the stride), at least one, and at most
// kMaxSceneBufferBytes. Errors are the scene's, at the value.
Result<std::vector<std::byte>> scene_buffer_bytes(const BufferRef& given, const StorageBufferInput& buffer);

}  // namespace xshade::harness
