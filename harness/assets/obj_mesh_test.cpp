#include "harness/assets/obj_mesh.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace xshade::harness {
namespace {

std::filesystem::path write_obj(const std::string& name, const std::string& text) {
  auto directory = std::filesystem::temp_directory_path() / "xshade_obj_mesh_test";
  std::filesystem::create_directories(directory);
  auto path = directory / name;
  std::ofstream(path) << text;
  return path;
}

TEST(LoadObj, TriangulatesAQuadFlipsVAndDerivesNormalsAndTangents) {
  // A unit quad in the xy plane, counter-clockwise seen from +z, vt v up along +y.
  auto path = write_obj("quad.obj",
                        "# a quad\n"
                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                        "f 1/1 2/2 3/3 4/4\n");
  Result<MeshData> mesh = load_obj(path);
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertices.size(), 4u);
  EXPECT_EQ(mesh->indices.size(), 6u);
  for (const Vertex& v : mesh->vertices) {
    EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);  // float rounding of the normalisation
    // The file's v = 1 (top of the image) becomes the harness's v = 0.
    EXPECT_FLOAT_EQ(v.uv.y, 1.0f - v.position.y);
    EXPECT_NEAR(v.tangent.x, 1.0f, 1e-6f);  // u grows along +x
    // v grows along -y, and cross(+z, +x) = +y, so the handedness is -1.
    EXPECT_EQ(v.tangent.w, -1.0f);
  }
}

TEST(LoadObj, KeepsAndNormalisesTheFilesNormals) {
  auto path = write_obj("normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1\n");
  Result<MeshData> mesh = load_obj(path);
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertices.size(), 3u);
  for (const Vertex& v : mesh->vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
}

TEST(LoadObj, SmoothNormalsOfAnOctahedronPointAtItsCorners) {
  // Every corner is shared by four congruent faces placed symmetrically around it, so its
  // area-weighted normal is the direction of the corner itself.
  auto path = write_obj("octahedron.obj",
                        "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                        "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n");
  Result<MeshData> mesh = load_obj(path);
  ASSERT_TRUE(mesh) << mesh.error().to_string();
  EXPECT_EQ(mesh->vertices.size(), 6u);
  EXPECT_EQ(mesh->indices.size(), 24u);
  for (const Vertex& v : mesh->vertices) {
    EXPECT_NEAR(glm::dot(v.normal, v.position), 1.0f, 1e-6f);  // float rounding
    EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.0f, 1e-6f);
  }
}

TEST(LoadObj, MalformedFacesAreErrorsNamingTheFileAndLine) {
  auto path = write_obj("malformed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  Result<MeshData> mesh = load_obj(path);
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.error().message.find(path.string()), std::string::npos) << mesh.error().message;
  EXPECT_EQ(mesh.error().where.file, path.string());
  EXPECT_EQ(mesh.error().where.line, 4u);
}

TEST(LoadObj, IndicesPastTheVerticesAreErrors) {
  auto path = write_obj("out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  Result<MeshData> mesh = load_obj(path);
  ASSERT_FALSE(mesh);
  EXPECT_NE(mesh.error().message.find(path.string()), std::string::npos) << mesh.error().message;
}

TEST(LoadObj, MissingFilesAndFilesWithoutFacesAreErrors) {
  auto missing = std::filesystem::temp_directory_path() / "xshade_obj_mesh_test" / "absent.obj";
  Result<MeshData> absent = load_obj(missing);
  ASSERT_FALSE(absent);
  EXPECT_NE(absent.error().message.find(missing.string()), std::string::npos) << absent.error().message;

  Result<MeshData> empty = load_obj(write_obj("points.obj", "v 0 0 0\n"));
  ASSERT_FALSE(empty);
  EXPECT_NE(empty.error().message.find("no faces"), std::string::npos) << empty.error().message;
}

TEST(LoadObj, AFifoIsRefusedWithoutWaitingForAWriter) {
  const auto fifo = std::filesystem::temp_directory_path() / ("xshade_obj_fifo_" + std::to_string(::getpid()) + ".obj");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  Result<MeshData> mesh = load_obj(fifo);
  std::filesystem::remove(fifo);
  ASSERT_FALSE(mesh);
  EXPECT_EQ(mesh.error().message, "the OBJ mesh " + fifo.string() + " is a FIFO, not a file");
}

}  // namespace
}  // namespace xshade::harness
