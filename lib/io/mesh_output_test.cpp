#include "dqskin/error.hpp"
#include "dqskin/load.hpp"
#include "dqskin/mesh_output.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace dqskin {
namespace {

namespace fs = std::filesystem;

// A small reader for what write_ply writes: the header's counts and properties, then the binary body.
struct PlyFile {
  std::vector<std::string> vertex_properties;
  std::vector<float> vertex_data;  // vertex count × properties
  std::vector<uint32_t> faces;     // 3 per face
};

PlyFile read_ply(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  PlyFile ply;
  size_t vertices = 0, faces = 0;
  std::string element;
  std::getline(in, line);
  EXPECT_EQ(line, "ply");
  std::getline(in, line);
  EXPECT_EQ(line, "format binary_little_endian 1.0");
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "element") {
      words >> element;
      (element == "vertex" ? vertices : faces) = std::stoul(line.substr(line.rfind(' ') + 1));
    } else if (word == "property" && element == "vertex") {
      words >> type >> name;
      EXPECT_EQ(type, "float");
      ply.vertex_properties.push_back(name);
    }
  }
  ply.vertex_data.resize(vertices * ply.vertex_properties.size());
  in.read(reinterpret_cast<char*>(ply.vertex_data.data()), std::streamsize(ply.vertex_data.size() * 4));
  for (size_t f = 0; f < faces; ++f) {
    unsigned char n = 0;
    in.read(reinterpret_cast<char*>(&n), 1);
    EXPECT_EQ(n, 3);
    uint32_t idx[3];
    in.read(reinterpret_cast<char*>(idx), 12);
    ply.faces.insert(ply.faces.end(), idx, idx + 3);
  }
  EXPECT_TRUE(in.good());
  EXPECT_EQ(in.peek(), EOF) << "nothing after the faces";
  return ply;
}

TEST(WritePly, ReadsBackAsTheDeformedFrame) {
  const Asset asset = load_asset(std::string(DQSKIN_TESTDATA_DIR) + "/two_skins.gltf");
  const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
  const DeformedFrame frame = deform_frame(asset, instances, sample_pose(asset, &asset.clips[0], 0.5), BlendMode::kDqs);
  const MergedMesh mesh = merge_frame(asset, instances, frame);

  const fs::path path = fs::temp_directory_path() / ("dqskin_ply_" + std::to_string(::getpid()) + ".ply");
  write_ply(path.string(), mesh);
  const PlyFile ply = read_ply(path);
  fs::remove(path);

  ASSERT_EQ(ply.vertex_properties, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "s", "t"}));
  // Both instances' vertices, in scene order and accessor order, as the deformer gave them.
  size_t v = 0;
  for (const DeformedPrimitive& p : frame.primitives) {
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
  for (const MeshInstance& inst : instances)
    for (const Primitive& p : asset.meshes[size_t(inst.mesh)].primitives) triangles += p.indices.size() / 3;
  EXPECT_EQ(ply.faces.size(), triangles * 3);
  // The second instance's faces point at its own vertices, after the first's.
  EXPECT_GE(ply.faces.back(), frame.primitives[0].positions.size());
}

TEST(WritePly, UnwritablePathIsAnOutputError) {
  EXPECT_THROW(write_ply("/nonexistent-dqskin-dir/frame.ply", MergedMesh{}), OutputError);
}

}  // namespace
}  // namespace dqskin
