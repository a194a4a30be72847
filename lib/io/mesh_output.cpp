#include "dqskin/mesh_output.hpp"

#include "dqskin/atomic_file.hpp"
#include "mesh.hpp"

#include <bit>
#include <cstring>

namespace dqskin {

MergedMesh merge_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const DeformedFrame& frame) {
  MergedMesh out;
  size_t index = 0;
  for (const MeshInstance& inst : instances) {
    for (const Primitive& prim : asset.meshes[size_t(inst.mesh)].primitives) {
      const DeformedPrimitive& d = frame.primitives[index++];
      const uint32_t base = uint32_t(out.positions.size());
      for (size_t v = 0; v < prim.vertex_count(); ++v) {
        out.positions.emplace_back(d.positions[v]);
        out.normals.push_back(d.normals.empty() ? glm::vec3(0) : glm::vec3(d.normals[v]));
        out.uv0.push_back(prim.uv0.empty() ? glm::vec2(0) : prim.uv0[v]);
      }
      for (uint32_t i : gltf::triangle_list(prim)) out.triangles.push_back(base + i);
    }
  }
  return out;
}

void write_ply(const std::string& path, const MergedMesh& mesh) {
  static_assert(std::endian::native == std::endian::little, "PLY is written as binary_little_endian");
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by dqskin\n";
  header += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz", "s", "t"}) header += std::string("property float ") + p + "\n";
  header += "element face " + std::to_string(mesh.triangles.size() / 3) + "\n";
  header += "property list uchar uint vertex_indices\nend_header\n";

  std::string body;
  body.reserve(mesh.positions.size() * 32 + mesh.triangles.size() / 3 * 13);
  auto put = [&body](const void* data, size_t bytes) { body.append(static_cast<const char*>(data), bytes); };
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    put(&mesh.positions[v], 12);
    put(&mesh.normals[v], 12);
    put(&mesh.uv0[v], 8);
  }
  for (size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const unsigned char three = 3;
    put(&three, 1);
    put(&mesh.triangles[t], 12);
  }
  AtomicFile file(path);
  file.write(header);
  file.write(body);
  file.commit();
}

}  // namespace dqskin
