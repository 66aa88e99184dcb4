// Procedural meshes in the one vertex format.
//
// Conventions of the 3D meshes here (and of load_obj):
// - World space is right-handed, +y up; each mesh is centred on the origin.
// - Triangles wind counter-clockwise seen from outside (from where the normals point).
// - Normals are unit length. uv is in [0, 1] with v = 0 at the top of a texture, laid out so
//   that a texture reads upright and unmirrored from outside: u runs to the viewer's right and
//   v downwards.
// - tangent.xyz is the unit direction of increasing u, orthogonal to the normal; tangent.w = +-1
//   is the handedness, chosen so that cross(normal, tangent.xyz) * tangent.w points along
//   increasing v, as Direct3D and Unity reconstruct the bitangent. With v running downwards on
//   an unmirrored mapping, w is -1 on every mesh below.
#pragma once

#include <cstdint>

#include "harness/backend/backend.h"

namespace xshade::harness {

// A rectangle in clip space from (x0, y0) to (x1, y1) at depth z, facing the viewer, with uv
// (0,0) at its top-left corner (x0, y1) as Direct3D and image files have it.
MeshData clip_rectangle(float x0, float y0, float x1, float y1, float z);

// A UV sphere of radius 1. uv follows the equirect mapping (equirect.h): u = 0.5 faces +z,
// u = 0.75 faces +x, the seam is at -z, v = 0 is the north pole (+y). Each pole has one vertex
// per segment (its tangent is the one of its meridian) and one triangle per segment.
MeshData sphere_mesh(uint32_t segments = 64, uint32_t rings = 32);

// A torus around the y axis: the tube's centre circle has radius `major_radius` in the xz plane,
// the tube radius `minor_radius`. u runs around the y axis as on the sphere (u = 0.5 at +z);
// v runs around the tube from its top (v = 0) over its outside (v = 0.25) to its bottom (0.5).
MeshData torus_mesh(float major_radius = 1.0f, float minor_radius = 0.35f, uint32_t segments = 64, uint32_t sides = 32);

// A 2 x 2 square in the xz plane at y = 0, normal +y, u along +x and v along +z (the top of a
// texture lies at -z, away from a camera at +z).
MeshData plane_mesh();

// A 2 x 2 x 2 cube with flat faces: 24 vertices (4 per face), 12 triangles. On the four sides
// a texture stands upright (v down along -y); on the top face its top lies at -z, on the bottom
// face at +z.
MeshData cube_mesh();

}  // namespace xshade::harness
