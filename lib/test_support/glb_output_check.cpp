// Test-only: the .glb frame checks of glb_output_check.hpp.
#include "glb_output_check.hpp"

#include "../write/glb_output.hpp"
#include "dqskin/error.hpp"
#include "dqskin/version.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

namespace dqskin::glb_check {

namespace fs = std::filesystem;
using DMat4 = Mat4<double>;
using DVec3 = Vec3<double>;

// ---------------------------------------------------------------------------------------------------
// Reading a .glb back.

namespace {
uint32_t le32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}
}  // namespace


// Checks the container of §4.4 and returns its chunks.
Glb parse_glb(const std::string& bytes) {
  Glb glb;
  EXPECT_GE(bytes.size(), 20u);
  if (bytes.size() < 20) return glb;
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(le32(bytes, 4), 2u);
  EXPECT_EQ(le32(bytes, 8), bytes.size());
  const uint32_t json_length = le32(bytes, 12);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  EXPECT_EQ(json_length % 4, 0u);
  glb.doc = json::parse(bytes.substr(20, json_length));
  const size_t next = 20 + json_length;
  if (next < bytes.size()) {
    const uint32_t bin_length = le32(bytes, next);
    EXPECT_EQ(bytes.substr(next + 4, 4), std::string("BIN\0", 4));
    EXPECT_EQ(bin_length % 4, 0u);
    EXPECT_EQ(next + 8 + bin_length, bytes.size());
    glb.bin = bytes.substr(next + 8, bin_length);
  }
  return glb;
}

// The values of an accessor the writer made (tightly packed, one view each), as double.
std::vector<double> read_accessor(const Glb& glb, int index) {
  const json& a = glb.doc["accessors"].at(size_t(index));
  const json& v = glb.doc["bufferViews"].at(a["bufferView"].get<size_t>());
  const std::map<std::string, size_t> components = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}};
  const size_t n = a["count"].get<size_t>() * components.at(a["type"].get<std::string>());
  const int type = a["componentType"].get<int>();
  const size_t size = type == 5123 ? 2 : 4;
  EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
  EXPECT_EQ(v["byteLength"].get<size_t>(), n * size);
  EXPECT_LE(v["byteOffset"].get<size_t>() + n * size, glb.bin.size());
  std::vector<double> out(n);
  const char* p = glb.bin.data() + v["byteOffset"].get<size_t>();
  for (size_t i = 0; i < n; ++i) {
    if (type == 5126) {
      float f;
      std::memcpy(&f, p + 4 * i, 4);
      out[i] = double(f);
    } else if (type == 5123) {
      uint16_t u;
      std::memcpy(&u, p + 2 * i, 2);
      out[i] = u;
    } else {
      uint32_t u;
      std::memcpy(&u, p + 4 * i, 4);
      out[i] = u;
    }
  }
  return out;
}

namespace {
DMat4 local_matrix(const json& node) {
  if (node.contains("matrix")) {
    std::vector<double> m = node["matrix"].get<std::vector<double>>();
    return glm::make_mat4(m.data());
  }
  const std::vector<double> t = node.value("translation", std::vector<double>{0, 0, 0});
  const std::vector<double> r = node.value("rotation", std::vector<double>{0, 0, 0, 1});
  const std::vector<double> s = node.value("scale", std::vector<double>{1, 1, 1});
  return glm::scale(glm::translate(DMat4(1.0), DVec3(t[0], t[1], t[2])) * glm::mat4_cast(Quat<double>(r[3], r[0], r[1], r[2])),
                    DVec3(s[0], s[1], s[2]));
}
}  // namespace

namespace {
// Every node's world matrix, from the transforms written (§3.5.3).
std::vector<DMat4> world_matrices(const json& doc) {
  const json& nodes = doc["nodes"];
  std::vector<int> parent(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i)
    for (int c : nodes[i].value("children", std::vector<int>{})) parent[size_t(c)] = int(i);
  std::vector<DMat4> world(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) {
    world[i] = DMat4(1.0);
    for (int n = int(i); n >= 0; n = parent[size_t(n)]) world[i] = local_matrix(nodes[size_t(n)]) * world[i];
  }
  return world;
}
}  // namespace

// ---------------------------------------------------------------------------------------------------
// Frames to encode.

namespace {
// The source nodes a scene reaches, ascending (the writer's output order).
std::vector<int> reached_nodes(const Asset& asset, int scene) {
  std::vector<char> reached(asset.nodes.size(), 0);
  std::vector<int> stack;
  if (scene >= 0) stack = asset.scenes[size_t(scene)].roots;
  for (size_t i = 0; scene < 0 && i < asset.nodes.size(); ++i)
    if (asset.nodes[i].parent < 0) stack.push_back(int(i));
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    reached[size_t(n)] = 1;
    for (int c : asset.nodes[size_t(n)].children) stack.push_back(c);
  }
  std::vector<int> out;
  for (size_t i = 0; i < reached.size(); ++i)
    if (reached[i]) out.push_back(int(i));
  return out;
}
}  // namespace


