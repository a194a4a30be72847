#include "dqskin/error.hpp"
#include "dqskin/info.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"
#include "../base/base64.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------------
// A tiny glTF writer: raw bytes into one buffer, accessors described in JSON, embedded as a data URI.

using io::base64;

struct GltfBuilder {
  std::vector<uint8_t> bytes;
  json doc = {{"asset", {{"version", "2.0"}}}, {"bufferViews", json::array()}, {"accessors", json::array()}};

  template <typename T>
  int view(const std::vector<T>& data, int stride = 0) {
    while (bytes.size() % 4) bytes.push_back(0);
    const size_t offset = bytes.size();
    bytes.resize(offset + data.size() * sizeof(T));
    std::memcpy(bytes.data() + offset, data.data(), data.size() * sizeof(T));
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}};
    if (stride) v["byteStride"] = stride;
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size()) - 1;
  }
  int accessor(json a) {
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size()) - 1;
  }
  Asset load() {
    doc["buffers"] = json::array({{{"byteLength", bytes.size()},
                                   {"uri", "data:application/octet-stream;base64," + base64(bytes)}}});
    const std::string text = doc.dump();
    return load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "test",
                                  ".");
  }
};

// One triangle, with a skin of two joints unless `skinned` is false.
GltfBuilder triangle(bool skinned = true) {
  GltfBuilder b;
  const int pos = b.accessor({{"bufferView", b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0})},
                              {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  json prim = {{"attributes", {{"POSITION", pos}}}};
  if (skinned) {
    prim["attributes"]["JOINTS_0"] = b.accessor({{"bufferView", b.view(std::vector<uint8_t>{0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0})},
                                                  {"componentType", 5121}, {"count", 3}, {"type", "VEC4"}});
    // Normalized unsigned bytes: 255 = 1.0, 51 = 0.2, 204 = 0.8.
    prim["attributes"]["WEIGHTS_0"] = b.accessor({{"bufferView", b.view(std::vector<uint8_t>{255, 0, 0, 0, 51, 204, 0, 0, 255, 0, 0, 0})},
                                                   {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC4"}});
  }
  b.doc["meshes"] = json::array({{{"primitives", json::array({prim})}}});
  b.doc["nodes"] = skinned ? json::array({{{"mesh", 0}, {"skin", 0}, {"translation", {5, 5, 5}}}, {{"children", {2}}}, {{"translation", {0, 1, 0}}}})
                           : json::array({{{"mesh", 0}}});
  if (skinned) b.doc["skins"] = json::array({{{"joints", {1, 2}}}});
  b.doc["scenes"] = json::array({{{"nodes", skinned ? json::array({0, 1}) : json::array({0})}}});
  b.doc["scene"] = 0;
  return b;
}

TEST(LoadAccessors, NormalizedUnsignedByteWeightsDecodeToUnitRange) {
  const Asset asset = triangle().load();
  const Primitive& p = asset.meshes[0].primitives[0];
  ASSERT_EQ(p.influences, 4);
  EXPECT_FLOAT_EQ(p.weights[0], 1.0f);
  EXPECT_FLOAT_EQ(p.weights[4], 0.2f);
  EXPECT_FLOAT_EQ(p.weights[5], 0.8f);
  EXPECT_EQ(p.joints[5], 1);
}

TEST(LoadAccessors, InterleavedAttributesHonourTheByteStride) {
  GltfBuilder b;
  // position xyz + 4 bytes of padding per vertex: stride 16.
  const int v = b.view(std::vector<float>{1, 2, 3, -1, 4, 5, 6, -1, 7, 8, 9, -1}, 16);
  const int pos = b.accessor({{"bufferView", v}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}}})}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  const Asset asset = b.load();
  EXPECT_EQ(asset.meshes[0].primitives[0].positions[2], glm::vec3(7, 8, 9));
}

TEST(LoadAccessors, SparseAccessorReplacesListedElements) {
  GltfBuilder b;
  const int base = b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
  const int idx = b.view(std::vector<uint16_t>{1, 3});
  const int val = b.view(std::vector<float>{5, 5, 5, 7, 7, 7});
  const int pos = b.accessor({{"bufferView", base}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                              {"sparse", {{"count", 2}, {"indices", {{"bufferView", idx}, {"componentType", 5123}}},
                                          {"values", {{"bufferView", val}}}}}});
  b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 0}}})}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  const Asset asset = b.load();
  const auto& p = asset.meshes[0].primitives[0].positions;
  EXPECT_EQ(p[0], glm::vec3(0, 0, 0));
  EXPECT_EQ(p[1], glm::vec3(5, 5, 5));
  EXPECT_EQ(p[2], glm::vec3(0, 1, 0));
  EXPECT_EQ(p[3], glm::vec3(7, 7, 7));
}

