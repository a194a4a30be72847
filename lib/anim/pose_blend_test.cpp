// The reference crossfade's blended pose (anim/pose_blend.hpp, docs/DESIGN.md §3.10), on the project's rigs.
#include "pose_blend.hpp"

#include "dqskin/load.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

namespace dqskin {
namespace {

Asset rig(const std::string& name) { return load_asset((std::filesystem::path(DQSKIN_TESTDATA_DIR) / name).string()); }

Quat<double> about(const Vec3<double>& axis, double degrees) {
  return glm::angleAxis(degrees * std::numbers::pi / 180, axis);
}

// The rotation angle of a unit quaternion, in degrees, whichever its sign.
double angle_degrees(const Quat<double>& q) { return 2 * std::acos(std::min(1.0, std::abs(q.w))) * 180 / std::numbers::pi; }

void expect_same_bits(const Pose& a, const Pose& b) {
  ASSERT_EQ(a.world.size(), b.world.size());
  for (size_t n = 0; n < a.world.size(); ++n)
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_EQ(a.world[n][c][r], b.world[n][c][r]) << "node " << n;
  EXPECT_EQ(a.weights, b.weights);
}

// sample_local_pose then world_pose is sample_pose, bit for bit, on every rig and clip (so the blended pose
// at w = 0 or 1 is exactly what a bake of the clip deforms).
TEST(PoseBlend, LocalThenWorldIsSamplePose) {
  for (const char* name : {"twisted_cylinder.gltf", "interpolation_modes.gltf", "morph_skin.gltf", "two_skins.gltf",
                           "camera_dolly.gltf", "nonuniform_scale.gltf"}) {
    SCOPED_TRACE(name);
    const Asset asset = rig(name);
    expect_same_bits(world_pose(asset, sample_local_pose(asset, nullptr, 0)), sample_pose(asset, nullptr, 0));
    for (const Clip& clip : asset.clips)
      for (double t : {0.0, 0.3, 0.5, 0.9, 1.0})
        expect_same_bits(world_pose(asset, sample_local_pose(asset, &clip, t)), sample_pose(asset, &clip, t));
  }
}

TEST(PoseBlend, TheEndsAreTheClips) {
  const Asset asset = rig("morph_skin.gltf");
  const LocalPose a = sample_local_pose(asset, &asset.clips[0], 0.2), b = sample_local_pose(asset, &asset.clips[0], 0.8);
  expect_same_bits(blend_poses(asset, a, b, 0), sample_pose(asset, &asset.clips[0], 0.2));
  expect_same_bits(blend_poses(asset, a, b, 1), sample_pose(asset, &asset.clips[0], 0.8));
}

// The twisted cylinder's child at 45° and 135° about +y: the crossfade turns it by the lerped angle, about the
// same axis, at every weight (slerp has constant speed; a matrix or DQ lerp would not).
TEST(PoseBlend, RotationIsSlerpedAtConstantSpeed) {
  const Asset asset = rig("twisted_cylinder.gltf");
  const LocalPose a = sample_local_pose(asset, &asset.clips[0], 0.25), b = sample_local_pose(asset, &asset.clips[0], 0.75);
  const size_t child = 2;
  ASSERT_EQ(asset.nodes[child].name, "child");
  for (double w : {0.25, 0.5, 0.75}) {
    const LocalTransform t = blend_local_poses(a, b, w).local[child];
    EXPECT_NEAR(angle_degrees(t.rotation), 45 + 90 * w, 1e-6) << "w = " << w;
    EXPECT_NEAR(std::abs(t.rotation.y), std::sin((45 + 90 * w) * std::numbers::pi / 360), 1e-6);
    EXPECT_NEAR(glm::length(t.rotation), 1, 1e-12);
  }
}

// Two keys on opposite signs (q and −q' with q' near q): the blend takes the short way, not the long one.
TEST(PoseBlend, RotationTakesTheShorterArc) {
  LocalPose a, b;
  a.local.resize(1), b.local.resize(1), a.weights.resize(1), b.weights.resize(1);
  a.local[0].rotation = about({0, 0, 1}, 10);
  b.local[0].rotation = -about({0, 0, 1}, 50);  // the same rotation as 50°, in the other hemisphere
  const Quat<double> mid = blend_local_poses(a, b, 0.5).local[0].rotation;
  EXPECT_NEAR(angle_degrees(mid), 30, 1e-9);
}

TEST(PoseBlend, TranslationScaleAndMorphWeightsAreLerped) {
  LocalPose a, b;
  a.local.resize(1), b.local.resize(1);
  a.local[0].translation = {1, 2, 3}, b.local[0].translation = {3, 2, -1};
  a.local[0].scale = {1, 1, 1}, b.local[0].scale = {2, 0.5, 1};
  a.weights = {{0.0, 1.0}}, b.weights = {{1.0, 0.0}};
  const LocalPose m = blend_local_poses(a, b, 0.25);
  EXPECT_EQ(m.local[0].translation, Vec3<double>(1.5, 2, 2));
  EXPECT_EQ(m.local[0].scale, Vec3<double>(1.25, 0.875, 1));
  EXPECT_EQ(m.weights[0], (std::vector<double>{0.25, 0.75}));
}

// A node given by a matrix cannot be animated; the blend leaves it alone.
TEST(PoseBlend, MatrixNodesKeepTheirMatrix) {
  LocalPose a, b;
  a.local.resize(1), b.local.resize(1), a.weights.resize(1), b.weights.resize(1);
  a.local[0].has_matrix = b.local[0].has_matrix = true;
  a.local[0].matrix = b.local[0].matrix = Mat4<double>(2.0);
  const LocalPose m = blend_local_poses(a, b, 0.5);
  EXPECT_TRUE(m.local[0].has_matrix);
  EXPECT_EQ(m.local[0].matrix, Mat4<double>(2.0));
}

}  // namespace
}  // namespace dqskin
