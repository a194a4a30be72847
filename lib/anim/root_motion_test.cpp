// The ground motion of a root (docs/DESIGN.md §3.11): the heading is the twist about +Y whichever way the
// root's own axes point, and M⁻¹ undoes M.
#include "dqskin/animation.hpp"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace dqskin {
namespace {

Mat4<double> turn(double radians, const Vec3<double>& axis) {
  return glm::mat4_cast(glm::angleAxis(radians, glm::normalize(axis)));
}

TEST(GroundMotion, HeadingIsTheTwistAboutUpWhateverTheRootsOwnAxes) {
  // A Z-up export's root: turned -90° about x, then tilted and swayed (the swing), then headed, then moved.
  for (double heading : {-3.0, -1.2, 0.0, 0.4, 2.5, 3.1}) {
    const Mat4<double> swing = turn(0.2, {1, 0, 0.3}) * turn(-M_PI / 2, {1, 0, 0});
    Mat4<double> world = turn(heading, {0, 1, 0}) * turn(0.15, {0, 0, 1}) * swing;
    world[3] = {1.5, 0.75, -2.25, 1};
    const GroundMotion g = ground_motion(world);
    EXPECT_NEAR(g.x, 1.5, 1e-15);
    EXPECT_NEAR(g.z, -2.25, 1e-15);
    // The twist of Ry(h) · S is h only when S has no twist about +Y; S here does (a little), so compare
    // with the twist computed from S alone: twist(Ry(h) S) = h + twist(S).
    const double swing_twist = ground_motion(turn(0.15, {0, 0, 1}) * swing).yaw;
    EXPECT_NEAR(std::remainder(g.yaw - heading - swing_twist, 2 * M_PI), 0, 1e-12) << heading;
    EXPECT_LE(std::abs(g.yaw), M_PI);
  }
}

TEST(GroundMotion, PureHeadingAndItsInverse) {
  const GroundMotion g{0.5, -4, 1.25};
  const Mat4<double> m = ground_matrix(g);
  const GroundMotion back = ground_motion(m);
  EXPECT_NEAR(back.x, 0.5, 1e-15);
  EXPECT_NEAR(back.z, -4, 1e-15);
  EXPECT_NEAR(back.yaw, 1.25, 1e-14);
  const Mat4<double> identity = m * ground_matrix_inverse(g);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(identity[c][r], c == r ? 1 : 0, 1e-15);
  // Ry(yaw) turns +z towards +x, as glm's rotation about +Y does.
  const Mat4<double> glm_turn = turn(1.25, {0, 1, 0});
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(m[c][r], glm_turn[c][r], 1e-15);
}

TEST(GroundMotion, InPlaceClipPutsTheRootOnTheOrigin) {
  // A one-node asset whose node walks and turns: in place, it stays at the origin with no heading.
  Asset asset;
  asset.nodes.resize(1);
  Clip clip;
  Channel walk;
  walk.node = 0;
  walk.path = TargetPath::kTranslation;
  walk.interpolation = Interpolation::kLinear;
  walk.components = 3;
  walk.times = {0, 1};
  walk.values = {0, 0, 0, 3, 1, 2};
  Channel head = walk;
  head.path = TargetPath::kRotation;
  head.components = 4;
  head.values = {0, 0, 0, 1, 0, float(std::sin(0.5)), 0, float(std::cos(0.5))};
  clip.channels = {walk, head};
  clip.last_key = 1;
  clip.in_place_root = 0;
  const Pose pose = sample_pose(asset, &clip, 1.0);
  ASSERT_TRUE(pose.removed.has_value());
  EXPECT_NEAR(pose.removed->x, 3, 1e-6);
  EXPECT_NEAR(pose.removed->z, 2, 1e-6);
  EXPECT_NEAR(pose.removed->yaw, 1.0, 1e-6);
  const GroundMotion left = ground_motion(pose.world[0]);
  EXPECT_NEAR(left.x, 0, 1e-15);
  EXPECT_NEAR(left.z, 0, 1e-15);
  EXPECT_NEAR(left.yaw, 0, 1e-15);
  EXPECT_NEAR(pose.world[0][3].y, 1, 1e-6);  // the height stays
  clip.in_place_root = -1;
  EXPECT_FALSE(sample_pose(asset, &clip, 1.0).removed.has_value());
}

}  // namespace
}  // namespace dqskin
