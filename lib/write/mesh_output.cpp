#include "mesh_output.hpp"
#include "dqskin/triangles.hpp"
#include "vertex_sharing.hpp"

#include "dqskin/version.hpp"

#include <bit>
#include <charconv>
#include <cstring>

namespace dqskin {
namespace {

// Shortest decimal that reads back as the same float (std::to_chars without precision).
void put_float(std::string& out, float x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

void put_uint(std::string& out, size_t x) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, result.ptr);
}

bool name_char_ok(char c) { return c > ' ' && c != '#' && c < 127; }

std::string ply_header(size_t vertices, size_t faces) {
  static_assert(std::endian::native == std::endian::little, "PLY is written as binary_little_endian");
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by dqskin\n";
  out += "element vertex " + std::to_string(vertices) + "\n";
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz", "s", "t"}) out += std::string("property float ") + p + "\n";
  out += "element face " + std::to_string(faces) + "\n";
  out += "property list uchar uint vertex_indices\nend_header\n";
  return out;
}

void put_ply_faces(std::string& out, const MergedMesh& mesh) {
  for (size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    out += char(3);
    out.append(reinterpret_cast<const char*>(&mesh.triangles[t]), 12);
  }
}

std::string obj_header(const std::string& mtl_file) {
  std::string out = std::string("# dqskin ") + kVersion + "\n";
  if (!mtl_file.empty()) out += "mtllib " + mtl_file + "\n";
  return out;
}

// "tag x y z\n" (n numbers).
void put_vector(std::string& out, const char* tag, const float* x, int n) {
  out += tag;
  for (int c = 0; c < n; ++c) {
    out += ' ';
    put_float(out, x[c]);
  }
  out += '\n';
}

void put_texcoords(std::string& out, const std::vector<glm::vec2>& uv0) {
  for (const glm::vec2& t : uv0) {
    const float st[2] = {t.x, 1.0f - t.y};
    put_vector(out, "vt", st, 2);
  }
}

void put_obj_faces(std::string& out, const MergedMesh& mesh, const Asset& asset, const std::string& mtl_file);

}  // namespace

MergedMesh merge_topology(const Asset& asset, const std::vector<MeshInstance>& instances) {
  MergedMesh out;
  const SharedVertexLayout layout = shared_vertex_layout(asset, instances);
  size_t flat = 0;
  for (const MeshInstance& inst : instances) {
    for (const Primitive& prim : asset.meshes[size_t(inst.mesh)].primitives) {
      const uint32_t base = uint32_t(layout.first_vertex[flat]);
      if (!layout.writes(flat++)) {
        // Shares an earlier primitive's vertices (vertex_sharing.hpp): adds faces only.
      } else if (prim.uv0.empty()) {
        out.uv0.resize(out.uv0.size() + prim.vertex_count(), glm::vec2(0));
      } else {
        out.uv0.insert(out.uv0.end(), prim.uv0.begin(), prim.uv0.end());
      }
      MergedMesh::Group group{asset.nodes[size_t(inst.node)].name, prim.material, out.triangles.size() / 3, 0};
      for (uint32_t i : triangle_list(prim)) out.triangles.push_back(base + i);
      group.triangle_count = out.triangles.size() / 3 - group.first_triangle;
      out.groups.push_back(std::move(group));
    }
  }
  return out;
}

MergedMesh merge_frame(const Asset& asset, const std::vector<MeshInstance>& instances, const FrameView& frame) {
  MergedMesh out = merge_topology(asset, instances);
  out.positions.reserve(out.uv0.size());
  out.normals.reserve(out.uv0.size());
  for (const PrimitiveView& d : distinct_vertices(frame, shared_vertex_layout(asset, instances)).primitives) {
    for (size_t v = 0; v < d.vertices; ++v) {
      out.positions.emplace_back(d.positions[3 * v], d.positions[3 * v + 1], d.positions[3 * v + 2]);
      out.normals.push_back(d.normals.empty() ? glm::vec3(0)
                                              : glm::vec3(d.normals[3 * v], d.normals[3 * v + 1], d.normals[3 * v + 2]));
    }
  }
  return out;
}

std::string encode_ply(const MergedMesh& mesh) {
  std::string out = ply_header(mesh.positions.size(), mesh.triangles.size() / 3);
  out.reserve(out.size() + mesh.positions.size() * 32 + mesh.triangles.size() / 3 * 13);
  auto put = [&out](const void* data, size_t bytes) { out.append(static_cast<const char*>(data), bytes); };
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    put(&mesh.positions[v], 12);
    put(&mesh.normals[v], 12);
    put(&mesh.uv0[v], 8);
  }
  put_ply_faces(out, mesh);
  return out;
}

std::string obj_material_name(const Asset& asset, int material) {
  if (material < 0) return "dqskin_default";
  const std::string& name = asset.materials[size_t(material)].name;
  auto cleaned = [](const std::string& n) {
    std::string s = n;
    for (char& c : s)
      if (!name_char_ok(c)) c = '_';
    return s;
  };
  const std::string mine = cleaned(name);
  bool taken = mine.empty() || mine == "dqskin_default";
  for (int i = 0; i < material && !taken; ++i) taken = cleaned(asset.materials[size_t(i)].name) == mine;
  return taken ? "material_" + std::to_string(material) : mine;
}

