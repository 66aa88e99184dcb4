// Normals and tangents computed from a mesh's triangles, for meshes that come without them.
// The tangent convention is the one of meshes.h: tangent.xyz along increasing u, orthogonal to
// the normal, and tangent.w = +-1 so that cross(normal, tangent.xyz) * w points along increasing v.
#pragma once

#include "harness/backend/backend.h"

namespace xshade::harness {

// Smooth unit normals: at each position, the sum of the geometric normals of the triangles
// around it weighted by their areas, shared by every vertex at exactly that position (so seams
// in uv do not crease the shading). Triangles count as counter-clockwise seen from outside.
// A position whose triangles all have zero area keeps the normal +y.
void compute_smooth_normals(MeshData& mesh);

// Tangents from uv: per vertex, the sum of its triangles' directions of increasing u and v
// (Lengyel's method), made orthogonal to the normal. A vertex whose triangles have degenerate uv
// gets any unit tangent orthogonal to its normal, with w = 1.
void compute_tangents(MeshData& mesh);

}  // namespace xshade::harness
