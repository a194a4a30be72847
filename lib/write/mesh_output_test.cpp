#include "dqskin/load.hpp"
#include "mesh_output.hpp"
#include "../test_support/ply_test_reader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

struct Rig {
  Asset asset;
  std::vector<MeshInstance> instances;
  DeformedFrame frame;
  DeformedBatch batch;
};

Rig two_skins() {
  Rig r;
  r.asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf");
  r.instances = mesh_instances(r.asset, choose_scene(r.asset, -1));
  r.frame = deform_frame(r.asset, r.instances, sample_pose(r.asset, &r.asset.clips[0], 0.5), BlendMode::kDqs);
  r.batch = to_batch(std::span<const DeformedFrame>(&r.frame, 1), 0);
  return r;
}

fs::path temporary(const std::string& name) {
  return fs::temp_directory_path() / ("dqskin_" + std::to_string(::getpid()) + "_" + name);
}

TEST(WritePly, ReadsBackAsTheDeformedFrame) {
  const Rig r = two_skins();
  const MergedMesh mesh = merge_frame(r.asset, r.instances, frame_view(r.batch, 0));

  const fs::path path = temporary("frame.ply");
  std::ofstream(path, std::ios::binary) << encode_ply(mesh);
  const PlyFile ply = read_ply(path);
  fs::remove(path);

  ASSERT_EQ(ply.vertex_properties, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "s", "t"}));
  // Both instances' vertices, in scene order and accessor order, as the deformer gave them.
  size_t v = 0;
  for (const DeformedPrimitive& p : r.frame.primitives) {
    for (size_t i = 0; i < p.positions.size(); ++i, ++v) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(ply.vertex_data[v * 8 + size_t(c)], float(p.positions[i][c]));
        EXPECT_EQ(ply.vertex_data[v * 8 + 3 + size_t(c)], float(p.normals[i][c]));
      }
    }
  }
  EXPECT_EQ(v * 8, ply.vertex_data.size());
  EXPECT_EQ(ply.faces, mesh.triangles);
  size_t triangles = 0;
  for (const MeshInstance& inst : r.instances)
    for (const Primitive& p : r.asset.meshes[size_t(inst.mesh)].primitives) triangles += p.indices.size() / 3;
  EXPECT_EQ(ply.faces.size(), triangles * 3);
  // The second instance's faces point at its own vertices, after the first's.
  EXPECT_GE(ply.faces.back(), r.frame.primitives[0].positions.size());
}

TEST(WriteObj, ReadsBackAsTheDeformedFrameWithOneObjectPerPrimitive) {
  const Rig r = two_skins();
  const MergedMesh mesh = merge_frame(r.asset, r.instances, frame_view(r.batch, 0));
  std::istringstream obj(encode_obj(mesh, r.asset, "materials.mtl"));
  std::vector<float> v, vn, vt;
  std::vector<uint32_t> faces;
  size_t objects = 0, usemtl = 0;
  std::string line;
  while (std::getline(obj, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    float x;
    if (tag == "v") while (words >> x) v.push_back(x);
    if (tag == "vn") while (words >> x) vn.push_back(x);
    if (tag == "vt") while (words >> x) vt.push_back(x);
    if (tag == "o") ++objects;
    if (tag == "usemtl") ++usemtl;
    if (tag == "f") {
      std::string corner;
      while (words >> corner) {
        const uint32_t i = uint32_t(std::stoul(corner));
        EXPECT_EQ(corner, std::to_string(i) + "/" + std::to_string(i) + "/" + std::to_string(i));
        faces.push_back(i - 1);
      }
    }
  }
  ASSERT_EQ(v.size(), mesh.positions.size() * 3);
  ASSERT_EQ(vn.size(), mesh.normals.size() * 3);
  ASSERT_EQ(vt.size(), mesh.uv0.size() * 2);
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(v[3 * i + size_t(c)], mesh.positions[i][c]) << "shortest round-trip form reads back exactly";
      EXPECT_EQ(vn[3 * i + size_t(c)], mesh.normals[i][c]);
    }
  for (size_t i = 0; i < mesh.uv0.size(); ++i) EXPECT_EQ(vt[2 * i + 1], 1.0f - mesh.uv0[i].y);
  EXPECT_EQ(faces, mesh.triangles);
  EXPECT_EQ(objects, mesh.groups.size());
  EXPECT_EQ(usemtl, mesh.groups.size());
}