std::string encode_mtl(const Asset& asset) {
  if (asset.materials.empty()) return {};
  std::string out = std::string("# dqskin ") + kVersion + ": base color factors of the glTF materials\n";
  auto entry = [&](int m, glm::vec4 color) {
    out += "\nnewmtl " + obj_material_name(asset, m) + "\nKd ";
    for (int c = 0; c < 3; ++c) {
      put_float(out, color[c]);
      out += c < 2 ? " " : "\nd ";
    }
    put_float(out, color.a);
    out += "\n";
  };
  for (size_t m = 0; m < asset.materials.size(); ++m) entry(int(m), asset.materials[m].base_color);
  entry(-1, glm::vec4(1.0f));  // glTF's default material (§3.9.6): base color 1
  return out;
}

std::string encode_obj(const MergedMesh& mesh, const Asset& asset, const std::string& mtl_file) {
  std::string out = obj_header(mtl_file);
  out.reserve(mesh.positions.size() * 96 + mesh.triangles.size() * 12);
  for (const glm::vec3& p : mesh.positions) put_vector(out, "v", &p.x, 3);
  put_texcoords(out, mesh.uv0);
  for (const glm::vec3& n : mesh.normals) put_vector(out, "vn", &n.x, 3);
  put_obj_faces(out, mesh, asset, mtl_file);
  return out;
}

MeshFrameEncoder::MeshFrameEncoder(const Asset& asset, const std::vector<MeshInstance>& instances,
                                   const std::string& mtl_file)
    : shared_(merge_topology(asset, instances)), layout_(shared_vertex_layout(asset, instances)) {
  vertices_ = shared_.uv0.size();
  ply_header_ = ply_header(vertices_, shared_.triangles.size() / 3);
  put_ply_faces(ply_faces_, shared_);
  obj_header_ = obj_header(mtl_file);
  put_texcoords(obj_texcoords_, shared_.uv0);
  put_obj_faces(obj_faces_, shared_, asset, mtl_file);
  shared_.triangles = {};  // encoded: no longer needed
}

void MeshFrameEncoder::encode_ply(const FrameView& frame, std::string& out) const {
  // Sized, not cleared: a reused buffer keeps its length, so no pass zero-fills what is overwritten next.
  out.resize(ply_size());
  std::memcpy(out.data(), ply_header_.data(), ply_header_.size());
  char* at = out.data() + ply_header_.size();
  const float zero[3] = {0, 0, 0};
  const glm::vec2* uv = shared_.uv0.data();
  for (const PrimitiveView& d : distinct_vertices(frame, layout_).primitives) {
    for (size_t v = 0; v < d.vertices; ++v, at += kPlyVertexBytes, ++uv) {
      std::memcpy(at, &d.positions[3 * v], 12);
      std::memcpy(at + 12, d.normals.empty() ? zero : &d.normals[3 * v], 12);
      std::memcpy(at + 24, uv, 8);
    }
  }
  std::memcpy(at, ply_faces_.data(), ply_faces_.size());
}

void MeshFrameEncoder::encode_obj(const FrameView& frame, std::string& out) const {
  out.assign(obj_header_);
  const float zero[3] = {0, 0, 0};
  const FrameView distinct = distinct_vertices(frame, layout_);
  for (const PrimitiveView& d : distinct.primitives)
    for (size_t v = 0; v < d.vertices; ++v) put_vector(out, "v", &d.positions[3 * v], 3);
  out += obj_texcoords_;
  for (const PrimitiveView& d : distinct.primitives)
    for (size_t v = 0; v < d.vertices; ++v) put_vector(out, "vn", d.normals.empty() ? zero : &d.normals[3 * v], 3);
  out += obj_faces_;
}

namespace {

void put_obj_faces(std::string& out, const MergedMesh& mesh, const Asset& asset, const std::string& mtl_file) {
  for (size_t g = 0; g < mesh.groups.size(); ++g) {
    const MergedMesh::Group& group = mesh.groups[g];
    if (group.triangle_count == 0) continue;
    out += "o ";
    for (char c : group.node_name.empty() ? "primitive_" + std::to_string(g) : group.node_name)
      out += name_char_ok(c) ? c : '_';
    out += '\n';
    if (!mtl_file.empty()) out += "usemtl " + obj_material_name(asset, group.material) + "\n";
    for (size_t t = group.first_triangle; t < group.first_triangle + group.triangle_count; ++t) {
      out += 'f';
      for (int k = 0; k < 3; ++k) {
        const size_t i = size_t(mesh.triangles[3 * t + size_t(k)]) + 1;  // OBJ counts from 1
        for (int a = 0; a < 3; ++a) {
          out += a == 0 ? ' ' : '/';
          put_uint(out, i);
        }
      }
      out += '\n';
    }
  }
}

}  // namespace
}  // namespace dqskin