TEST(LoadAccessors, SparseAccessorWithoutBufferViewStartsFromZeros) {
  GltfBuilder b;
  const int idx = b.view(std::vector<uint8_t>{2, 0, 0, 0});
  const int val = b.view(std::vector<float>{1, 2, 3});
  const int pos = b.accessor({{"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                              {"sparse", {{"count", 1}, {"indices", {{"bufferView", idx}, {"componentType", 5121}}},
                                          {"values", {{"bufferView", val}}}}}});
  b.doc["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"mode", 0}}})}}});
  b.doc["nodes"] = json::array({{{"mesh", 0}}});
  const Asset asset = b.load();
  const auto& p = asset.meshes[0].primitives[0].positions;
  EXPECT_EQ(p[0], glm::vec3(0));
  EXPECT_EQ(p[2], glm::vec3(1, 2, 3));
}

TEST(LoadPrimitives, NonTriangleModesAreCarriedThroughWithoutGeneratedNormals) {
  GltfBuilder b = triangle(false);
  b.doc["meshes"][0]["primitives"][0]["mode"] = 1;  // LINES
  const Asset asset = b.load();
  EXPECT_EQ(asset.meshes[0].primitives[0].mode, PrimitiveMode::kLines);
  EXPECT_TRUE(asset.meshes[0].primitives[0].normals.empty());
}