TEST(WriteObj, MaterialLibraryHasEveryMaterialWithUniqueNames) {
  Asset asset;
  auto material = [](std::string name, glm::vec4 base_color) {
    Material m;
    m.name = std::move(name);
    m.base_color = base_color;
    return m;
  };
  asset.materials = {material("skin", glm::vec4(0.5f, 0.25f, 1.0f, 0.75f)), material("skin", glm::vec4(1.0f)),
                     material("", glm::vec4(1.0f)), material("two words", glm::vec4(1.0f))};
  EXPECT_EQ(obj_material_name(asset, 0), "skin");
  EXPECT_EQ(obj_material_name(asset, 1), "material_1");
  EXPECT_EQ(obj_material_name(asset, 2), "material_2");
  EXPECT_EQ(obj_material_name(asset, 3), "two_words");
  EXPECT_EQ(obj_material_name(asset, -1), "dqskin_default");
  const std::string mtl = encode_mtl(asset);
  EXPECT_NE(mtl.find("newmtl skin\nKd 0.5 0.25 1\nd 0.75\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("newmtl dqskin_default\nKd 1 1 1\nd 1\n"), std::string::npos) << mtl;
  EXPECT_EQ(encode_mtl(Asset{}), "");
}

// The frame encoder bake uses writes the bytes of encode_ply/encode_obj of merge_frame: on every rig and
// the shared models with several primitives, materials, no UVs or no normals, with and without a
// material library, frame after frame into one reused buffer.
TEST(MeshFrameEncoder, WritesTheBytesOfMergeFrameAndEncode) {
  std::vector<std::string> paths;
  for (const char* rig : {"twisted_cylinder", "bending_arm", "morph_skin", "two_skins", "eight_influences",
                          "textured_cylinder", "nonuniform_scale"})
    paths.push_back(std::string(DQSKIN_TESTDATA_DIR) + "/" + rig + ".gltf");
  for (const char* model : {"BrainStem/BrainStem.glb", "Fox/Fox.glb", "SimpleSkin/SimpleSkin.gltf",
                            "AnimatedMorphCube/AnimatedMorphCube.glb", "raylib_robot/robot.glb"}) {
    const std::string path = std::string(DQSKIN_SHARED_TESTDATA_DIR) + "/" + model;
    if (fs::exists(path)) paths.push_back(path);
    else std::cout << "  skipped, test data not found: " << path << "\n";
  }
  for (const std::string& path : paths) {
    const Asset asset = load_asset(path);
    const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
    for (const std::string mtl : {"", "materials.mtl"}) {
      const MeshFrameEncoder encoder(asset, instances, mtl);
      std::string ply, obj;  // reused, as bake reuses its buffers
      for (double t : {0.0, 0.37, 0.9}) {
        const Clip* clip = asset.clips.empty() ? nullptr : &asset.clips[0];
        const DeformedFrame frame = deform_frame(asset, instances, sample_pose(asset, clip, t), BlendMode::kDqs);
        const DeformedBatch batch = to_batch(std::span<const DeformedFrame>(&frame, 1), 0);
        const FrameView view = frame_view(batch, 0);
        const MergedMesh mesh = merge_frame(asset, instances, view);
        encoder.encode_ply(view, ply);
        encoder.encode_obj(view, obj);
        EXPECT_TRUE(ply == encode_ply(mesh)) << path << " t=" << t;
        EXPECT_EQ(ply.size(), encoder.ply_size()) << path;
        EXPECT_TRUE(obj == encode_obj(mesh, asset, mtl)) << path << " t=" << t << " mtl '" << mtl << "'";
      }
    }
  }
}

}  // namespace
}  // namespace dqskin
