#include "harness/assets/obj_mesh.h"

#include <map>
#include <regex>
#include <tuple>

#include <tiny_obj_loader.h>
#include <glm/geometric.hpp>

#include "base/file_io.h"
#include "harness/assets/vertex_frames.h"

namespace xshade::harness {
namespace {

// tinyobjloader ends its messages with newlines and puts the line number in the text.
Error reader_error(const std::filesystem::path& path, std::string detail) {
  while (!detail.empty() && (detail.back() == '\n' || detail.back() == '\r')) detail.pop_back();
  SourceLocation where{path.string(), 0, 0};
  std::smatch match;
  if (std::regex_search(detail, match, std::regex(R"(line (\d+))"))) where.line = uint32_t(std::stoul(match[1]));
  return Error{"cannot load OBJ mesh " + path.string() + ": " + detail, where, {}};
}

}  // namespace

Result<MeshData> load_obj(const std::filesystem::path& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  // Read here, as a file checked first (a FIFO is not waited on); the OBJ's materials are not
  // used, so no .mtl file is read beside it.
  auto text = read_input_file(path, kMaxObjFileBytes, "the OBJ mesh");
  if (!text) return fail(text.error());
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(*text, "", config)) return fail(reader_error(path, reader.Error()));
  // Out-of-range indices are only a warning to tinyobjloader; reading them would overrun.
  if (reader.Warning().find("out of bounds") != std::string::npos) return fail(reader_error(path, reader.Warning()));

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const auto positions = int(attrib.vertices.size() / 3), normals = int(attrib.normals.size() / 3),
             texcoords = int(attrib.texcoords.size() / 2);
  MeshData mesh;
  bool every_corner_has_a_normal = true;
  std::map<std::tuple<int, int, int>, uint32_t> shared;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& corner : shape.mesh.indices) {
      if (corner.vertex_index < 0 || corner.vertex_index >= positions || corner.normal_index >= normals ||
          corner.texcoord_index >= texcoords)
        return fail(reader_error(path, "a face of shape '" + shape.name + "' indexes past the vertices"));
      auto key = std::make_tuple(corner.vertex_index, corner.normal_index, corner.texcoord_index);
      auto [found, inserted] = shared.try_emplace(key, uint32_t(mesh.vertices.size()));
      if (inserted) {
        Vertex vertex;
        const size_t p = size_t(corner.vertex_index) * 3;
        vertex.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
        if (corner.normal_index >= 0) {
          const size_t n = size_t(corner.normal_index) * 3;
          glm::vec3 normal{attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]};
          float length = glm::length(normal);
          vertex.normal = length > 0.0f ? normal / length : glm::vec3(0, 1, 0);
        } else {
          every_corner_has_a_normal = false;
        }
        if (corner.texcoord_index >= 0) {
          const size_t t = size_t(corner.texcoord_index) * 2;
          vertex.uv = {attrib.texcoords[t], 1.0f - attrib.texcoords[t + 1]};
        }
        mesh.vertices.push_back(vertex);
      }
      mesh.indices.push_back(found->second);
    }
  }
  if (mesh.indices.empty()) return fail(reader_error(path, "it has no faces"));
  if (!every_corner_has_a_normal) compute_smooth_normals(mesh);
  compute_tangents(mesh);
  return mesh;
}

}  // namespace xshade::harness
