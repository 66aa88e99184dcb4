#include "harness/assets/meshes.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace xshade::harness {
namespace {

// A point of a parametric surface: where it is, its unit normal, and the directions of
// increasing u and v along it.
struct SurfacePoint {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 along_u;  // unit
  glm::vec3 along_v;  // any length
};

Vertex surface_vertex(const SurfacePoint& point, glm::vec2 uv) {
  Vertex vertex;
  vertex.position = point.position;
  vertex.normal = point.normal;
  float handedness = glm::dot(glm::cross(point.normal, point.along_u), point.along_v) < 0.0f ? -1.0f : 1.0f;
  vertex.tangent = glm::vec4(point.along_u, handedness);
  vertex.uv = uv;
  return vertex;
}

// Triangles of a (columns x rows)-cell grid of vertices laid out row by row, each cell split
// from its top-left to its bottom-right corner; counter-clockwise when u runs right and v down
// as seen from outside. Cells in a row whose top (or bottom) edge has collapsed to a point give
// only their one non-degenerate triangle.
void grid_triangles(MeshData& mesh, uint32_t columns, uint32_t rows, bool top_collapsed, bool bottom_collapsed) {
  for (uint32_t j = 0; j < rows; ++j)
    for (uint32_t i = 0; i < columns; ++i) {
      uint32_t top_left = j * (columns + 1) + i, top_right = top_left + 1;
      uint32_t bottom_left = top_left + columns + 1, bottom_right = bottom_left + 1;
      if (!(bottom_collapsed && j == rows - 1))
        mesh.indices.insert(mesh.indices.end(), {top_left, bottom_left, bottom_right});
      if (!(top_collapsed && j == 0)) mesh.indices.insert(mesh.indices.end(), {top_left, bottom_right, top_right});
    }
}

template <class Surface>
MeshData grid_mesh(uint32_t columns, uint32_t rows, bool poles, Surface surface) {
  MeshData mesh;
  mesh.vertices.reserve(size_t(columns + 1) * (rows + 1));
  for (uint32_t j = 0; j <= rows; ++j)
    for (uint32_t i = 0; i <= columns; ++i) {
      glm::vec2 uv{float(i) / float(columns), float(j) / float(rows)};
      mesh.vertices.push_back(surface_vertex(surface(uv), uv));
    }
  grid_triangles(mesh, columns, rows, poles, poles);
  return mesh;
}

// The azimuth of u on the sphere and the torus: u = 0.5 at +z, as in the equirect mapping.
float azimuth(float u) { return (u - 0.5f) * 2.0f * std::numbers::pi_v<float>; }

glm::vec3 along_azimuth(float phi) { return {std::cos(phi), 0.0f, -std::sin(phi)}; }

}  // namespace

MeshData clip_rectangle(float x0, float y0, float x1, float y1, float z) {
  auto corner = [z](float x, float y, float u, float v) {
    Vertex vertex;
    vertex.position = {x, y, z};
    vertex.uv = {u, v};
    return vertex;
  };
  MeshData mesh;
  mesh.vertices = {corner(x0, y1, 0, 0), corner(x1, y1, 1, 0), corner(x0, y0, 0, 1), corner(x1, y0, 1, 1)};
  mesh.indices = {0, 1, 2, 2, 1, 3};
  return mesh;
}

MeshData sphere_mesh(uint32_t segments, uint32_t rings) {
  return grid_mesh(segments, rings, true, [](glm::vec2 uv) {
    const float phi = azimuth(uv.x), theta = uv.y * std::numbers::pi_v<float>;
    // Exact poles, so that a pole's vertices coincide.
    const float sin_theta = uv.y == 0.0f || uv.y == 1.0f ? 0.0f : std::sin(theta);
    const float cos_theta = uv.y == 0.0f ? 1.0f : uv.y == 1.0f ? -1.0f : std::cos(theta);
    glm::vec3 normal{sin_theta * std::sin(phi), cos_theta, sin_theta * std::cos(phi)};
    glm::vec3 along_v{cos_theta * std::sin(phi), -sin_theta, cos_theta * std::cos(phi)};
    return SurfacePoint{normal, normal, along_azimuth(phi), along_v};
  });
}

MeshData torus_mesh(float major_radius, float minor_radius, uint32_t segments, uint32_t sides) {
  return grid_mesh(segments, sides, false, [=](glm::vec2 uv) {
    const float phi = azimuth(uv.x);
    const float psi = 0.5f * std::numbers::pi_v<float> -
                      uv.y * 2.0f * std::numbers::pi_v<float>;  // the angle above the tube's outer equator
    const float ring = major_radius + minor_radius * std::cos(psi);
    glm::vec3 position{ring * std::sin(phi), minor_radius * std::sin(psi), ring * std::cos(phi)};
    glm::vec3 normal{std::cos(psi) * std::sin(phi), std::sin(psi), std::cos(psi) * std::cos(phi)};
    glm::vec3 along_v{std::sin(psi) * std::sin(phi), -std::cos(psi), std::sin(psi) * std::cos(phi)};
    return SurfacePoint{position, normal, along_azimuth(phi), along_v};
  });
}

MeshData plane_mesh() {
  return grid_mesh(1, 1, false, [](glm::vec2 uv) {
    return SurfacePoint{{2.0f * uv.x - 1.0f, 0.0f, 2.0f * uv.y - 1.0f}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}};
  });
}

MeshData cube_mesh() {
  // Each face: its outward normal and the direction that is up on it seen from outside.
  struct Face {
    glm::vec3 normal, up;
  };
  const Face faces[] = {{{0, 0, 1}, {0, 1, 0}},  {{0, 0, -1}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}},
                        {{-1, 0, 0}, {0, 1, 0}}, {{0, 1, 0}, {0, 0, -1}}, {{0, -1, 0}, {0, 0, 1}}};
  MeshData mesh;
  for (const Face& face : faces) {
    // Looking at the face from outside the viewer looks along -normal, so right = (-normal) x up.
    const glm::vec3 right = glm::cross(-face.normal, face.up);
    MeshData quad = grid_mesh(1, 1, false, [&](glm::vec2 uv) {
      glm::vec3 position = face.normal + right * (2.0f * uv.x - 1.0f) - face.up * (2.0f * uv.y - 1.0f);
      return SurfacePoint{position, face.normal, right, -face.up};
    });
    const auto base = uint32_t(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), quad.vertices.begin(), quad.vertices.end());
    for (uint32_t index : quad.indices) mesh.indices.push_back(base + index);
  }
  return mesh;
}

}  // namespace xshade::harness
