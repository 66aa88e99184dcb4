#include "harness/assets/vertex_frames.h"

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

namespace xshade::harness {
namespace {

glm::vec3 any_orthogonal(glm::vec3 n) {
  glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(axis, n));
}

}  // namespace

void compute_smooth_normals(MeshData& mesh) {
  // Vertices at exactly the same position share one accumulated normal.
  std::map<std::tuple<float, float, float>, glm::vec3> sums;
  auto key = [&mesh](uint32_t v) {
    const glm::vec3& p = mesh.vertices[v].position;
    return std::make_tuple(p.x, p.y, p.z);
  };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    // The cross product's length is twice the triangle's area: the area weighting comes free.
    glm::vec3 weighted = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                                    mesh.vertices[c].position - mesh.vertices[a].position);
    for (uint32_t v : {a, b, c}) sums[key(v)] += weighted;
  }
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    auto found = sums.find(key(uint32_t(v)));
    glm::vec3 sum = found == sums.end() ? glm::vec3(0.0f) : found->second;
    float length = glm::length(sum);
    mesh.vertices[v].normal = length > 0.0f ? sum / length : glm::vec3(0, 1, 0);
  }
}

void compute_tangents(MeshData& mesh) {
  std::vector<glm::vec3> along_u(mesh.vertices.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> along_v(mesh.vertices.size(), glm::vec3(0.0f));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    const glm::vec3 e1 = mesh.vertices[b].position - mesh.vertices[a].position;
    const glm::vec3 e2 = mesh.vertices[c].position - mesh.vertices[a].position;
    const glm::vec2 d1 = mesh.vertices[b].uv - mesh.vertices[a].uv;
    const glm::vec2 d2 = mesh.vertices[c].uv - mesh.vertices[a].uv;
    const float determinant = d1.x * d2.y - d2.x * d1.y;
    if (determinant == 0.0f || !std::isfinite(determinant)) continue;
    // Solve e1 = d1.x * dP/du + d1.y * dP/dv, e2 likewise, for dP/du and dP/dv.
    const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / determinant;
    const glm::vec3 dv = (e2 * d1.x - e1 * d2.x) / determinant;
    for (uint32_t v : {a, b, c}) along_u[v] += du, along_v[v] += dv;
  }
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    Vertex& vertex = mesh.vertices[v];
    const glm::vec3 n = vertex.normal;
    glm::vec3 tangent = along_u[v] - n * glm::dot(n, along_u[v]);
    float length = glm::length(tangent);
    if (!(length > 1e-12f)) {
      vertex.tangent = glm::vec4(any_orthogonal(n), 1.0f);
      continue;
    }
    tangent /= length;
    float handedness = glm::dot(glm::cross(n, tangent), along_v[v]) < 0.0f ? -1.0f : 1.0f;
    vertex.tangent = glm::vec4(tangent, handedness);
  }
}

}  // namespace xshade::harness
