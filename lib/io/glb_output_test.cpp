// GlbWriter: each frame is read back (JSON and BIN chunk) and compared with the source and the deformed
// frame. With DQSKIN_GLB_SAMPLE_DIR set, every .glb made here is also written there, for the Khronos
// glTF-Validator (CTest's glb_validator).
#include "dqskin/error.hpp"
#include "dqskin/frame_view.hpp"
#include "dqskin/glb_output.hpp"
#include "dqskin/load.hpp"
#include "dqskin/version.hpp"
#include "glb_output_check.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using DMat4 = Mat4<double>;
using DVec3 = Vec3<double>;

// The writer copies what the loader kept of the file.
const LoadOptions kKeepSource = [] {
  LoadOptions o;
  o.keep_source = true;
  return o;
}();

// ---------------------------------------------------------------------------------------------------
// Reading a .glb back.

uint32_t le32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

struct Glb {
  json doc;
  std::string bin;
};

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

// ---------------------------------------------------------------------------------------------------
// Frames to encode.

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

// One CPU-reference frame of an asset in the middle of its first clip (rest pose without clips).
struct Frame {
  int scene = -1;
  std::vector<MeshInstance> instances;
  const Clip* clip = nullptr;
  double time = 0;
  DeformedBatch batch;
  FrameView view;
};

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

TEST(GlbOutput, SyntheticRigsRoundTrip) {
  size_t checked = 0;
  for (const auto& entry : fs::directory_iterator(DQSKIN_TESTDATA_DIR)) {
    if (entry.path().extension() != ".gltf") continue;
    check_model(entry.path().string(), entry.path().stem().string());
    ++checked;
  }
  EXPECT_GE(checked, 8u);
}

TEST(GlbOutput, SharedModelsRoundTrip) {
  const fs::path shared = DQSKIN_SHARED_TESTDATA_DIR;
  if (!fs::is_directory(shared))
    GTEST_SKIP() << "the shared sample models are not present at " << shared.string() << " (DQSKIN_SHARED_TESTDATA_DIR)";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(shared))
    if (entry.path().extension() == ".glb" || entry.path().extension() == ".gltf") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty()) << "no .glb or .gltf under " << shared.string();
  for (const fs::path& file : files) {
    std::string name = fs::relative(file, shared).string();
    std::replace(name.begin(), name.end(), '/', '_');
    std::replace(name.begin(), name.end(), '.', '_');
    check_model(file.string(), "shared_" + name);
  }
}

// Bad normals and tangents from the GPU (zero, NaN, not unit) become unit vectors: the file stays valid.
TEST(GlbOutput, NonUnitNormalsAreReplaced) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf", kKeepSource);
  Frame f = mid_frame(asset);
  std::vector<float>& normals = f.batch.primitives[0].normals;
  normals[0] = normals[1] = normals[2] = 0;
  normals[3] = std::numeric_limits<float>::quiet_NaN();
  normals[6] *= 3;
  f.view = frame_view(f.batch, 0);
  const Glb glb = parse_glb(GlbWriter(asset, f.instances, f.scene).encode(f.view, f.clip, f.time));
  const std::vector<double> n = read_accessor(glb, glb.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>());
  for (size_t v = 0; v < n.size() / 3; ++v)
    EXPECT_NEAR(glm::length(DVec3(n[3 * v], n[3 * v + 1], n[3 * v + 2])), 1.0, 1e-5) << "vertex " << v;
}

// A skinned mesh ignores its node's transform (§3.7.3.1); once the node carries it, a mirroring node
// would turn its faces inside out (§3.7.4), so the triangles' winding is reversed.
TEST(GlbOutput, MirroredSkinnedNodeReversesWinding) {
  Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf", kKeepSource);
  const Frame plain = mid_frame(asset);
  const int node = plain.instances.at(0).node;
  asset.nodes[size_t(node)].local.scale = DVec3(-1, 1, 1);
  const Frame f = mid_frame(asset);
  const Glb glb = parse_glb(GlbWriter(asset, f.instances, f.scene).encode(f.view, f.clip, f.time));
  expect_frame(asset, source_json(asset.path), f, glb);
  const std::vector<uint32_t>& src = asset.meshes[size_t(f.instances[0].mesh)].primitives[0].indices;
  const std::vector<double> idx = read_accessor(glb, glb.doc["meshes"][0]["primitives"][0]["indices"].get<int>());
  ASSERT_EQ(idx.size(), src.size());
  for (size_t t = 0; t + 2 < src.size(); t += 3) {
    EXPECT_EQ(idx[t], src[t]);
    EXPECT_EQ(idx[t + 1], src[t + 2]);
    EXPECT_EQ(idx[t + 2], src[t + 1]);
  }
}