TEST(LoadPrimitives, MissingNormalsAreGeneratedSmooth) {
  const Asset asset = triangle(false).load();
  const Primitive& p = asset.meshes[0].primitives[0];
  EXPECT_TRUE(p.normals_generated);
  ASSERT_EQ(p.normals.size(), 3u);
  for (const glm::vec3& n : p.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // counter-clockwise in xy: +z
}

TEST(LoadSkins, MissingInverseBindMatricesAreIdentity) {
  const Asset asset = triangle().load();
  ASSERT_EQ(asset.skins.size(), 1u);
  for (const Mat4<double>& m : asset.skins[0].inverse_bind) EXPECT_EQ(m, Mat4<double>(1.0));
}

TEST(LoadSkins, SkinnedMeshNodeTransformIsIgnored) {
  // The mesh node has translation (5, 5, 5); joint 1 (node 2) sits at (0, 1, 0) with identity inverse
  // bind matrices, so vertex 0 (all on joint 0 = node 1 at the origin) stays at the origin, and vertex 2
  // (all on joint 1) moves by (0, 1, 0).
  const Asset asset = triangle().load();
  const Pose pose = sample_pose(asset, nullptr, 0);
  const std::vector<MeshInstance> inst = mesh_instances(asset, choose_scene(asset, -1));
  ASSERT_EQ(inst.size(), 1u);
  const JointTransforms jt = joint_transforms(asset.skins[0], pose);
  const DeformedPrimitive d = deform_primitive(asset, inst[0], 0, pose, &jt, BlendMode::kLbs);
  EXPECT_EQ(d.positions[0], Vec3<double>(0, 0, 0));
  EXPECT_NEAR(glm::distance(d.positions[2], Vec3<double>(0, 2, 0)), 0, 1e-12);     // all on joint 1: +(0,1,0)
  EXPECT_NEAR(glm::distance(d.positions[1], Vec3<double>(1, 0.8, 0)), 0, 1e-6);    // 0.2/0.8 blend
}

TEST(LoadWarnings, IgnoredSkinnedMeshTransformAndNonUnitRotationAreReported) {
  GltfBuilder b = triangle();
  b.doc["nodes"][2]["rotation"] = {0, 0, 0, 2};  // a joint with a rotation of length 2
  const Asset asset = b.load();
  ASSERT_EQ(asset.warnings.size(), 1u);
  EXPECT_EQ(asset.warnings[0], "node 2: rotation is not a unit quaternion; it is normalized");
  // The ignored transform is a notice (glTF defines it), which only some commands print.
  ASSERT_EQ(asset.notices.size(), 1u);
  EXPECT_EQ(asset.notices[0], "1 skinned mesh node has a transform (its own or a parent's); glTF ignores it (§3.7.3.1): node 0");
  EXPECT_EQ(asset.nodes[2].local.rotation, Quat<double>(1, 0, 0, 0));

  GltfBuilder clean = triangle();
  clean.doc["nodes"][0].erase("translation");
  EXPECT_TRUE(clean.load().warnings.empty());
  EXPECT_TRUE(clean.load().notices.empty());
}

TEST(LoadWarnings, SkinnedMeshTransformsAreOneNoticePerFile) {
  // Three more skinned mesh nodes under a moved parent (node 3), and one under an unmoved one (node 7):
  // one notice counting the four moved ones, not a line per node.
  GltfBuilder b = triangle();
  b.doc["nodes"].push_back({{"translation", {0, 0, 1}}, {"children", {4, 5, 6}}});
  for (int i = 0; i < 3; ++i) b.doc["nodes"].push_back({{"mesh", 0}, {"skin", 0}});
  b.doc["nodes"].push_back({{"children", {8}}});
  b.doc["nodes"].push_back({{"mesh", 0}, {"skin", 0}, {"name", "still"}});
  const Asset asset = b.load();
  EXPECT_TRUE(asset.warnings.empty());
  ASSERT_EQ(asset.notices.size(), 1u);
  EXPECT_EQ(asset.notices[0],
            "4 skinned mesh nodes have a transform (of their own or a parent's); glTF ignores it (§3.7.3.1): node 0, node 4, "
            "node 5, node 6");
}

TEST(LoadScenes, SceneChoiceFollowsTheFileAndTheRequest) {
  GltfBuilder b = triangle(false);
  b.doc["nodes"].push_back({{"mesh", 0}, {"translation", {1, 0, 0}}});
  b.doc["scenes"] = json::array({{{"nodes", {0}}}, {{"nodes", {1, 0}}}});
  b.doc["scene"] = 1;
  const Asset asset = b.load();
  EXPECT_EQ(choose_scene(asset, -1), 1);
  EXPECT_EQ(mesh_instances(asset, 1).size(), 2u);
  EXPECT_EQ(mesh_instances(asset, 0).size(), 1u);
  EXPECT_THROW(choose_scene(asset, 2), InputError);
}

TEST(LoadErrors, MessagesNameThePartThatIsWrong) {
  GltfBuilder joints = triangle();
  joints.doc["skins"][0]["joints"] = {1};  // joint index 1 is now out of range
  try {
    joints.load();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uses joint 1, but skin 0 has 1 joints"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
}

// ---------------------------------------------------------------------------------------------------
// Appearance and cameras: what the renderer reads, every index checked.

// The triangle (unskinned) with TEXCOORD_0/1, a COLOR_0 of `color_type` ("VEC3" float or "VEC4" unsigned
// short normalized), a textured material, and a perspective and an orthographic camera on two nodes.
GltfBuilder textured_triangle(const std::string& color_type) {
  GltfBuilder b = triangle(false);
  json& attributes = b.doc["meshes"][0]["primitives"][0]["attributes"];
  attributes["TEXCOORD_0"] = b.accessor({{"bufferView", b.view(std::vector<float>{0, 0, 1, 0, 0, 1})},
                                         {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  // Normalized unsigned bytes, as §3.7.2.1 allows for texture coordinates: 255 = 1.
  // Vertex attributes are 4-byte aligned (§3.6.2.4): two bytes of padding per element, stride 4.
  attributes["TEXCOORD_1"] = b.accessor({{"bufferView", b.view(std::vector<uint8_t>{0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0}, 4)},
                                         {"componentType", 5121}, {"normalized", true}, {"count", 3}, {"type", "VEC2"}});
  if (color_type == "VEC3")
    attributes["COLOR_0"] = b.accessor({{"bufferView", b.view(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1})},
                                        {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  else
    attributes["COLOR_0"] = b.accessor({{"bufferView", b.view(std::vector<uint16_t>{65535, 0, 0, 0, 0, 65535, 0, 32768, 0, 0, 65535, 65535})},
                                        {"componentType", 5123}, {"normalized", true}, {"count", 3}, {"type", "VEC4"}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["materials"] = json::array({{{"name", "skin"},
                                     {"alphaMode", "MASK"},
                                     {"alphaCutoff", 0.25},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}},
                                                               {"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}}}});
  b.doc["textures"] = json::array({{{"source", 0}, {"sampler", 0}}});
  b.doc["samplers"] = json::array({{{"magFilter", 9728}, {"wrapS", 33071}}});
  // A PNG signature is enough: the loader keeps the bytes, only the renderer decodes them.
  b.doc["images"] = json::array({{{"name", "albedo"}, {"mimeType", "image/png"},
                                  {"bufferView", b.view(std::vector<uint8_t>{0x89, 'P', 'N', 'G', 13, 10, 26, 10})}}});
  b.doc["cameras"] = json::array({{{"name", "persp"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}},
                                  {{"type", "orthographic"},
                                   {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0}, {"zfar", 10}}}}});
  b.doc["nodes"].push_back({{"name", "cam_a"}, {"camera", 0}});
  b.doc["nodes"].push_back({{"name", "cam_b"}, {"camera", 1}});
  b.doc["scenes"][0]["nodes"] = {0, 1, 2};
  return b;
}

TEST(LoadAppearance, MaterialTextureSamplerImageAndVertexColorsAreKept) {
  const Asset asset = textured_triangle("VEC3").load();
  const Primitive& p = asset.meshes[0].primitives[0];
  ASSERT_EQ(p.uv0.size(), 3u);
  ASSERT_EQ(p.uv1.size(), 3u);
  EXPECT_EQ(p.uv1[1], glm::vec2(1, 0));
  ASSERT_EQ(p.colors.size(), 3u);
  EXPECT_EQ(p.colors[1], glm::vec4(0, 1, 0, 1)) << "RGB colors get alpha 1";
  ASSERT_EQ(asset.materials.size(), 1u);
  const Material& m = asset.materials[0];
  EXPECT_EQ(m.base_color, glm::vec4(0.5f, 0.25f, 1, 1));
  EXPECT_EQ(m.base_color_texture.texture, 0);
  EXPECT_EQ(m.base_color_texture.texcoord, 1);
  EXPECT_EQ(m.alpha_mode, AlphaMode::kMask);
  EXPECT_EQ(m.alpha_cutoff, 0.25f);
  ASSERT_EQ(asset.textures.size(), 1u);
  EXPECT_EQ(asset.textures[0].image, 0);
  EXPECT_EQ(asset.textures[0].sampler.mag_filter, 9728);
  EXPECT_EQ(asset.textures[0].sampler.min_filter, 0) << "left to the viewer";
  EXPECT_EQ(asset.textures[0].sampler.wrap_s, 33071);
  EXPECT_EQ(asset.textures[0].sampler.wrap_t, 10497) << "REPEAT by default";
  ASSERT_EQ(asset.images.size(), 1u);
  EXPECT_EQ(asset.images[0].name, "albedo");
  EXPECT_EQ(asset.images[0].mime_type, "image/png");
  EXPECT_EQ(asset.images[0].bytes.size(), 8u);
  EXPECT_TRUE(asset.images[0].uri.empty()) << "embedded";
}

TEST(LoadAppearance, NormalizedRgbaColorsDecodeToUnitRange) {
  const Asset asset = textured_triangle("VEC4").load();
  const std::vector<glm::vec4>& c = asset.meshes[0].primitives[0].colors;
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], glm::vec4(1, 0, 0, 0));
  EXPECT_FLOAT_EQ(c[1].w, 32768.0f / 65535.0f);
}

TEST(LoadCameras, PerspectiveAndOrthographicCamerasAndTheirNodes) {
  const Asset asset = textured_triangle("VEC3").load();
  ASSERT_EQ(asset.cameras.size(), 2u);
  EXPECT_EQ(asset.cameras[0].name, "persp");
  EXPECT_FALSE(asset.cameras[0].orthographic);
  EXPECT_DOUBLE_EQ(asset.cameras[0].yfov, 0.7);
  EXPECT_EQ(asset.cameras[0].aspect_ratio, 0) << "the viewport's";
  EXPECT_EQ(asset.cameras[0].zfar, 0) << "infinite";
  EXPECT_TRUE(asset.cameras[1].orthographic);
  EXPECT_EQ(asset.cameras[1].xmag, 2);
  EXPECT_EQ(asset.cameras[1].zfar, 10);
  EXPECT_EQ(asset.nodes[0].camera, -1);
  EXPECT_EQ(asset.nodes[1].camera, 0);
  EXPECT_EQ(asset.nodes[2].camera, 1);
}

// Appearance does not change the deformation: a broken part loads with a warning naming it, and is dropped.
// (tinygltf itself refuses an unknown camera type: that file is an error.)
TEST(LoadWarnings, BadAppearanceAndCamerasAreDroppedWithAWarning) {
  struct Case {
    const char* expected;
    std::function<void(json&)> edit;
    std::function<bool(const Asset&)> dropped;
  };
  const std::vector<Case> cases = {
      {"material 0 baseColorTexture: texture 3 does not exist; it is drawn without the texture",
       [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3; },
       [](const Asset& a) { return a.materials[0].base_color_texture.texture == -1; }},
      {"material 0: alphaMode 'CLEAR' is not OPAQUE, MASK or BLEND; it is drawn opaque",
       [](json& d) { d["materials"][0]["alphaMode"] = "CLEAR"; },
       [](const Asset& a) { return a.materials[0].alpha_mode == AlphaMode::kOpaque; }},
      {"material 0: alphaCutoff must be at least 0; 0.5 is used", [](json& d) { d["materials"][0]["alphaCutoff"] = -1; },
       [](const Asset& a) { return a.materials[0].alpha_cutoff == 0.5f; }},
      {"material 0: baseColorFactor must be 4 numbers in [0, 1]; white is used",
       [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2, 0, 0, 1}; },
       [](const Asset& a) { return a.materials[0].base_color == glm::vec4(1.0f); }},
      {"mesh 0 primitive 0: material 4 does not exist; the default material is used",
       [](json& d) { d["meshes"][0]["primitives"][0]["material"] = 4; },
       [](const Asset& a) { return a.meshes[0].primitives[0].material == -1; }},
      {"texture 0: image 5 does not exist; textures using it are not drawn", [](json& d) { d["textures"][0]["source"] = 5; },
       [](const Asset& a) { return a.textures[0].image == -1; }},
      {"texture 0: sampler 2 does not exist; the default sampler is used", [](json& d) { d["textures"][0]["sampler"] = 2; },
       [](const Asset& a) { return a.textures[0].sampler.mag_filter == 0 && a.textures[0].sampler.wrap_s == 10497; }},
      {"sampler 0: magFilter 9986 must be one of 9728, 9729; the default is used",
       [](json& d) { d["samplers"][0]["magFilter"] = 9986; },
       [](const Asset& a) { return a.textures[0].sampler.mag_filter == 0; }},
      {"sampler 0: wrapT 1 must be one of 33071, 33648, 10497; REPEAT is used", [](json& d) { d["samplers"][0]["wrapT"] = 1; },
       [](const Asset& a) { return a.textures[0].sampler.wrap_t == 10497 && a.textures[0].sampler.wrap_s == 33071; }},
      {"camera 0: yfov must be above 0; it cannot be rendered through",
       [](json& d) { d["cameras"][0]["perspective"]["yfov"] = 0; },
       [](const Asset& a) { return !a.cameras[0].problem.empty() && a.nodes[1].camera == 0; }},
      {"camera 0: znear must be above 0", [](json& d) { d["cameras"][0]["perspective"]["znear"] = 0; },
       [](const Asset& a) { return !a.cameras[0].problem.empty(); }},
      {"camera 0: zfar must be above znear", [](json& d) { d["cameras"][0]["perspective"]["zfar"] = 0.05; },
       [](const Asset& a) { return !a.cameras[0].problem.empty(); }},
      {"camera 1: xmag and ymag must not be 0", [](json& d) { d["cameras"][1]["orthographic"]["ymag"] = 0; },
       [](const Asset& a) { return !a.cameras[1].problem.empty() && a.cameras[0].problem.empty(); }},
      {"camera 1: zfar must be above znear", [](json& d) { d["cameras"][1]["orthographic"]["zfar"] = 0; },
       [](const Asset& a) { return !a.cameras[1].problem.empty(); }},
      {"node 2: camera 7 does not exist; it is ignored", [](json& d) { d["nodes"][2]["camera"] = 7; },
       [](const Asset& a) { return a.nodes[2].camera == -1; }},
      {"COLOR_0 has 2 elements, POSITION has 3; COLOR_0 is ignored",
       [](json& d) { d["accessors"][d["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].get<size_t>()]["count"] = 2; },
       [](const Asset& a) { return a.meshes[0].primitives[0].colors.empty(); }},
      {"TEXCOORD_1 (accessor 2): has unsigned byte components that are not normalized; TEXCOORD_1 is ignored", [](json& d) {
         d["accessors"][d["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"].get<size_t>()].erase("normalized");
       },
       [](const Asset& a) { return a.meshes[0].primitives[0].uv1.empty() && !a.meshes[0].primitives[0].uv0.empty(); }},
  };
  for (const Case& c : cases) {
    GltfBuilder b = textured_triangle("VEC3");
    c.edit(b.doc);
    try {
      const Asset asset = b.load();
      const bool warned = std::any_of(asset.warnings.begin(), asset.warnings.end(), [&](const std::string& w) {
        return w.find(c.expected) != std::string::npos;
      });
      std::string all;
      for (const std::string& w : asset.warnings) all += "\n  " + w;
      EXPECT_TRUE(warned) << c.expected << "\nwarnings:" << all;
      EXPECT_TRUE(c.dropped(asset)) << c.expected;
      EXPECT_EQ(asset.meshes[0].primitives[0].positions.size(), 3u) << "the geometry still loads";
    } catch (const std::exception& e) {
      ADD_FAILURE() << c.expected << ": " << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// The shared sample models: every one loads, and `info` reports the facts of shared/testdata/README.md.

struct ModelFacts {
  const char* file;
  size_t vertices, joint_nodes, skins;
  int max_influences;
  std::vector<std::pair<const char*, double>> clips;  // name, duration (last key)
  size_t morph_targets;                               // on the first morphed mesh, 0 when none
};

const std::vector<ModelFacts>& shared_models() {
  static const std::vector<ModelFacts> facts = {
      {"RiggedSimple/RiggedSimple.glb", 160, 2, 1, 2, {{"animation0", 2.0833}}, 0},
      {"RiggedSimple/glTF/RiggedSimple.gltf", 160, 2, 1, 2, {{"animation0", 2.0833}}, 0},
      {"RiggedFigure/RiggedFigure.glb", 370, 19, 1, 4, {{"animation0", 1.25}}, 0},
      {"CesiumMan/CesiumMan.glb", 3273, 19, 1, 4, {{"animation0", 2.0}}, 0},
      {"SimpleSkin/SimpleSkin.gltf", 10, 2, 1, 2, {{"animation0", 5.5}}, 0},
      {"Fox/Fox.glb", 1728, 24, 1, 4, {{"Survey", 3.4167}, {"Walk", 0.7083}, {"Run", 1.1583}}, 0},
      {"BrainStem/BrainStem.glb", 34159, 18, 1, 1, {{"animation0", 34.88}}, 0},
      {"RecursiveSkeletons/RecursiveSkeletons.glb", 40, 840, 84, 1, {{"Track0", 2.0}}, 0},
      {"raylib_robot/robot.glb", 7218, 43, 1, 4, {{"Robot_Dance", 3.3333}, {"Robot_Wave", 1.8333}}, 0},
      {"raylib_greenman/greenman.glb", 196, 12, 1, 4, {{"0_pose", 0.1667}, {"1_idle", 2.5}, {"3_attack", 0.8333}}, 0},
      {"InterpolationTest/InterpolationTest.glb", 220, 0, 0, 0, {{"Step Scale", 1.6667}, {"Linear Rotation", 1.7083}}, 0},
      {"AnimatedMorphCube/AnimatedMorphCube.glb", 24, 0, 0, 0, {{"Square", 4.2}}, 2},
      {"SimpleMorph/SimpleMorph.gltf", 3, 0, 0, 0, {{"animation0", 4.0}}, 2},
  };
  return facts;
}

class SharedModel : public testing::TestWithParam<ModelFacts> {};

TEST_P(SharedModel, LoadsAndReportsTheFactsOfTheSharedReadme) {
  const fs::path path = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / GetParam().file;
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const ModelFacts& want = GetParam();
  const AssetFacts f = describe(load_asset(path.string()));
  EXPECT_EQ(f.vertices, want.vertices);
  EXPECT_EQ(f.joint_nodes, want.joint_nodes);
  EXPECT_EQ(f.skins.size(), want.skins);
  int influences = 0;
  for (const SkinnedMeshFacts& m : f.skinned_meshes) influences = std::max(influences, m.max_influences);
  EXPECT_EQ(influences, want.max_influences);
  for (const auto& [name, duration] : want.clips) {
    // An init-capture: clang 14 (the sanitize build) cannot capture a structured binding.
    const auto it = std::find_if(f.clips.begin(), f.clips.end(), [&wanted = name](const ClipFacts& c) { return c.name == wanted; });
    ASSERT_NE(it, f.clips.end()) << "clip " << name;
    EXPECT_NEAR(it->duration, duration, 1e-3) << name;
  }
  EXPECT_EQ(f.morph_targets.empty() ? 0 : f.morph_targets.front().targets, want.morph_targets);
}

INSTANTIATE_TEST_SUITE_P(All, SharedModel, testing::ValuesIn(shared_models()),
                         [](const testing::TestParamInfo<ModelFacts>& param) {
                           std::string name = param.param.file;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(SharedModelFiles, GlbAndGltfWithExternalBufferLoadTheSameData) {
  const fs::path dir = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "RiggedSimple";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared test data not found: " << dir;
  const Asset glb = load_asset((dir / "RiggedSimple.glb").string());
  const Asset gltf = load_asset((dir / "glTF" / "RiggedSimple.gltf").string());
  ASSERT_EQ(glb.meshes.size(), gltf.meshes.size());
  EXPECT_EQ(glb.meshes[0].primitives[0].positions, gltf.meshes[0].primitives[0].positions);
  EXPECT_EQ(glb.meshes[0].primitives[0].weights, gltf.meshes[0].primitives[0].weights);
}

TEST(SharedModelFiles, MissingExternalBufferIsAnError) {
  const fs::path src = fs::path(DQSKIN_SHARED_TESTDATA_DIR) / "RiggedSimple" / "glTF" / "RiggedSimple.gltf";
  if (!fs::exists(src)) GTEST_SKIP() << "shared test data not found: " << src;
  const fs::path dir = fs::temp_directory_path() / ("dqskin_load_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(src, dir / "RiggedSimple.gltf", fs::copy_options::overwrite_existing);  // without its .bin
  EXPECT_THROW(load_asset((dir / "RiggedSimple.gltf").string()), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dqskin
