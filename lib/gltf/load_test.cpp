#include "dqskin/error.hpp"
#include "dqskin/info.hpp"
#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ---------------------------------------------------------------------------------------------------
// A tiny glTF writer: raw bytes into one buffer, accessors described in JSON, embedded as a data URI.

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[n >> 18 & 63];
    out += table[n >> 12 & 63];
    out += i + 1 < bytes.size() ? table[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

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
  ASSERT_EQ(asset.warnings.size(), 2u);
  EXPECT_EQ(asset.warnings[0], "node 2: rotation is not a unit quaternion; it is normalized");
  EXPECT_EQ(asset.warnings[1], "node 0: is skinned but has a transform of its own or of a parent; as glTF says, it is ignored");
  EXPECT_EQ(asset.nodes[2].local.rotation, Quat<double>(1, 0, 0, 0));

  GltfBuilder clean = triangle();
  clean.doc["nodes"][0].erase("translation");
  EXPECT_TRUE(clean.load().warnings.empty());
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
    const auto it = std::find_if(f.clips.begin(), f.clips.end(), [&](const ClipFacts& c) { return c.name == name; });
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
