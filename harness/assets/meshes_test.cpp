#include "harness/assets/meshes.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "harness/assets/equirect.h"

namespace xshade::harness {
namespace {

// Float rounding of sin, cos and normalisation.
constexpr float kUnitTolerance = 1e-5f;

struct NamedMesh {
  std::string name;
  MeshData mesh;
};

std::vector<NamedMesh> all_meshes() {
  return {{"sphere", sphere_mesh()}, {"torus", torus_mesh()}, {"plane", plane_mesh()}, {"cube", cube_mesh()}};
}

TEST(Meshes, AreValidWithUnitNormalsOrthogonalTangentsAndUvInRange) {
  for (const NamedMesh& named : all_meshes()) {
    SCOPED_TRACE(named.name);
    ASSERT_TRUE(validate_mesh(named.mesh));
    for (const Vertex& v : named.mesh.vertices) {
      EXPECT_NEAR(glm::length(v.normal), 1.0f, kUnitTolerance);
      EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, kUnitTolerance);
      EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0f, kUnitTolerance);
      EXPECT_EQ(v.tangent.w, -1.0f);  // v runs down an unmirrored mapping (meshes.h)
      EXPECT_TRUE(v.uv.x >= 0.0f && v.uv.x <= 1.0f && v.uv.y >= 0.0f && v.uv.y <= 1.0f);
    }
  }
}

// Per triangle, from its corners alone: it winds counter-clockwise seen from where its normals
// point, and the tangent frame agrees with how uv runs across it (solving the edges for dP/du
// and dP/dv): tangent along dP/du, cross(n, t) * w along dP/dv.
TEST(Meshes, TrianglesWindOutwardAndTangentFramesFollowUv) {
  for (const NamedMesh& named : all_meshes()) {
    SCOPED_TRACE(named.name);
    const MeshData& mesh = named.mesh;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Vertex& a = mesh.vertices[mesh.indices[t]];
      const Vertex& b = mesh.vertices[mesh.indices[t + 1]];
      const Vertex& c = mesh.vertices[mesh.indices[t + 2]];
      const glm::vec3 geometric = glm::cross(b.position - a.position, c.position - a.position);
      ASSERT_GT(glm::length(geometric), 0.0f) << "degenerate triangle " << t / 3;
      const glm::vec3 mean_normal = a.normal + b.normal + c.normal;
      EXPECT_GT(glm::dot(geometric, mean_normal), 0.0f) << "triangle " << t / 3;

      const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
      const glm::vec2 d1 = b.uv - a.uv, d2 = c.uv - a.uv;
      const float determinant = d1.x * d2.y - d2.x * d1.y;
      const glm::vec3 du = (e1 * d2.y - e2 * d1.y) / determinant;
      const glm::vec3 dv = (e2 * d1.x - e1 * d2.x) / determinant;
      for (const Vertex* v : {&a, &b, &c}) {
        const glm::vec3 tangent(v->tangent);
        EXPECT_GT(glm::dot(tangent, du), 0.0f) << "triangle " << t / 3;
        EXPECT_GT(glm::dot(glm::cross(v->normal, tangent) * v->tangent.w, dv), 0.0f) << "triangle " << t / 3;
      }
    }
  }
}

TEST(SphereMesh, IsTheUnitSphereWithOutwardNormalsAndEquirectUv) {
  MeshData sphere = sphere_mesh(64, 32);
  // Each pole row of cells gives one triangle per segment, the others two.
  EXPECT_EQ(sphere.indices.size() / 3, size_t(64 * 30 * 2 + 64 * 2));
  for (const Vertex& v : sphere.vertices) {
    EXPECT_NEAR(glm::length(v.position), 1.0f, kUnitTolerance);
    EXPECT_GT(glm::dot(v.normal, v.position), 0.99f);  // the normal is the position
    const bool pole_or_seam = v.uv.y == 0.0f || v.uv.y == 1.0f || v.uv.x == 0.0f || v.uv.x == 1.0f;
    if (!pole_or_seam) {
      glm::vec2 uv = equirect_uv(v.position);
      EXPECT_NEAR(uv.x, v.uv.x, 1e-5f);  // float rounding through sin, cos and atan2
      EXPECT_NEAR(uv.y, v.uv.y, 1e-5f);
    }
  }
}

TEST(TorusMesh, HasItsRadiiAndNormalsPointingOutOfTheTube) {
  MeshData torus = torus_mesh(1.0f, 0.35f);
  for (const Vertex& v : torus.vertices) {
    // The nearest point of the tube's centre circle.
    const glm::vec3 centre = glm::normalize(glm::vec3(v.position.x, 0.0f, v.position.z));
    const glm::vec3 from_centre = v.position - centre;
    EXPECT_NEAR(glm::length(from_centre), 0.35f, kUnitTolerance);
    EXPECT_GT(glm::dot(v.normal, from_centre), 0.0f);
  }
}

TEST(PlaneMesh, IsTwoTrianglesFacingUp) {
  MeshData plane = plane_mesh();
  EXPECT_EQ(plane.vertices.size(), 4u);
  EXPECT_EQ(plane.indices.size(), 6u);
  for (const Vertex& v : plane.vertices) {
    EXPECT_EQ(v.normal, glm::vec3(0, 1, 0));
    EXPECT_EQ(v.position.y, 0.0f);
    EXPECT_EQ(std::abs(v.position.x), 1.0f);
    EXPECT_EQ(std::abs(v.position.z), 1.0f);
  }
}

TEST(CubeMesh, HasTwelveTrianglesAndFlatFaces) {
  MeshData cube = cube_mesh();
  EXPECT_EQ(cube.vertices.size(), 24u);
  EXPECT_EQ(cube.indices.size(), 36u);
  for (const Vertex& v : cube.vertices) {
    EXPECT_EQ(glm::dot(v.position, v.normal), 1.0f);  // on its face's plane, one unit out
    for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(std::abs(v.position[axis]), 1.0f);  // a corner
  }
  // The front face (+z) reads upright from the default camera: uv (0, 0) at its top-left corner.
  for (const Vertex& v : cube.vertices)
    if (v.normal == glm::vec3(0, 0, 1) && v.uv == glm::vec2(0, 0)) {
      EXPECT_EQ(v.position, glm::vec3(-1, 1, 1));
    }
}

}  // namespace
}  // namespace xshade::harness
