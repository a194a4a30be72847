// bones_mesh.glb (bones_mesh_glb.hpp): every skinned primitive in bind space, with the influences the
// bone texture's joints are indexed by, read back from the GLB container itself, byte for byte.
#include "bones_mesh_glb.hpp"

#include "dqskin/load.hpp"

#include "../test_support/test_models.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace dqskin::texture {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The JSON and BIN chunks of a .glb (glTF 2.0 §4.4).
struct Glb {
  json doc;
  std::string bin;

  explicit Glb(const std::string& bytes) {
    auto u32 = [&](size_t at) {
      uint32_t v;
      std::memcpy(&v, bytes.data() + at, 4);
      return v;
    };
    EXPECT_EQ(bytes.compare(0, 4, "glTF"), 0);
    EXPECT_EQ(u32(8), bytes.size());
    const uint32_t json_length = u32(12);
    doc = json::parse(bytes.substr(20, json_length));
    if (bytes.size() > 20 + json_length) bin = bytes.substr(28 + json_length, u32(20 + json_length));
  }

  // The accessor's bytes (dqskin writes each accessor at the start of a view of its own).
  template <class T>
  std::vector<T> values(int accessor) const {
    const json& a = doc["accessors"][size_t(accessor)];
    const json& v = doc["bufferViews"][a["bufferView"].get<size_t>()];
    std::vector<T> out(v["byteLength"].get<size_t>() / sizeof(T));
    std::memcpy(out.data(), bin.data() + v["byteOffset"].get<size_t>(), out.size() * sizeof(T));
    return out;
  }
};

class BonesMeshGlb : public testing::TestWithParam<const char*> {};

TEST_P(BonesMeshGlb, CarriesTheBindPoseAndInfluencesOfEverySkinnedPrimitive) {
  const std::string param = GetParam();
  const fs::path path = testing_support::model_path(param);
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset asset = load_asset(path.string());
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const std::string bytes = encode_bones_mesh_glb(asset, instances, "mesh");
  EXPECT_EQ(bytes, encode_bones_mesh_glb(asset, instances, "mesh"));  // deterministic
  if (const char* dir = std::getenv("DQSKIN_REST_GLB_SAMPLE_DIR"); dir && *dir) {
    fs::create_directories(dir);
    std::ofstream(fs::path(dir) / (fs::path(param).stem().string() + "_bones_mesh.glb"), std::ios::binary) << bytes;
  }

  const Glb glb(bytes);
  const json& primitives = glb.doc["meshes"][0]["primitives"];
  size_t next = 0;
  for (const MeshInstance& instance : instances) {
    if (instance.skin < 0) continue;
    for (const Primitive& source : asset.meshes[size_t(instance.mesh)].primitives) {
      SCOPED_TRACE("primitive " + std::to_string(next));
      ASSERT_LT(next, primitives.size());
      const json& p = primitives[next++];
      EXPECT_EQ(p["extras"]["skin"], instance.skin);
      EXPECT_EQ(p["extras"]["bones"], "bones_skin" + std::to_string(instance.skin));
      const json& a = p["attributes"];
      const std::vector<float> positions = glb.values<float>(a["POSITION"]);
      ASSERT_EQ(positions.size(), 3 * source.vertex_count());
      EXPECT_EQ(std::memcmp(positions.data(), source.positions.data(), positions.size() * sizeof(float)), 0);
      const size_t per = size_t(source.influences);
      ASSERT_GT(per, 0u);
      EXPECT_EQ(a.contains("_JOINTS_1"), per == 8);
      for (size_t set = 0; set * 4 < per; ++set) {
        const std::vector<uint16_t> joints = glb.values<uint16_t>(a["_JOINTS_" + std::to_string(set)]);
        const std::vector<float> weights = glb.values<float>(a["_WEIGHTS_" + std::to_string(set)]);
        ASSERT_EQ(joints.size(), 4 * source.vertex_count());
        ASSERT_EQ(weights.size(), 4 * source.vertex_count());
        for (size_t v = 0; v < source.vertex_count(); ++v)
          for (size_t i = 0; i < 4; ++i) {
            ASSERT_EQ(joints[4 * v + i], source.joints[v * per + 4 * set + i]) << "vertex " << v;
            ASSERT_EQ(weights[4 * v + i], source.weights[v * per + 4 * set + i]) << "vertex " << v;
          }
      }
    }
  }
  EXPECT_EQ(next, primitives.size());
  EXPECT_GT(next, 0u);
}

INSTANTIATE_TEST_SUITE_P(Models, BonesMeshGlb,
                         testing::Values("twisted_cylinder.gltf", "two_skins.gltf", "eight_influences.gltf",
                                         "morph_skin.gltf", "CesiumMan/CesiumMan.glb", "Fox/Fox.glb",
                                         "BrainStem/BrainStem.glb", "RiggedFigure/RiggedFigure.glb",
                                         "raylib_robot/robot.glb"),
                         testing_support::model_test_name);

}  // namespace
}  // namespace dqskin::texture
