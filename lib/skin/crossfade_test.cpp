// The crossfade models (skin/crossfade.hpp, docs/DESIGN.md §3.10) on their own: the ends, the midpoints,
// antipodal inputs and scaled joints. Their accuracy against the reference is crossfade_accuracy_test.cpp.
#include "crossfade.hpp"

#include "dqskin/load.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

namespace dqskin {
namespace {

using DVec4 = glm::vec<4, double, glm::defaultp>;

Asset rig(const std::string& name) { return load_asset((std::filesystem::path(DQSKIN_TESTDATA_DIR) / name).string()); }

DualQuat<double> turn(const Vec3<double>& axis, double degrees, const Vec3<double>& t) {
  return from_rotation_translation(glm::angleAxis(degrees * std::numbers::pi / 180, axis), t);
}

JointTransforms palette(std::vector<DualQuat<double>> rigid, std::vector<Mat3<double>> scale = {}) {
  JointTransforms jt;
  jt.rigid = std::move(rigid);
  jt.scale = scale.empty() ? std::vector<Mat3<double>>(jt.rigid.size(), Mat3<double>(1.0)) : std::move(scale);
  for (size_t j = 0; j < jt.rigid.size(); ++j) {
    jt.matrices.push_back(to_rigid_matrix(jt.rigid[j]) * Mat4<double>(jt.scale[j]));
    jt.any_non_rigid = jt.any_non_rigid || jt.scale[j] != Mat3<double>(1.0);
  }
  return jt;
}

double max_difference(const Mat4<double>& a, const Mat4<double>& b) {
  double d = 0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) d = std::max(d, std::abs(a[c][r] - b[c][r]));
  return d;
}

TEST(VatCrossfade, LerpsPositionsAndRenormalizesDirections) {
  DeformedPrimitive a, b;
  a.positions = {{0, 0, 0}, {1, 2, 3}};
  b.positions = {{4, 0, 0}, {1, 2, 3}};
  a.normals = {{1, 0, 0}, {0, 1, 0}};
  b.normals = {{0, 1, 0}, {0, -1, 0}};  // the second pair cancels: a's direction is kept
  a.tangents = {DVec4(0, 0, 1, -1), DVec4(0, 0, 1, 1)};
  b.tangents = {DVec4(0, 1, 0, 1), DVec4(0, 0, 1, 1)};
  const DeformedPrimitive m = vat_crossfade(a, b, 0.5);
  EXPECT_EQ(m.positions[0], Vec3<double>(2, 0, 0));
  EXPECT_EQ(m.positions[1], Vec3<double>(1, 2, 3));
  EXPECT_NEAR(m.normals[0].x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(m.normals[0].y, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(m.normals[1], Vec3<double>(0, 1, 0));
  EXPECT_NEAR(glm::length(Vec3<double>(m.tangents[0])), 1, 1e-15);
  EXPECT_EQ(m.tangents[0].w, -1);  // handedness is a's
  // The ends are the frames, bit for bit.
  EXPECT_EQ(vat_crossfade(a, b, 0).positions, a.positions);
  EXPECT_EQ(vat_crossfade(a, b, 1).positions, b.positions);
  EXPECT_EQ(vat_crossfade(a, b, 0).normals, a.normals);
  EXPECT_EQ(vat_crossfade(a, b, 1).normals, b.normals);
}

TEST(VatCrossfade, RefusesFramesOfDifferentShapes) {
  DeformedPrimitive a, b;
  a.positions = {{0, 0, 0}};
  EXPECT_THROW(vat_crossfade(a, b, 0.5), std::invalid_argument);
  DeformedFrame fa, fb;
  fa.primitives.push_back(a);
  EXPECT_THROW(vat_crossfade(fa, fb, 0.5), std::invalid_argument);
}

// Two turns about the same axis line: the DQ crossfade is a turn about that line, halfway at w = 0.5 (DLB of
// two is ScLERP's screw, exact in angle at the midpoint [Kavan §4]).
TEST(DqCrossfade, BlendsEachJointAlongItsScrew) {
  const Vec3<double> pivot(0, 2, 0), axis(0, 1, 0);
  auto about_pivot = [&](double degrees) {
    const DualQuat<double> r = turn(axis, degrees, Vec3<double>(0));
    return turn({0, 0, 1}, 0, pivot) * r * turn({0, 0, 1}, 0, -pivot);
  };
  const JointTransforms a = palette({identity<double>(), about_pivot(40)});
  const JointTransforms b = palette({identity<double>(), about_pivot(100)});
  const JointTransforms m = dq_crossfade(a, b, 0.5);
  EXPECT_LT(max_difference(to_rigid_matrix(m.rigid[1]), to_rigid_matrix(about_pivot(70))), 1e-12);
  EXPECT_LT(max_difference(to_rigid_matrix(m.rigid[0]), Mat4<double>(1.0)), 1e-15);
  EXPECT_LT(max_difference(m.matrices[1], to_rigid_matrix(about_pivot(70))), 1e-12);
  EXPECT_FALSE(m.any_non_rigid);
}

// The ends reproduce A and B, and a B stored in the other hemisphere (−q, the same pose) changes nothing.
TEST(DqCrossfade, TheEndsAreThePalettesWhateverTheSigns) {
  const JointTransforms a = palette({turn({1, 0, 0}, 30, {1, 2, 3}), turn({0, 1, 0}, -170, {0, 1, 0})});
  const JointTransforms b = palette({turn({0, 0, 1}, 80, {-1, 0, 2}), turn({0, 1, 0}, 170, {0, 1, 0})});
  JointTransforms b_flipped = b;
  for (DualQuat<double>& q : b_flipped.rigid) q = -q;
  for (double w : {0.0, 1.0}) {
    const JointTransforms& expect = w == 0 ? a : b;
    const JointTransforms m = dq_crossfade(a, b_flipped, w);
    for (size_t j = 0; j < 2; ++j) EXPECT_LT(max_difference(m.matrices[j], expect.matrices[j]), 1e-14) << w << " " << j;
  }
  // Joint 1 turns from −170° to +170°: the short way is through 180°, not through 0°.
  const JointTransforms mid = dq_crossfade(a, b_flipped, 0.5);
  EXPECT_LT(max_difference(to_rigid_matrix(mid.rigid[1]), to_rigid_matrix(turn({0, 1, 0}, 180, {0, 1, 0}))), 1e-12);
  EXPECT_LT(max_difference(dq_crossfade(a, b, 0.3).matrices[0], dq_crossfade(a, b_flipped, 0.3).matrices[0]), 1e-15);
}

// Non-rigid joints: S is lerped (the two-phase rule) and the result says it is non-rigid.
TEST(DqCrossfade, LerpsTheScaleRows) {
  const Mat3<double> s2(Vec3<double>(2, 0, 0), Vec3<double>(0, 0.5, 0), Vec3<double>(0, 0, 1));
  const JointTransforms a = palette({identity<double>()});
  const JointTransforms b = palette({identity<double>()}, {s2});
  const JointTransforms m = dq_crossfade(a, b, 0.25);
  EXPECT_TRUE(m.any_non_rigid);
  EXPECT_EQ(m.scale[0], Mat3<double>(Vec3<double>(1.25, 0, 0), Vec3<double>(0, 0.875, 0), Vec3<double>(0, 0, 1)));
  EXPECT_EQ(m.matrices[0][0][0], 1.25);
  EXPECT_THROW(dq_crossfade(a, palette({identity<double>(), identity<double>()}), 0.5), std::invalid_argument);
}

// On a rig with morph targets and on one with scaled joints, the DQ crossfade at w = 0 and 1 is the
// deformation of pose A and of pose B.
TEST(DqCrossfade, FrameAtTheEndsIsTheDeformedPose) {
  for (const char* name : {"morph_skin.gltf", "nonuniform_scale.gltf", "two_skins.gltf"}) {
    SCOPED_TRACE(name);
    const Asset asset = rig(name);
    const std::vector<MeshInstance> instances = mesh_instances(asset, choose_scene(asset, -1));
    const Pose a = sample_pose(asset, &asset.clips[0], 0.2), b = sample_pose(asset, &asset.clips[0], 0.9);
    for (double w : {0.0, 1.0}) {
      const DeformedFrame expect = deform_frame(asset, instances, w == 0 ? a : b, BlendMode::kDqs);
      const DeformedFrame got = dq_crossfade_frame(asset, instances, a, b, w, BlendMode::kDqs);
      ASSERT_EQ(got.primitives.size(), expect.primitives.size());
      for (size_t p = 0; p < got.primitives.size(); ++p)
        for (size_t v = 0; v < got.primitives[p].positions.size(); ++v) {
          EXPECT_LT(glm::length(got.primitives[p].positions[v] - expect.primitives[p].positions[v]), 1e-12);
          if (!expect.primitives[p].normals.empty()) {
            EXPECT_LT(glm::length(got.primitives[p].normals[v] - expect.primitives[p].normals[v]), 1e-12);
          }
        }
    }
  }
}

// A mesh without a skin follows its node's world matrix: the DQ crossfade blends that matrix like a joint's.
TEST(DqCrossfade, RigidInstanceBlendsItsNodeMatrix) {
  Asset asset;
  asset.nodes.resize(1);
  asset.nodes[0].mesh = 0;
  asset.meshes.resize(1);
  asset.meshes[0].primitives.resize(1);
  asset.meshes[0].primitives[0].positions = {{1, 0, 0}, {0, 0, 1}};
  asset.meshes[0].primitives[0].normals = {{1, 0, 0}, {0, 0, 1}};
  const std::vector<MeshInstance> instances = {{0, 0, -1}};
  Pose a, b;
  a.world = {to_rigid_matrix(turn({0, 1, 0}, 20, {0, 0, 0}))};
  b.world = {to_rigid_matrix(turn({0, 1, 0}, 80, {0, 0, 0}))};
  a.weights = b.weights = {{}};
  const DeformedFrame got = dq_crossfade_frame(asset, instances, a, b, 0.5, BlendMode::kDqs);
  Pose mid = a;
  mid.world = {to_rigid_matrix(turn({0, 1, 0}, 50, {0, 0, 0}))};
  const DeformedFrame expect = deform_frame(asset, instances, mid, BlendMode::kDqs);
  for (size_t v = 0; v < 2; ++v) {
    EXPECT_LT(glm::length(got.primitives[0].positions[v] - expect.primitives[0].positions[v]), 1e-12);
    EXPECT_LT(glm::length(got.primitives[0].normals[v] - expect.primitives[0].normals[v]), 1e-12);
  }
}

}  // namespace
}  // namespace dqskin