Frame mid_frame(const Asset& asset) {
  Frame f;
  f.scene = choose_scene(asset, -1);
  f.instances = mesh_instances(asset, f.scene);
  if (!asset.clips.empty()) {
    f.clip = &asset.clips[0];
    f.time = 0.5 * (f.clip->first_key + f.clip->last_key);
  }
  const DeformedFrame deformed = deform_frame(asset, f.instances, sample_pose(asset, f.clip, f.time), BlendMode::kDqs);
  f.batch = to_batch(std::span(&deformed, 1), 0);
  f.view = frame_view(f.batch, 0);
  return f;
}

// The JSON of a .gltf or .glb file.
json source_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.rfind("glTF", 0) == 0) return json::parse(bytes.substr(20, le32(bytes, 12)));
  return json::parse(bytes);
}

// Writes `bytes` as NAME.glb into $DQSKIN_GLB_SAMPLE_DIR, when set (emptied once per process).
void keep_sample(const std::string& name, const std::string& bytes) {
  const char* dir = std::getenv("DQSKIN_GLB_SAMPLE_DIR");
  if (!dir || !*dir) return;
  static const bool cleared = [&] {
    fs::remove_all(dir);
    return fs::create_directories(dir);
  }();
  (void)cleared;
  std::ofstream(fs::path(dir) / (name + ".glb"), std::ios::binary) << bytes;
}

// ---------------------------------------------------------------------------------------------------
// What every frame must satisfy.

