// Wavefront OBJ files as meshes (through tinyobjloader).
#pragma once

#include <filesystem>

#include "base/result.h"
#include "harness/backend/backend.h"

namespace xshade::harness {

// A scene's mesh of a million triangles is some 100 MB of OBJ text; past 256 MiB a file is not a
// mesh a scene means to draw (a log, a device), and is refused before it is read.
inline constexpr size_t kMaxObjFileBytes = size_t(256) << 20;

// Every shape of the file merged into one triangle list; polygons are triangulated as fans.
// Vertices are shared where a face corner repeats the same position, normal and uv indices.
// - Normals: the file's, normalised; if any face corner has none, smooth area-weighted normals
//   are computed for the whole mesh (compute_smooth_normals).
// - uv: the file's vt with v flipped (OBJ puts v = 0 at the bottom of a texture, the harness at
//   the top); (0, 0) where a corner has none.
// - Tangents: computed from uv (compute_tangents), following the convention of meshes.h.
// Materials are ignored. Fails, naming the file and the line where the reader says one, when the
// file cannot be read (or is not a file, or is past kMaxObjFileBytes), a line is malformed, an index is out of range,
// or there are no faces.
Result<MeshData> load_obj(const std::filesystem::path& path);

}  // namespace xshade::harness
