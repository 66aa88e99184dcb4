// Procedural meshes in the one vertex format.
#pragma once

#include "harness/backend.h"

namespace xshade::harness {

// A rectangle in clip space from (x0, y0) to (x1, y1) at depth z, facing the viewer, with uv
// (0,0) at its top-left corner (x0, y1) as Direct3D and image files have it.
MeshData clip_rectangle(float x0, float y0, float x1, float y1, float z);

}  // namespace xshade::harness