void expect_frame(const Asset& asset, const json& source, const Frame& f, const Glb& glb) {
  const json& doc = glb.doc;
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  EXPECT_EQ(doc["asset"]["generator"], std::string("dqskin ") + kVersion);
  EXPECT_FALSE(doc.contains("skins"));
  EXPECT_FALSE(doc.contains("animations"));
  for (const json& e : doc.value("extensionsUsed", json::array())) EXPECT_NE(e, "KHR_mesh_quantization");
  EXPECT_EQ(doc.value("materials", json::array()).size(), source.value("materials", json::array()).size());
  ASSERT_EQ(doc["scene"], 0);
  ASSERT_EQ(doc["scenes"].size(), 1u);

  // Nodes: those of the scene, in source order, names and hierarchy kept; then the detached ones.
  const std::vector<int> reached = reached_nodes(asset, f.scene);
  const json& nodes = doc["nodes"];
  ASSERT_GE(nodes.size(), reached.size());
  std::map<int, int> new_index;
  for (size_t i = 0; i < reached.size(); ++i) new_index[reached[i]] = int(i);
  for (size_t i = 0; i < reached.size(); ++i) {
    const Node& src = asset.nodes[size_t(reached[i])];
    EXPECT_EQ(nodes[i].value("name", ""), src.name) << "node " << i;
    std::vector<int> children;
    for (int c : src.children) children.push_back(new_index.at(c));
    EXPECT_EQ(nodes[i].value("children", std::vector<int>{}), children) << "node " << i;
    EXPECT_FALSE(nodes[i].contains("skin"));
    EXPECT_FALSE(nodes[i].contains("weights"));
  }
  for (size_t i = reached.size(); i < nodes.size(); ++i) {
    EXPECT_TRUE(nodes[i]["name"].get<std::string>().ends_with(" (deformed)"));
    EXPECT_FALSE(nodes[i].contains("translation") || nodes[i].contains("rotation") || nodes[i].contains("scale") ||
                 nodes[i].contains("matrix"));
  }

  // Mesh k is instance k; its node's world matrix carries its vertices to the frame's world positions.
  ASSERT_EQ(doc["meshes"].size(), f.instances.size());
  std::map<int, int> node_of_mesh;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].contains("mesh")) {
      EXPECT_TRUE(node_of_mesh.emplace(nodes[i]["mesh"].get<int>(), int(i)).second);
    }
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const PrimitiveView& v : f.view.primitives)
    for (size_t i = 0; i < v.positions.size(); ++i) lo[int(i % 3)] = std::min(lo[int(i % 3)], double(v.positions[i])),
                                                    hi[int(i % 3)] = std::max(hi[int(i % 3)], double(v.positions[i]));
  const double tolerance = 1e-4 * std::max(glm::length(hi - lo), 1e-6);
  const std::vector<DMat4> world = world_matrices(doc);
  size_t first = 0;
  for (size_t k = 0; k < f.instances.size(); ++k) {
    ASSERT_TRUE(node_of_mesh.count(int(k))) << "no node draws mesh " << k;
    const DMat4& m = world[size_t(node_of_mesh[int(k)])];
    const Mat3<double> normal_matrix = glm::inverseTranspose(Mat3<double>(m));
    const Mesh& mesh = asset.meshes[size_t(f.instances[k].mesh)];
    const json& prims = doc["meshes"][k]["primitives"];
    ASSERT_EQ(prims.size(), mesh.primitives.size());
    for (size_t p = 0; p < prims.size(); ++p) {
      const Primitive& src = mesh.primitives[p];
      const PrimitiveView& view = f.view.primitives[first + p];
      const json& attributes = prims[p]["attributes"];
      for (const auto& [name, unused] : attributes.items())
        EXPECT_TRUE(name.rfind("JOINTS_", 0) != 0 && name.rfind("WEIGHTS_", 0) != 0) << name;
      EXPECT_FALSE(prims[p].contains("targets"));
      const std::vector<double> pos = read_accessor(glb, attributes["POSITION"].get<int>());
      ASSERT_EQ(pos.size(), 3 * src.vertex_count());
      const json& accessor = doc["accessors"][attributes["POSITION"].get<size_t>()];
      for (int c = 0; c < 3; ++c) {
        double min = pos[size_t(c)], max = pos[size_t(c)];
        for (size_t i = size_t(c); i < pos.size(); i += 3) min = std::min(min, pos[i]), max = std::max(max, pos[i]);
        EXPECT_EQ(accessor["min"][size_t(c)].get<double>(), min);
        EXPECT_EQ(accessor["max"][size_t(c)].get<double>(), max);
      }
      for (size_t v = 0; v < src.vertex_count(); ++v) {
        const DVec3 placed = DVec3(m * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0));
        const DVec3 expected(view.positions[3 * v], view.positions[3 * v + 1], view.positions[3 * v + 2]);
        ASSERT_LE(glm::length(placed - expected), tolerance) << "instance " << k << " primitive " << p << " vertex " << v;
      }
      EXPECT_EQ(attributes.contains("NORMAL"), !src.normals_generated);
      if (attributes.contains("NORMAL")) {
        const std::vector<double> n = read_accessor(glb, attributes["NORMAL"].get<int>());
        for (size_t v = 0; v < src.vertex_count(); ++v) {
          const DVec3 local(n[3 * v], n[3 * v + 1], n[3 * v + 2]);
          EXPECT_NEAR(glm::length(local), 1.0, 1e-4);
          const DVec3 expected(view.normals[3 * v], view.normals[3 * v + 1], view.normals[3 * v + 2]);
          EXPECT_LE(glm::length(glm::normalize(normal_matrix * local) - expected), 1e-3) << "normal of vertex " << v;
        }
      }
      EXPECT_EQ(attributes.contains("TANGENT"), !src.tangents.empty() && !src.normals_generated);
      if (!src.uv0.empty()) {
        const std::vector<double> uv = read_accessor(glb, attributes["TEXCOORD_0"].get<int>());
        for (size_t v = 0; v < src.vertex_count(); ++v) {
          EXPECT_EQ(uv[2 * v], double(src.uv0[v].x));
          EXPECT_EQ(uv[2 * v + 1], double(src.uv0[v].y));
        }
      }
      // Reversed winding under a mirroring node: see MirroredSkinnedNodeReversesWinding.
      const bool reversed = f.instances[k].skin >= 0 && glm::determinant(Mat3<double>(m)) < 0;
      if (!src.indices.empty() && !reversed) {
        const std::vector<double> idx = read_accessor(glb, prims[p]["indices"].get<int>());
        EXPECT_EQ(idx, std::vector<double>(src.indices.begin(), src.indices.end()));
      }
      EXPECT_EQ(prims[p].value("material", -1), src.material);
    }
    first += mesh.primitives.size();
  }
}

// Encodes the middle frame of the asset at `path` twice and from several threads; all must be equal.
void check_model(const std::string& path, const std::string& sample_name) {
  SCOPED_TRACE(path);
  const Asset asset = load_asset(path, kKeepSource);
  const Frame f = mid_frame(asset);
  const GlbWriter writer(asset, f.instances, f.scene);
  const std::string bytes = writer.encode(f.view, f.clip, f.time);
  EXPECT_EQ(writer.encode(f.view, f.clip, f.time), bytes) << "two encodes differ";
  std::vector<std::string> parallel(3);
  std::vector<std::thread> threads;
  for (std::string& out : parallel) threads.emplace_back([&] { out = writer.encode(f.view, f.clip, f.time); });
  for (std::thread& t : threads) t.join();
  for (const std::string& out : parallel) EXPECT_EQ(out, bytes) << "an encode on another thread differs";
  expect_frame(asset, source_json(path), f, parse_glb(bytes));
  keep_sample(sample_name, bytes);
}

}  // namespace dqskin::glb_check