// ---------------------------------------------------------------------------------------------------
// Small hand-made files: a quad with appearance, written with its buffer (and images) into a folder.

constexpr uint8_t kPng[] = {  // 1×1 RGBA
    0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1F, 0x15, 0xC4, 0x89, 0x00, 0x00, 0x00,
    0x0D, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9C, 0x63, 0xF8, 0xDF, 0xC0, 0xF0, 0x1F, 0x00, 0x06, 0x80, 0x02, 0x7F,
    0x10, 0x4C, 0x1B, 0xE1, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
constexpr const char* kPngDataUri =
    "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGP438DwHwAGgAJ/EEwb4QAAAABJRU5ErkJggg==";

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("dqskin_glb_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

void write_file(const fs::path& path, const void* data, size_t size) {
  std::ofstream(path, std::ios::binary).write(static_cast<const char*>(data), std::streamsize(size));
}

// A quad (two triangles, ubyte indices) with POSITION, NORMAL, TEXCOORD_0 (float), TEXCOORD_1 (unsigned
// bytes, not normalized: KHR_mesh_quantization) and COLOR_0 (normalized unsigned bytes, VEC3), both with
// a stride of 4. Its buffer is quad.bin in `dir`.
json quad_gltf(const fs::path& dir) {
  std::string bin;
  auto add = [&](const void* data, size_t size) {
    bin.resize((bin.size() + 3) & ~size_t(3), '\0');
    const size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), size);
    return offset;
  };
  const float positions[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const float uv0[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const uint8_t uv1[] = {0, 0, 0, 0, 7, 0, 0, 0, 7, 9, 0, 0, 0, 9, 0, 0};
  const uint8_t color[] = {255, 0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 51, 102, 204, 0};
  const uint8_t indices[] = {0, 1, 2, 0, 2, 3};
  json views = json::array();
  auto view = [&](const void* data, size_t size, int stride) {
    json v = {{"buffer", 0}, {"byteOffset", add(data, size)}, {"byteLength", size}};
    if (stride) v["byteStride"] = stride;
    views.push_back(v);
    return views.size() - 1;
  };
  json doc;
  doc["accessors"] = json::array({
      {{"bufferView", view(positions, sizeof positions, 0)}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
       {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
      {{"bufferView", view(normals, sizeof normals, 0)}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
      {{"bufferView", view(uv0, sizeof uv0, 0)}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
      {{"bufferView", view(uv1, sizeof uv1, 4)}, {"componentType", 5121}, {"count", 4}, {"type", "VEC2"}},
      {{"bufferView", view(color, sizeof color, 4)}, {"componentType", 5121}, {"normalized", true}, {"count", 4},
       {"type", "VEC3"}},
      {{"bufferView", view(indices, sizeof indices, 0)}, {"componentType", 5121}, {"count", 6}, {"type", "SCALAR"}},
  });
  doc["bufferViews"] = views;
  write_file(dir / "quad.bin", bin.data(), bin.size());
  doc["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "quad.bin"}}});
  doc["asset"] = {{"version", "2.0"}, {"copyright", "nobody"}};
  doc["meshes"] = json::array({{{"name", "Quad"},
                                {"primitives", json::array({{{"attributes", {{"POSITION", 0}, {"NORMAL", 1},
                                                                             {"TEXCOORD_0", 2}, {"TEXCOORD_1", 3},
                                                                             {"COLOR_0", 4}}},
                                                             {"indices", 5}}})}}});
  doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  return doc;
}

Frame rest_frame(const Asset& asset) {
  Frame f;
  f.scene = choose_scene(asset, -1);
  f.instances = mesh_instances(asset, f.scene);
  const DeformedFrame deformed = deform_frame(asset, f.instances, sample_pose(asset, nullptr, 0), BlendMode::kDqs);
  f.batch = to_batch(std::span(&deformed, 1), 0);
  f.view = frame_view(f.batch, 0);
  return f;
}

// Images: an external PNG and a data URI are embedded, a missing file dropped with the texture that
// showed it and the material slot that used that texture; a sampler that does not exist is dropped.
// Cameras, lights, copyright, colours and every texture coordinate set are kept.
TEST(GlbOutput, AppearanceIsCopiedWithItsReferencesChecked) {
  const TempDir dir("appearance");
  json doc = quad_gltf(dir.path);
  write_file(dir.path / "my image.png", kPng, sizeof kPng);
  doc["images"] = json::array({{{"uri", "missing.png"}}, {{"uri", "my%20image.png"}}, {{"uri", kPngDataUri}}});
  doc["samplers"] = json::array({{{"magFilter", 9729}}});
  doc["textures"] = json::array({{{"source", 0}}, {{"source", 1}, {"sampler", 0}}, {{"source", 2}, {"sampler", 4}}});
  doc["materials"] = json::array({{{"name", "Lit"},
                                   {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}},
                                   {"emissiveTexture", {{"index", 1}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0}}}}}}}},
                                   {"occlusionTexture", {{"index", 2}, {"texCoord", 1}}}}});
  doc["meshes"][0]["primitives"][0]["material"] = 0;
  doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
  doc["extensions"] = {{"KHR_lights_punctual", {{"lights", json::array({{{"type", "point"}}})}}}};
  doc["extensionsUsed"] = {"KHR_mesh_quantization", "KHR_texture_transform", "KHR_lights_punctual"};
  doc["nodes"] = json::array({{{"name", "Root"}, {"translation", {0, 2, 0}}, {"camera", 0}, {"children", {2}},
                               {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
                              {{"name", "Unreached"}},
                              {{"name", "Quad"}, {"mesh", 0}, {"rotation", {0, 0.6, 0, 0.8}}}});
  doc["scenes"] = json::array({{{"name", "Main"}, {"nodes", {0}}}});
  doc["scene"] = 0;
  const fs::path path = dir.path / "appearance.gltf";
  std::ofstream(path) << doc.dump();

  const Asset asset = load_asset(path.string(), kKeepSource);
  const Frame f = rest_frame(asset);
  const std::string bytes = GlbWriter(asset, f.instances, f.scene).encode(f.view, nullptr, 0);
  keep_sample("appearance", bytes);
  const Glb glb = parse_glb(bytes);
  expect_frame(asset, doc, f, glb);
  const json& out = glb.doc;

  ASSERT_EQ(out["images"].size(), 2u);
  EXPECT_EQ(out["images"][0]["mimeType"], "image/png");
  EXPECT_FALSE(out["images"][0].contains("uri"));
  const json& image_view = out["bufferViews"][out["images"][0]["bufferView"].get<size_t>()];
  EXPECT_EQ(glb.bin.substr(image_view["byteOffset"].get<size_t>(), image_view["byteLength"].get<size_t>()),
            std::string(reinterpret_cast<const char*>(kPng), sizeof kPng));
  EXPECT_EQ(out["images"][1]["mimeType"], "image/png") << "a data URI is embedded too";
  EXPECT_FALSE(out["images"][1].contains("uri"));
  EXPECT_EQ(out["textures"], json::parse(R"([{"source": 0, "sampler": 0}, {"source": 1}])"));
  const json& material = out["materials"][0];
  EXPECT_FALSE(material["pbrMetallicRoughness"].contains("baseColorTexture"));
  EXPECT_EQ(material["emissiveTexture"]["index"], 0);
  EXPECT_EQ(material["occlusionTexture"], json({{"index", 1}, {"texCoord", 1}}));

  EXPECT_EQ(out["asset"]["copyright"], "nobody");
  EXPECT_EQ(out["cameras"], doc["cameras"]);
  EXPECT_EQ(out["extensions"], doc["extensions"]);
  EXPECT_EQ(out["extensionsUsed"], json({"KHR_lights_punctual", "KHR_texture_transform"}));
  EXPECT_FALSE(out.contains("extensionsRequired"));
  ASSERT_EQ(out["nodes"].size(), 2u);  // "Unreached" is not in the scene
  EXPECT_EQ(out["nodes"][0]["camera"], 0);
  EXPECT_EQ(out["nodes"][0]["extensions"], doc["nodes"][0]["extensions"]);
  EXPECT_EQ(out["scenes"][0], json({{"name", "Main"}, {"nodes", {0}}}));

  const json& attributes = out["meshes"][0]["primitives"][0]["attributes"];
  EXPECT_EQ(read_accessor(glb, attributes["TEXCOORD_1"].get<int>()), (std::vector<double>{0, 0, 7, 0, 7, 9, 0, 9}));
  const std::vector<double> color = read_accessor(glb, attributes["COLOR_0"].get<int>());
  EXPECT_EQ(out["accessors"][attributes["COLOR_0"].get<size_t>()]["type"], "VEC3");
  ASSERT_EQ(color.size(), 12u);
  EXPECT_EQ(color[0], 1.0);
  EXPECT_EQ(color[9], double(float(51 / 255.0)));
  EXPECT_EQ(out["accessors"][out["meshes"][0]["primitives"][0]["indices"].get<size_t>()]["componentType"], 5123);
}

// A node whose world matrix is singular (scale 0 on one axis) cannot carry its mesh in local space: a new
// root node with the identity transform draws the world-space vertices. From memory, with base_dir.
TEST(GlbOutput, SingularNodeMeshMovesToANewRoot) {
  const TempDir dir("singular");
  json doc = quad_gltf(dir.path);
  doc["nodes"] = json::array({{{"name", "Flat"}, {"mesh", 0}, {"scale", {1, 0, 1}}, {"translation", {0, 0, 3}}}});
  doc["scenes"] = json::array({{{"nodes", {0}}}});
  const std::string text = doc.dump();
  const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  const Asset asset = load_asset_from_memory(bytes, "memory", dir.path.string(), kKeepSource);
  const Frame f = rest_frame(asset);
  const std::string glb_bytes = GlbWriter(asset, f.instances, f.scene).encode(f.view, nullptr, 0);
  keep_sample("singular_node", glb_bytes);
  const Glb glb = parse_glb(glb_bytes);
  expect_frame(asset, doc, f, glb);
  const json& nodes = glb.doc["nodes"];
  ASSERT_EQ(nodes.size(), 2u);
  EXPECT_FALSE(nodes[0].contains("mesh"));
  EXPECT_EQ(nodes[0]["scale"], json({1.0, 0.0, 1.0}));
  EXPECT_EQ(nodes[1], json({{"name", "Flat (deformed)"}, {"mesh", 0}}));
  EXPECT_EQ(glb.doc["scenes"][0]["nodes"], json({0, 1}));
  const std::vector<double> pos = read_accessor(glb, glb.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>());
  EXPECT_EQ(pos[7], 0.0);  // vertex 2's y, flattened
  EXPECT_EQ(pos[8], 3.0);  // and moved by the node
}

TEST(GlbOutput, FrameThatDoesNotMatchTheInstancesIsRejected) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf", kKeepSource);
  const Frame f = mid_frame(asset);
  const GlbWriter writer(asset, f.instances, f.scene);
  FrameView fewer = f.view;
  fewer.primitives.pop_back();
  EXPECT_THROW(writer.encode(fewer, f.clip, f.time), std::invalid_argument);
}

// The writer reads nothing of the file: what it copies comes with the asset, which must have kept it.
TEST(GlbOutput, WriterNeedsTheSourceTheLoaderKept) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/textured_cylinder.gltf");
  EXPECT_EQ(asset.source, nullptr);
  EXPECT_THROW(GlbWriter(asset, mesh_instances(asset, 0), 0), std::invalid_argument);
}

TEST(GlbOutput, WriterDoesNotReadTheFileAgain) {
  const TempDir dir("moved");
  const fs::path copy = dir.path / "textured_cylinder.gltf";
  fs::copy_file(std::string(DQSKIN_TESTDATA_DIR) + "/textured_cylinder.gltf", copy);
  const Asset asset = load_asset(copy.string(), kKeepSource);
  const Frame f = rest_frame(asset);
  fs::remove(copy);  // gone before the writer is made
  const Glb glb = parse_glb(GlbWriter(asset, f.instances, f.scene).encode(f.view, nullptr, 0));
  EXPECT_EQ(glb.doc["images"].size(), 1u);  // the checker PNG, from the asset
  EXPECT_TRUE(glb.doc["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0"));
  EXPECT_TRUE(glb.doc["meshes"][0]["primitives"][0]["attributes"].contains("COLOR_0"));
}

}  // namespace

void check_glb_frame(const std::string& path, const std::string& sample_name) { check_model(path, sample_name); }

}  // namespace dqskin
