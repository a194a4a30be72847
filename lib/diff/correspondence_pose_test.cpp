// Where the geometric diff makes its correspondence (correspondence_pose.hpp) and how it compares normals
// (normal_comparison.hpp): the criteria on hand-made surfaces, and the choice on a rig whose rest pose folds.
#include "correspondence_pose.hpp"

#include "dqskin/load.hpp"
#include "../test_support/scratch_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <vector>

namespace dqskin::diff_detail {
namespace {

// A flat grid of n × n quads in the xy plane (two triangles each), normals +z.
struct Grid {
  std::vector<glm::dvec3> positions, normals;
  std::vector<uint32_t> triangles;
};

Grid grid(int n) {
  Grid g;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) g.positions.emplace_back(x, y, 0), g.normals.emplace_back(0, 0, 1);
  auto at = [&](int x, int y) { return uint32_t(y * (n + 1) + x); };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      g.triangles.insert(g.triangles.end(), {at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y), at(x + 1, y + 1), at(x, y + 1)});
  return g;
}

// `bind` as POSITION and NORMAL store it (float).
PoseDistortion distortion(const Grid& posed, const Grid& bind, size_t first = 0) {
  std::vector<glm::vec3> positions, normals;
  for (size_t v = 0; v < bind.positions.size(); ++v)
    positions.emplace_back(glm::vec3(bind.positions[v])), normals.emplace_back(glm::vec3(bind.normals[v]));
  return primitive_distortion(posed.positions, posed.normals, positions, normals, bind.triangles, first);
}

TEST(PoseDistortion, TheBindPoseAndAUniformScaleAreNoDistortion) {
  const Grid bind = grid(10);
  EXPECT_EQ(distortion(bind, bind).distorted, 0u);
  EXPECT_EQ(distortion(bind, bind).triangles, 200u);
  Grid small = bind;  // an armature at 0.01 scale, moved and turned about z
  for (glm::dvec3& p : small.positions) p = glm::dvec3(-p.y, p.x, 0) * 0.01 + glm::dvec3(5, 0, 0);
  EXPECT_EQ(distortion(small, bind).distorted, 0u);
  EXPECT_FALSE(distortion(small, bind).degenerate());
}

TEST(PoseDistortion, AStretchUnderTwiceIsNoDistortionAndOverTwiceIs) {
  const Grid bind = grid(10);
  Grid bent = bind;
  for (glm::dvec3& p : bent.positions)
    if (p.x > 5) p.x = 5 + (p.x - 5) * 1.9;  // half the grid stretched 1.9 times along x
  EXPECT_EQ(distortion(bent, bind).distorted, 0u);
  for (glm::dvec3& p : bent.positions)
    if (p.x > 5) p.x = 5 + (p.x - 5) * 1.1;  // now 2.09 times: every triangle of that half
  EXPECT_EQ(distortion(bent, bind).distorted, 100u);
}

TEST(PoseDistortion, ACollapsedBandIsDegenerate) {
  const Grid bind = grid(10);
  Grid crushed = bind;  // the rows between y = 3 and y = 5 crushed onto y = 3: 40 of 200 triangles
  for (glm::dvec3& p : crushed.positions) p.y = p.y <= 3 ? p.y : p.y <= 5 ? 3 + (p.y - 3) * 0.01 : p.y - 2 + 0.02;
  const PoseDistortion d = distortion(crushed, bind);
  EXPECT_EQ(d.distorted, 40u);
  EXPECT_TRUE(d.degenerate());
}

TEST(PoseDistortion, AFoldThatKeepsEveryLengthIsDegenerate) {
  const Grid bind = grid(10);
  Grid folded = bind;  // mirrored about x = 5 beyond it (every length kept), normals carried as skinning does
  for (glm::dvec3& p : folded.positions)
    if (p.x > 5) p.x = 10 - p.x;
  const PoseDistortion d = distortion(folded, bind);
  EXPECT_EQ(d.distorted, 100u);
  EXPECT_TRUE(d.degenerate());
}

TEST(PoseDistortion, EverythingOnOnePointIsDegenerateAndBindTrianglesWithoutAreaDoNotCount) {
  Grid bind = grid(4);
  Grid point = bind;
  for (glm::dvec3& p : point.positions) p = glm::dvec3(1, 2, 3);
  EXPECT_EQ(distortion(point, bind).distorted, 32u);
  bind.triangles.insert(bind.triangles.end(), {0, 0, 1});  // no face at the bind pose
  EXPECT_EQ(distortion(point, bind).triangles, 32u);
}

TEST(PoseDistortion, TrianglesAreNumberedFromThePrimitivesFirstVertex) {
  Grid bind = grid(4);
  Grid point = bind;
  for (glm::dvec3& p : point.positions) p = glm::dvec3(1, 2, 3);
  for (uint32_t& v : bind.triangles) v += 1000;  // the primitive's vertices are 1000 onward in the diff's numbering
  EXPECT_EQ(distortion(point, bind, 1000).distorted, 32u);
  EXPECT_EQ(distortion(bind, bind, 1000).distorted, 0u);
}

// The bending arm with its elbow at the shoulder when not animated (its translation removed): the forearm
// folds back over the upper arm at rest, and its clip only turns the elbow, so every pose of it folds too.
const std::string kArm = std::string(DQSKIN_TESTDATA_DIR) + "/bending_arm.gltf";

DiffSide arm_side(const std::string& path) { return make_diff_side(load_asset(path), BlendMode::kDqs); }

TEST(CorrespondencePose, AWellPosedRestPoseIsUsed) {
  const DiffSide arm = arm_side(kArm);
  const CorrespondencePose pose =
      choose_correspondence_pose(arm, arm, &arm.asset.clips[0], &arm.asset.clips[0], "bend", 0, BlendMode::kDqs);
  EXPECT_EQ(pose.kind, PoseKind::kRest);
  EXPECT_EQ(pose.rest_a.distorted, 0u);
  EXPECT_EQ(&pose.of_a(arm), &arm.rest);
}

TEST(CorrespondencePose, AFoldedRestPoseAndClipFallBackToTheBindPose) {
  const testing_support::ScratchDir dir("correspondence_pose");
  nlohmann::json doc;
  std::ifstream(kArm) >> doc;
  for (nlohmann::json& node : doc["nodes"])
    if (node["name"] == "elbow") node.erase("translation");
  const std::string path = (dir.path() / "folded_arm.gltf").string();
  std::ofstream(path) << doc.dump();
  const DiffSide arm = arm_side(kArm), folded = arm_side(path);
  const CorrespondencePose pose = choose_correspondence_pose(arm, folded, &arm.asset.clips[0],
                                                             &folded.asset.clips[0], "bend", 0, BlendMode::kDqs);
  EXPECT_FALSE(pose.rest_a.degenerate());
  EXPECT_TRUE(pose.rest_b.degenerate());
  EXPECT_TRUE(pose.clip_b.degenerate());
  ASSERT_EQ(pose.kind, PoseKind::kBind);
  // At the bind pose both are what POSITION stores: the same arm.
  ASSERT_EQ(pose.a.positions.size(), pose.b.positions.size());
  for (size_t v = 0; v < pose.a.positions.size(); ++v) EXPECT_EQ(pose.a.positions[v], pose.b.positions[v]) << v;
  // Without clips there is no pose to try but the bind pose.
  EXPECT_EQ(choose_correspondence_pose(arm, folded, nullptr, nullptr, "", 0, BlendMode::kDqs).kind, PoseKind::kBind);
}

}  // namespace
}  // namespace dqskin::diff_detail
