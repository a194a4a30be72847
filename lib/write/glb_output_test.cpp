// GlbWriter: each frame is read back (JSON and BIN chunk) and compared with the source and the deformed
// frame. With DQSKIN_GLB_SAMPLE_DIR set, every .glb made here is also written there, for the Khronos
// glTF-Validator (CTest's glb_validator).
#include "dqskin/error.hpp"
#include "dqskin/frame_view.hpp"
#include "glb_output.hpp"
#include "dqskin/load.hpp"
#include "dqskin/version.hpp"
#include "../test_support/glb_output_check.hpp"

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

using namespace glb_check;
namespace fs = std::filesystem;
using DMat4 = Mat4<double>;
using DVec3 = Vec3<double>;

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


}  // namespace dqskin
