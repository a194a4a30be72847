// The meshes beside textures (rest.glb and the profiles' rest meshes, bones_mesh.glb) carry the source's
// look: read back with dqskin's loader, each primitive keeps its material, UVs and COLOR_0, and the file
// the source's materials, textures, samplers and images. With DQSKIN_REST_GLB_SAMPLE_DIR set the files are
// also written there, for the Khronos glTF-Validator (CTest's rest_glb_validator).
#include "rest_glb.hpp"
#include "bones_mesh_glb.hpp"
#include "../write/glb_appearance.hpp"
#include "../test_support/scratch_dir.hpp"
#include "../test_support/test_models.hpp"

#include "dqskin/load.hpp"
#include "dqskin/skinning.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>

namespace dqskin::texture {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

Asset load_keeping_source(const std::string& path) {
  LoadOptions o;
  o.keep_source = true;
  return load_asset(path, o);
}

// The loader's bind-space positions and normals as one frame, in the writers' layout: the rest mesh's
// positions do not matter here, only its look.
DeformedBatch bind_frame(const Asset& asset, const std::vector<MeshInstance>& instances) {
  DeformedBatch batch;
  batch.frame_count = 1;
  for (const MeshInstance& inst : instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) {
      DeformedBatch::Primitive out;
      out.vertices = p.vertex_count();
      for (const glm::vec3& v : p.positions) out.positions.insert(out.positions.end(), {v.x, v.y, v.z});
      for (const glm::vec3& n : p.normals) out.normals.insert(out.normals.end(), {n.x, n.y, n.z});
      batch.primitives.push_back(std::move(out));
    }
  return batch;
}

void write_sample(const std::string& name, const std::string& bytes) {
  const char* dir = std::getenv("DQSKIN_REST_GLB_SAMPLE_DIR");
  if (!dir || !*dir) return;
  fs::create_directories(dir);
  std::ofstream(fs::path(dir) / name, std::ios::binary) << bytes;
}

// `written`'s appearance is the source's: the same materials (by name and base color), textures drawing
// images of the same bytes, and each primitive (in `instances` order, skinned ones only when
// `skinned_only`) its source's material, TEXCOORD_0 and COLOR_0.
void expect_same_look(const Asset& source, const std::vector<MeshInstance>& instances, const Asset& written,
                      bool skinned_only) {
  ASSERT_EQ(written.materials.size(), source.materials.size());
  for (size_t m = 0; m < source.materials.size(); ++m) {
    EXPECT_EQ(written.materials[m].name, source.materials[m].name);
    EXPECT_EQ(written.materials[m].base_color, source.materials[m].base_color);
    const int s = source.materials[m].base_color_texture.texture, w = written.materials[m].base_color_texture.texture;
    ASSERT_EQ(w >= 0, s >= 0) << "material " << m;
    if (s < 0) continue;
    const int si = source.textures[size_t(s)].image, wi = written.textures[size_t(w)].image;
    ASSERT_GE(wi, 0) << "material " << m << ": its texture has no image";
    EXPECT_EQ(written.images[size_t(wi)].bytes, source.images[size_t(si)].bytes) << "material " << m;
  }
  ASSERT_EQ(written.meshes.size(), 1u);
  size_t next = 0;
  for (const MeshInstance& inst : instances) {
    if (skinned_only && inst.skin < 0) continue;
    for (const Primitive& src : source.meshes[size_t(inst.mesh)].primitives) {
      SCOPED_TRACE("primitive " + std::to_string(next));
      const Primitive& p = written.meshes[0].primitives.at(next++);
      EXPECT_EQ(p.material, src.material);
      if (!src.uv0.empty()) {
        EXPECT_EQ(p.uv0, src.uv0);
      }
      EXPECT_EQ(p.colors.size(), src.colors.size());
      for (size_t v = 0; v < p.colors.size() && v < src.colors.size(); ++v)
        ASSERT_EQ(p.colors[v], glm::clamp(src.colors[v], 0.0f, 1.0f)) << "vertex " << v;
    }
  }
  EXPECT_EQ(next, written.meshes[0].primitives.size());
}

class MeshLook : public testing::TestWithParam<const char*> {};

TEST_P(MeshLook, RestAndBonesMeshesKeepTheSourcesMaterialsTexturesAndUvs) {
  const std::string param = GetParam();
  const fs::path path = testing_support::model_path(param);
  if (!fs::exists(path)) GTEST_SKIP() << "shared test data not found: " << path;
  const Asset asset = load_keeping_source(path.string());
  ASSERT_FALSE(asset.materials.empty()) << "a model with a look to keep";
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const glb::Appearance look = glb::read_look(asset);
  const DeformedBatch rest = bind_frame(asset, instances);
  size_t vertices = 0;
  for (const auto& p : rest.primitives) vertices += p.vertices;
  const VatLayout layout = plan_vat_layout(VatFormat{}, vertices, 3, 1024, false, "t");
  const testing_support::ScratchDir dir("mesh_look");
  const std::string stem = fs::path(param).stem().string();

  const std::string rest_bytes = encode_rest_glb(asset, instances, frame_view(rest, 0), layout, "rest", &look);
  EXPECT_EQ(rest_bytes, encode_rest_glb(asset, instances, frame_view(rest, 0), layout, "rest", &look));  // deterministic
  write_sample(stem + "_rest_look.glb", rest_bytes);
  std::ofstream(dir.path() / "rest.glb", std::ios::binary) << rest_bytes;
  {
    SCOPED_TRACE("rest.glb");
    expect_same_look(asset, instances, load_asset((dir.path() / "rest.glb").string()), false);
  }

  const std::string bones_bytes = encode_bones_mesh_glb(asset, instances, "mesh", &look);
  write_sample(stem + "_bones_look.glb", bones_bytes);
  std::ofstream(dir.path() / "bones.glb", std::ios::binary) << bones_bytes;
  {
    SCOPED_TRACE("bones_mesh.glb");
    expect_same_look(asset, instances, load_asset((dir.path() / "bones.glb").string()), true);
  }
}

INSTANTIATE_TEST_SUITE_P(Models, MeshLook,
                         testing::Values("textured_cylinder.gltf", "CesiumMan/CesiumMan.glb", "Fox/Fox.glb",
                                         "BrainStem/BrainStem.glb"),
                         testing_support::model_test_name);

// A material that reads the second UV set reads it at TEXCOORD_2 of the rest mesh, whose TEXCOORD_1 is the
// texel lookup: the set moves there and the material's texCoord (and its transform's) follows.
TEST(MeshLookUvSets, SecondSetMovesToTheThirdInTheRestMesh) {
  const fs::path path = testing_support::model_path("textured_cylinder.gltf");
  std::ifstream in(path);
  json doc = json::parse(in);
  json& info = doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
  info["texCoord"] = 1;
  doc["materials"][0]["emissiveTexture"] = {{"index", 0},
                                            {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}};
  doc["extensionsUsed"] = {"KHR_texture_transform"};
  json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
  attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
  const std::string text = doc.dump();
  LoadOptions o;
  o.keep_source = true;
  const Asset asset =
      load_asset_from_memory(std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), "uv1", ".", o);
  ASSERT_FALSE(asset.meshes[0].primitives[0].uv1.empty());
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const glb::Appearance look = glb::read_look(asset);
  const DeformedBatch rest = bind_frame(asset, instances);
  const VatLayout layout = plan_vat_layout(VatFormat{}, rest.primitives[0].vertices, 3, 1024, false, "t");
  const std::string bytes = encode_rest_glb(asset, instances, frame_view(rest, 0), layout, "rest", &look);
  write_sample("uv_sets_rest_look.glb", bytes);

  const testing_support::ScratchDir dir("mesh_look_uv");
  std::ofstream(dir.path() / "rest.glb", std::ios::binary) << bytes;
  const Asset back = load_asset((dir.path() / "rest.glb").string());
  const Primitive& p = back.meshes[0].primitives[0];
  EXPECT_EQ(back.materials[0].base_color_texture.texcoord, 2);
  EXPECT_EQ(p.uv0, asset.meshes[0].primitives[0].uv0);
  // TEXCOORD_2 itself: the loader reads sets 0 and 1 only, so from the file's JSON.
  const uint32_t json_length = uint32_t(uint8_t(bytes[12])) | uint32_t(uint8_t(bytes[13])) << 8 |
                               uint32_t(uint8_t(bytes[14])) << 16 | uint32_t(uint8_t(bytes[15])) << 24;
  const json written = json::parse(bytes.substr(20, json_length));
  EXPECT_TRUE(written["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_2"));
  EXPECT_EQ(written["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"], 2);
  EXPECT_EQ(written["materials"][0]["emissiveTexture"]["extensions"]["KHR_texture_transform"]["texCoord"], 2);
}

}  // namespace
}  // namespace dqskin::texture
