// Which primitives share their vertices (vertex_sharing.hpp): the same accessor for every attribute and
// morph target attribute, normals read from the file, and only within one instance.
#include "vertex_sharing.hpp"

#include <gtest/gtest.h>

namespace dqskin {
namespace {

// A primitive of `n` vertices naming `accessors` ("POSITION" → 0, ...).
Primitive primitive(size_t n, std::vector<std::pair<std::string, int>> accessors) {
  Primitive p;
  p.positions.assign(n, glm::vec3(0));
  p.normals.assign(n, glm::vec3(0, 1, 0));
  p.vertex_accessors = std::move(accessors);
  return p;
}

const std::vector<std::pair<std::string, int>> kSet = {{"NORMAL", 1}, {"POSITION", 0}, {"TEXCOORD_0", 2}};

// One node drawing mesh 0 for each of `nodes`.
Asset asset_of(Mesh mesh, int nodes) {
  Asset a;
  a.meshes.push_back(std::move(mesh));
  for (int i = 0; i < nodes; ++i) {
    Node node;
    node.name = std::to_string(i);
    node.mesh = 0;
    a.nodes.push_back(node);
  }
  return a;
}

std::vector<MeshInstance> instances(int nodes) {
  std::vector<MeshInstance> out;
  for (int i = 0; i < nodes; ++i) out.push_back({i, 0, -1});
  return out;
}

TEST(VertexSharing, PrimitivesNamingTheSameAccessorsShareTheFirstOnesVertices) {
  Mesh mesh;
  for (int i = 0; i < 3; ++i) mesh.primitives.push_back(primitive(5, kSet));
  EXPECT_EQ(vertex_data_owners(mesh), (std::vector<size_t>{0, 0, 0}));
  const SharedVertexLayout l = shared_vertex_layout(asset_of(mesh, 1), instances(1));
  EXPECT_EQ(l.vertices, 5u);
  EXPECT_EQ(l.first_vertex, (std::vector<size_t>{0, 0, 0}));
  EXPECT_TRUE(l.writes(0));
  EXPECT_FALSE(l.writes(1));
  EXPECT_FALSE(l.writes(2));
}

TEST(VertexSharing, OneDifferentAccessorKeepsThePrimitivesApart) {
  Mesh mesh;
  mesh.primitives.push_back(primitive(5, kSet));
  mesh.primitives.push_back(primitive(5, {{"NORMAL", 3}, {"POSITION", 0}, {"TEXCOORD_0", 2}}));  // NORMAL differs
  mesh.primitives.push_back(primitive(5, {{"NORMAL", 1}, {"POSITION", 0}}));                      // no TEXCOORD_0
  mesh.primitives.push_back(primitive(5, kSet));
  EXPECT_EQ(vertex_data_owners(mesh), (std::vector<size_t>{0, 1, 2, 0}));
  const SharedVertexLayout l = shared_vertex_layout(asset_of(mesh, 1), instances(1));
  EXPECT_EQ(l.vertices, 15u);
  EXPECT_EQ(l.first_vertex, (std::vector<size_t>{0, 5, 10, 0}));
}

TEST(VertexSharing, MorphTargetsAreAttributesToo) {
  Mesh mesh;
  auto with_target = kSet;
  with_target.emplace_back("0/POSITION", 7);
  mesh.primitives.push_back(primitive(5, with_target));
  mesh.primitives.push_back(primitive(5, kSet));
  with_target.back().second = 8;
  mesh.primitives.push_back(primitive(5, with_target));
  EXPECT_EQ(vertex_data_owners(mesh), (std::vector<size_t>{0, 1, 2}));
}

TEST(VertexSharing, GeneratedNormalsAndUnknownAccessorsAreNotShared) {
  Mesh mesh;
  mesh.primitives.push_back(primitive(5, kSet));
  mesh.primitives.push_back(primitive(5, kSet));
  mesh.primitives[1].normals_generated = true;  // from its own faces: not the first one's normals
  mesh.primitives.push_back(primitive(5, {}));  // not read from a file
  mesh.primitives.push_back(primitive(5, {}));
  EXPECT_EQ(vertex_data_owners(mesh), (std::vector<size_t>{0, 1, 2, 3}));
}

TEST(VertexSharing, EachInstanceWritesItsOwnVertices) {
  Mesh mesh;
  mesh.primitives.push_back(primitive(4, kSet));
  mesh.primitives.push_back(primitive(4, kSet));
  const SharedVertexLayout l = shared_vertex_layout(asset_of(mesh, 2), instances(2));
  EXPECT_EQ(l.vertices, 8u);
  EXPECT_EQ(l.owner, (std::vector<size_t>{0, 0, 2, 2}));
  EXPECT_EQ(l.first_vertex, (std::vector<size_t>{0, 0, 4, 4}));

  FrameView frame;
  frame.primitives.resize(4);
  for (size_t p = 0; p < 4; ++p) frame.primitives[p].vertices = 10 + p;
  const FrameView distinct = distinct_vertices(frame, l);
  ASSERT_EQ(distinct.primitives.size(), 2u);
  EXPECT_EQ(distinct.primitives[0].vertices, 10u);
  EXPECT_EQ(distinct.primitives[1].vertices, 12u);
}

}  // namespace
}  // namespace dqskin
