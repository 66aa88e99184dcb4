#include "harness/meshes.h"

namespace xshade::harness {

MeshData clip_rectangle(float x0, float y0, float x1, float y1, float z) {
  auto corner = [z](float x, float y, float u, float v) {
    Vertex vertex;
    vertex.position = {x, y, z};
    vertex.uv = {u, v};
    return vertex;
  };
  MeshData mesh;
  mesh.vertices = {corner(x0, y1, 0, 0), corner(x1, y1, 1, 0), corner(x0, y0, 0, 1),
                   corner(x1, y0, 1, 1)};
  mesh.indices = {0, 1, 2, 2, 1, 3};
  return mesh;
}

}  // namespace xshade::harness
